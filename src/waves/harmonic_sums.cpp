// The harmonic sums of the wave kinematics (include/towsim/waves/harmonic_sums.hpp).
// Compiled with -ffp-contract=off (CMakeLists.txt), as vector_math.cpp.
#include "towsim/waves/harmonic_sums.hpp"

#include <algorithm>
#include <array>

#include "towsim/waves/vector_math.hpp"

// One variant per instruction set, chosen at start-up (GNU ifunc).
#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define TOWSIM_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define TOWSIM_VECTOR_CLONES
#endif

namespace towsim {

namespace {

constexpr std::size_t kChunk = 64;  // harmonics per pass [-]: a multiple of the lanes, 11 arrays of 512 bytes
static_assert(kChunk % vecmath::kLanes == 0);
using vecmath::accumulate, vecmath::Lanes, vecmath::total;

}  // namespace

TOWSIM_VECTOR_CLONES HarmonicSums harmonic_sums(const WaveComponent* comps, std::size_t n, double x, double y, double s,
                                                double zc, double t, bool deep, bool spread) {
  // Phases [rad], their sin and cos, k z and e^{kz} [-], the terms a w C cos, a w^2 C sin,
  // a w S sin, a w^2 S cos, and (short-crested) the directions.
  std::array<double, kChunk> th, sn, cs, kz, ez, uc, as, ws, ac, dx, dy;
  Lanes U{}, W{}, AH{}, AZ{}, Ux{}, Uy{}, Ax{}, Ay{};
  for (std::size_t b = 0; b < n; b += kChunk) {
    const std::size_t m = std::min(kChunk, n - b);
    const WaveComponent* c = comps + b;
    // Phases and depth exponents, then their sin, cos and exp in vectorised passes.
    for (std::size_t j = 0; j < m; ++j) {
      const double si = spread ? c[j].dx * x + c[j].dy * y : s;  // distance along its direction
      th[j] = c[j].omega * t - c[j].k * si - c[j].phase;
      kz[j] = c[j].k * zc;
    }
    vecmath::sincos_n(m, th.data(), sn.data(), cs.data());
    vecmath::exp_n(m, kz.data(), ez.data());
    // Depth factors as exponentials: (e^{kz} +- e^{-2kh} / e^{kz}) / (1 - e^{-2kh}); here kz <- C, ez <- S.
    if (!deep)
      for (std::size_t j = 0; j < m; ++j) {
        const double e = c[j].e2kh / ez[j], den = 1 - c[j].e2kh;
        kz[j] = (ez[j] + e) / den;
        ez[j] = (ez[j] - e) / den;
      }
    else
      for (std::size_t j = 0; j < m; ++j) kz[j] = ez[j];
    // The terms, then their partial sums.
    for (std::size_t j = 0; j < m; ++j) {
      const double aw = c[j].amplitude * c[j].omega, aw2 = aw * c[j].omega;
      uc[j] = aw * kz[j] * cs[j], as[j] = aw2 * kz[j] * sn[j];
      ws[j] = aw * ez[j] * sn[j], ac[j] = aw2 * ez[j] * cs[j];
    }
    if (spread) {
      for (std::size_t j = 0; j < m; ++j) dx[j] = c[j].dx, dy[j] = c[j].dy;
      // The horizontal terms along each harmonic's direction (uc, as reused for x, th, kz for y).
      for (std::size_t j = 0; j < m; ++j) th[j] = uc[j] * dy[j], kz[j] = as[j] * dy[j];
      for (std::size_t j = 0; j < m; ++j) uc[j] *= dx[j], as[j] *= dx[j];
      accumulate(Ux, uc.data(), m), accumulate(Uy, th.data(), m);
      accumulate(Ax, as.data(), m), accumulate(Ay, kz.data(), m);
    } else {
      accumulate(U, uc.data(), m), accumulate(AH, as.data(), m);
    }
    accumulate(W, ws.data(), m), accumulate(AZ, ac.data(), m);
  }
  HarmonicSums r;
  r.U = total(U), r.W = total(W), r.AH = total(AH), r.AZ = total(AZ);
  r.Ux = total(Ux), r.Uy = total(Uy), r.Ax = total(Ax), r.Ay = total(Ay);
  return r;
}

}  // namespace towsim
