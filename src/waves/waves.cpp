// Linear waves: dispersion, spectrum synthesis and Airy kinematics
// (docs/theory.md "Waves").
#include "towsim/waves/waves.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "towsim/waves/harmonic_sums.hpp"
#include "towsim/waves/vector_math.hpp"

namespace towsim {

namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kTwoPi = 2 * std::numbers::pi;

/// JONSWAP peak factor's exponent r at x = (omega_p / omega)^4.
double peak_exponent(double x) {
  if (x <= 0) return 0;
  const double s = x >= 1 ? 0.07 : 0.09;    // sigma: 0.07 below the peak frequency, 0.09 above
  const double d = std::pow(x, -0.25) - 1;  // omega / omega_p - 1
  return std::exp(-d * d / (2 * s * s));
}

/// In x = (omega_p / omega)^4, S d(omega) = C / (4 omega_p^4) f(x) dx with
/// f(x) = exp(-5/4 x) gamma^r(x): smooth, and the PM part integrates to 4/5.
double shape_in_x(double x, double gamma) { return std::exp(-1.25 * x) * std::pow(gamma, peak_exponent(x)); }

constexpr double kXMax = 40.0;      // exp(-1.25 * 40) = 2e-22 of the integrand: the rest is negligible
constexpr int kXIntervals = 80000;  // trapezoid in x, step 5e-4: resolves the peak (width ~ 4 sigma ~ 0.3 in x)

/// Cumulative integral E(x_j) = int_0^{x_j} f(x) dx on the uniform grid (trapezoid).
std::vector<double> cumulative_shape(double gamma) {
  std::vector<double> E(kXIntervals + 1, 0.0);
  const double h = kXMax / kXIntervals;
  double prev = shape_in_x(0.0, gamma);
  for (int j = 1; j <= kXIntervals; ++j) {
    const double cur = shape_in_x(j * h, gamma);
    E[j] = E[j - 1] + 0.5 * h * (prev + cur);
    prev = cur;
  }
  return E;
}

/// Height below which a component's kinematics are below kWaveCutoff of their surface value.
double cut_height(double k, double depth) {
  const double kh = k * depth;
  if (!std::isfinite(depth) || kh > 20) return std::log(kWaveCutoff) / k;  // cosh ratio = e^{kz} to 1e-17
  const double c = kWaveCutoff * std::cosh(kh);
  if (c < 1) return -std::numeric_limits<double>::infinity();  // never that small above the seabed
  return std::acosh(c) / k - depth;
}

/// Sort components deepest cut first and fill their wavenumbers and cuts.
void finish(WaveField& w) {
  for (auto& c : w.components) {
    c.k = wave_number(c.omega, w.depth, w.g);
    c.z_cut = cut_height(c.k, w.depth);
    c.e2kh = std::isfinite(w.depth) ? std::exp(-2 * c.k * w.depth) : 0.0;
  }
  for (auto& c : w.components) c.dx = w.direction.x(), c.dy = w.direction.y();
  std::stable_sort(w.components.begin(), w.components.end(),
                   [](const WaveComponent& a, const WaveComponent& b) { return a.z_cut < b.z_cut; });
}

/// Work arrays of one vectorised pass of the elevation over up to kChunk harmonics.
constexpr std::size_t kChunk = 64;  // [-]: 3 arrays of 512 bytes on the stack
struct Chunk {
  std::array<double, kChunk> th, sn, cs;  // phase [rad], its sin and cos [-]
};

}  // namespace

double wave_number(double omega, double depth, double g) {
  const double k_deep = omega * omega / g;
  if (!std::isfinite(depth)) return k_deep;
  // Newton on f(k) = g k tanh(kh) - omega^2 from the guess omega^2 / (g sqrt(tanh(k_deep h))),
  // exact in both the deep and the shallow limits.
  double k = k_deep / std::sqrt(std::tanh(k_deep * depth));
  for (int it = 0; it < 100; ++it) {
    const double th = std::tanh(k * depth);
    const double f = g * k * th - omega * omega;
    const double df = g * th + g * k * depth * (1 - th * th);
    const double dk = f / df;
    k -= dk;
    if (std::abs(dk) <= 1e-15 * k) break;
  }
  return k;
}

