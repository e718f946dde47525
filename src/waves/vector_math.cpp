// Vectorised sin, cos and exp (include/towsim/waves/vector_math.hpp). This
// file is compiled with -ffp-contract=off (CMakeLists.txt): the AVX-512
// variant must not fuse multiply-adds, so that every variant rounds alike.
#include "towsim/waves/vector_math.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

// One variant per instruction set, chosen at start-up (GNU ifunc).
#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define TOWSIM_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define TOWSIM_VECTOR_CLONES
#endif

namespace towsim::vecmath {

TOWSIM_VECTOR_CLONES void sincos_n(std::size_t n, const double* __restrict x, double* __restrict s,
                                   double* __restrict c) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kMagic = 0x1.8p52;  // adding it rounds to an integer, held in the low bits
  // pi/2 = P1 + P2 + P3 (Cody-Waite, fdlibm's pio2_1, pio2_2, pio2_2t: P1 and P2 have 33
  // significant bits, so q P1 and q P2 are exact for |q| < 2^20).
  constexpr double kP1 = 1.57079632673412561417e+00, kP2 = 6.07710050630396597660e-11, kP3 = 2.02226624879595063154e-21;
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[i];
    const double qm = xi * kTwoOverPi + kMagic;
    const double q = qm - kMagic;  // nearest integer to x / (pi/2)
    const std::uint64_t qi = std::bit_cast<std::uint64_t>(qm);
    const double r = ((xi - q * kP1) - q * kP2) - q * kP3;  // |r| <= pi/4
    const double r2 = r * r;
    // fdlibm's kernels __kernel_sin and __kernel_cos (minimax on [-pi/4, pi/4]).
    const double sr = r +
                      r * r2 *
                          (-1.66666666666666324348e-01 +
                           r2 * (8.33333333332248946124e-03 +
                                 r2 * (-1.98412698298579493134e-04 +
                                       r2 * (2.75573137070700676789e-06 +
                                             r2 * (-2.50507602534068634195e-08 + r2 * 1.58969099521155010221e-10)))));
    const double cr = 1.0 - 0.5 * r2 +
                      r2 * r2 *
                          (4.16666666666666019037e-02 +
                           r2 * (-1.38888888888741095749e-03 +
                                 r2 * (2.48015872894767294178e-05 +
                                       r2 * (-2.75573143513906633035e-07 +
                                             r2 * (2.08757232129817482790e-09 + r2 * -1.13596475577881948265e-11)))));
    // Quadrant q mod 4: odd swaps sin and cos; bit 1 flips sin's sign, bit 1 of q + 1 cos's.
    const std::uint64_t swap = std::uint64_t{0} - (qi & 1);
    const std::uint64_t sb = std::bit_cast<std::uint64_t>(sr), cb = std::bit_cast<std::uint64_t>(cr);
    const std::uint64_t so = ((cb & swap) | (sb & ~swap)) ^ ((qi & 2) << 62);
    const std::uint64_t co = ((sb & swap) | (cb & ~swap)) ^ (((qi + 1) & 2) << 62);
    s[i] = std::bit_cast<double>(so);
    c[i] = std::bit_cast<double>(co);
  }
  for (std::size_t i = 0; i < n; ++i)  // rare: huge phases, or NaN
    if (!(std::abs(x[i]) <= kSinCosRange)) s[i] = std::sin(x[i]), c[i] = std::cos(x[i]);
}

TOWSIM_VECTOR_CLONES void exp_n(std::size_t n, const double* __restrict x, double* __restrict e) {
  constexpr double kInvLn2 = 1.44269504088896338700e+00;
  constexpr double kMagic = 0x1.8p52;
  // ln 2 = L1 + L2 (fdlibm: L1 has trailing zeros, so m L1 is exact).
  constexpr double kL1 = 6.93147180369123816490e-01, kL2 = 1.90821492927058770002e-10;
  const std::int64_t magic_bits = std::bit_cast<std::int64_t>(kMagic);
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[i];
    const double mm = xi * kInvLn2 + kMagic;
    const double m = mm - kMagic;               // nearest integer to x / ln 2
    const double r = (xi - m * kL1) - m * kL2;  // |r| <= ln 2 / 2
    // Taylor series to r^13 / 13!: the next term is below 4e-18 for |r| <= 0.347.
    double p = 1.0 / 6227020800.0;
    p = p * r + 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r * r + r;  // exp(r) - 1
    const std::int64_t mi = std::bit_cast<std::int64_t>(mm) - magic_bits;
    const double scale = std::bit_cast<double>(static_cast<std::uint64_t>(mi + 1023) << 52);  // 2^m
    e[i] = scale + scale * p;
  }
  for (std::size_t i = 0; i < n; ++i)  // rare: outside [-708, 709] (2^m not a normal number), or NaN
    if (!(x[i] >= -708.0 && x[i] <= 709.0)) e[i] = std::exp(x[i]);
}

}  // namespace towsim::vecmath