double spectral_density(double hs, double tp, double gamma, double omega) {
  if (omega <= 0) return 0;
  const double wp = kTwoPi / tp;
  const double x = std::pow(wp / omega, 4);
  // The normalising integral, kept for the last gamma asked (one per thread).
  thread_local double last_gamma = std::numeric_limits<double>::quiet_NaN(), J = 0;
  if (gamma != last_gamma) J = cumulative_shape(gamma).back(), last_gamma = gamma;
  // S = C omega^-5 exp(-5/4 x) gamma^r with C = (hs^2/16) 4 omega_p^4 / J.
  const double C = hs * hs / 16 * 4 * std::pow(wp, 4) / J;
  return C * std::pow(omega, -5) * shape_in_x(x, gamma);
}

WaveField make_regular_wave(double height, double period, const Vec3& direction, double depth, double g) {
  WaveField w;
  w.g = g;
  w.depth = depth;
  w.direction = direction.normalized();
  w.components.push_back(WaveComponent{0.5 * height, kTwoPi / period, 0, 0, 0});
  finish(w);
  return w;
}

WaveField make_irregular_sea(double hs, double tp, double gamma, int n, std::uint64_t seed, const Vec3& direction,
                             double depth, double g) {
  WaveField w;
  w.g = g;
  w.depth = depth;
  w.direction = direction.normalized();
  const double wp = kTwoPi / tp;
  const std::vector<double> E = cumulative_shape(gamma);
  const double h = kXMax / kXIntervals;
  const double amplitude = std::sqrt(2 * hs * hs / 16 / n);  // a^2 / 2 = m0 / n
  std::mt19937_64 gen(seed);
  // Component j (increasing frequency) sits at the median of the j-th
  // equal-energy bin counted from the low-frequency end, i.e. where the energy
  // above its frequency is (n - j - 1/2) / n, which is E(x) / E(inf) in x.
  for (int j = 0; j < n; ++j) {
    const double target = (n - j - 0.5) / n * E.back();
    const auto it = std::lower_bound(E.begin(), E.end(), target);
    const std::size_t i1 = std::clamp<std::size_t>(static_cast<std::size_t>(it - E.begin()), 1, E.size() - 1);
    const double x = h * (static_cast<double>(i1 - 1) + (target - E[i1 - 1]) / (E[i1] - E[i1 - 1]));
    const double omega = wp * std::pow(x, -0.25);
    const double u = static_cast<double>(gen() >> 11) * 0x1.0p-53;  // exactly 53 random bits in [0, 1)
    w.components.push_back(WaveComponent{amplitude, omega, 0, kTwoPi * u, 0});
  }
  finish(w);
  return w;
}

void WaveField::ramp(double t, double& r, double& rd, double& rdd) const {
  r = 1, rd = 0, rdd = 0;
  if (!(ramp_time > 0) || t >= ramp_time) return;
  if (t <= 0) {
    r = 0;
    return;
  }
  const double s = t / ramp_time, T = ramp_time;
  r = s * s * s * (10 - 15 * s + 6 * s * s);
  rd = 30 * s * s * (1 - s) * (1 - s) / T;
  rdd = 60 * s * (1 - s) * (1 - 2 * s) / (T * T);
}

double WaveField::elevation(const Vec3& x, double t) const {
  const double s = direction.x() * x.x() + direction.y() * x.y();
  double eta = 0;
  Chunk ch;
  for (std::size_t b = 0; b < components.size(); b += kChunk) {
    const std::size_t m = std::min(kChunk, components.size() - b);
    const WaveComponent* c = &components[b];
    for (std::size_t j = 0; j < m; ++j) {
      const double si = spread ? c[j].dx * x.x() + c[j].dy * x.y() : s;  // distance along its direction
      ch.th[j] = c[j].omega * t - c[j].k * si - c[j].phase;
    }
    vecmath::sincos_n(m, ch.th.data(), ch.sn.data(), ch.cs.data());
    for (std::size_t j = 0; j < m; ++j) eta += c[j].amplitude * ch.cs[j];
  }
  double r, rd, rdd;
  ramp(t, r, rd, rdd);
  return r * eta;
}

double WaveField::stretched(double z, double eta) const {
  if (!wheeler) return z;
  return std::isfinite(depth) ? (z - eta) * depth / (depth + eta) : z - eta;
}

void WaveField::kinematics(const Vec3& x, double t, Vec3* u, Vec3* a) const {
  if (u) u->setZero();
  if (a) a->setZero();
  const double eta = wheeler ? elevation(x, t) : 0.0;  // kinematics up to eta (Wheeler) or z = 0
  if (x.z() > eta) return;
  const double z = stretched(x.z(), eta);
  const double s = direction.x() * x.x() + direction.y() * x.y();
  const bool deep = !std::isfinite(depth);
  const double zc = deep ? z : std::max(z, -depth);  // at or above the seabed
  // The harmonics not cut off at z: a prefix (sorted by z_cut; a NaN z keeps them all).
  const auto n = static_cast<std::size_t>(std::partition_point(components.begin(), components.end(),
                                                               [z](const WaveComponent& c) { return !(c.z_cut > z); }) -
                                          components.begin());
  // Sums over the harmonics (harmonic_sums.hpp): U, W, AH, AZ (short-crested: U and AH as vectors).
  const HarmonicSums hs = harmonic_sums(components.data(), n, x.x(), x.y(), s, zc, t, deep, spread);
  Eigen::Vector2d Uv(hs.Ux, hs.Uy), Av(hs.Ax, hs.Ay);
  double r, rd, rdd;
  ramp(t, r, rd, rdd);
  if (!spread)
    Uv = hs.U * Eigen::Vector2d(direction.x(), direction.y()),
    Av = hs.AH * Eigen::Vector2d(direction.x(), direction.y());
  // u = r (U d, -W); du/dt with the build-up's rate: d(r u)/dt = r' u + r du/dt.
  if (u) *u = r * Vec3(Uv.x(), Uv.y(), -hs.W);
  if (a) {
    const Eigen::Vector2d h = -r * Av + rd * Uv;
    *a = Vec3(h.x(), h.y(), -r * hs.AZ - rd * hs.W);
  }
}

Vec3 WaveField::velocity(const Vec3& x, double t) const {
  Vec3 u;
  kinematics(x, t, &u, nullptr);
  return u;
}

Vec3 WaveField::acceleration(const Vec3& x, double t) const {
  Vec3 a;
  kinematics(x, t, nullptr, &a);
  return a;
}

void spread_directions(WaveField& w, double s, std::uint64_t seed) {
  // CDF of D(theta) ~ cos^(2s)(theta / 2) on [-pi, pi], trapezoid on a fine grid.
  constexpr int kN = 20000;  // intervals: the CDF to ~1e-8 for s up to ~100
  std::vector<double> cdf(kN + 1, 0.0);
  const double h = kTwoPi / kN;
  auto D = [s](double th) { return std::pow(std::cos(0.5 * th), 2 * s); };
  for (int i = 1; i <= kN; ++i)
    cdf[static_cast<std::size_t>(i)] = cdf[static_cast<std::size_t>(i - 1)] +
                                       0.5 * h * (D(-std::numbers::pi + (i - 1) * h) + D(-std::numbers::pi + i * h));
  std::mt19937_64 gen(seed ^ 0x5eed5eed5eed5eedULL);
  // One draw per component in its order of construction (increasing frequency), then finish's sort.
  std::vector<std::size_t> order(w.components.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&w](std::size_t a, std::size_t b) { return w.components[a].omega < w.components[b].omega; });
  for (std::size_t i : order) {
    const double u = static_cast<double>(gen() >> 11) * 0x1.0p-53 * cdf.back();
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    const std::size_t j = std::clamp<std::size_t>(static_cast<std::size_t>(it - cdf.begin()), 1, kN);
    const double f = (u - cdf[j - 1]) / (cdf[j] - cdf[j - 1]);
    const double theta = -std::numbers::pi + (static_cast<double>(j - 1) + f) * h;
    auto& c = w.components[i];
    c.dx = std::cos(theta) * w.direction.x() - std::sin(theta) * w.direction.y();
    c.dy = std::sin(theta) * w.direction.x() + std::cos(theta) * w.direction.y();
  }
  w.spread = true;
}

double WaveField::variance() const {
  double v = 0;
  for (const auto& c : components) v += 0.5 * c.amplitude * c.amplitude;
  return v;
}

}  // namespace towsim
