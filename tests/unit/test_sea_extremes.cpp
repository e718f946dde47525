// Extreme-value statistics of summary.json's "statistics" (towsim::output::signal_stats,
// weibull_fit) against analytic cases: a Gaussian record's moments, a
// Weibull fit to Rayleigh values and to their upper tail, the Rayleigh and Weibull most probable
// maxima of a narrow-band Gaussian process, and the flag of a record whose
// maximum exceeds its Rayleigh mpm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "towsim/output/sea_statistics.hpp"

namespace {

constexpr double kPi = std::numbers::pi;

/// Uniform in (0, 1] from 53 bits of the generator (the same on every platform).
double unit(std::mt19937_64& g) { return (static_cast<double>(g() >> 11) + 1) * 0x1.0p-53; }

/// A standard normal value (Box-Muller from two uniform ones).
double normal(std::mt19937_64& g) { return std::sqrt(-2 * std::log(unit(g))) * std::cos(2 * kPi * unit(g)); }

// Independent N(4, 2^2) samples, n = 200000: skewness 0 and kurtosis 3 up to
// their sampling errors sqrt(6 / n) = 0.0055 and sqrt(24 / n) = 0.011;
// tolerances 5 of those (0.03, 0.06).
TEST(SeaExtremes, GaussianRecordHasSkewness0Kurtosis3) {
  std::mt19937_64 g(5);
  std::vector<double> t, x;
  for (int i = 0; i < 200000; ++i) t.push_back(0.1 * i), x.push_back(4 + 2 * normal(g));
  const auto s = towsim::output::signal_stats(t, x);
  std::printf("[measured] Gaussian record: skewness %.4f (0), kurtosis %.4f (3)\n", s.skewness, s.kurtosis);
  EXPECT_NEAR(s.skewness, 0, 0.03);
  EXPECT_NEAR(s.kurtosis, 3, 0.06);
  // A uniform record: skewness 0, kurtosis 9/5 (exact moments of the law; same sampling tolerances).
  for (auto& v : x) v = unit(g);
  const auto u = towsim::output::signal_stats(t, x);
  EXPECT_NEAR(u.skewness, 0, 0.03);
  EXPECT_NEAR(u.kurtosis, 1.8, 0.06);
}

// Rayleigh values y = sigma sqrt(-2 ln U) are Weibull with shape 2 and scale
// sqrt(2) sigma. The maximum-likelihood shape's standard error is
// 0.78 * 2 / sqrt(n) = 0.011 at n = 20000, the scale's ~0.5 %: tolerances
// 0.06 and 2.5 % (5 standard errors). An exponential sample (shape 1, scale
// its mean) likewise.
TEST(SeaExtremes, WeibullFitOfRayleighValuesHasShape2) {
  std::mt19937_64 g(6);
  const double sigma = 3.0;
  std::vector<double> y(20000), e(20000);
  for (auto& v : y) v = sigma * std::sqrt(-2 * std::log(unit(g)));
  for (auto& v : e) v = -5.0 * std::log(unit(g));
  const auto [shape, scale] = towsim::output::weibull_fit(y);
  const auto [shape_e, scale_e] = towsim::output::weibull_fit(e);
  std::printf("[measured] Rayleigh: shape %.4f (2), scale %.4f (%.4f); exponential: shape %.4f (1), scale %.4f (5)\n",
              shape, scale, std::sqrt(2.0) * sigma, shape_e, scale_e);
  EXPECT_NEAR(shape, 2, 0.06);
  EXPECT_NEAR(scale, std::sqrt(2.0) * sigma, 0.025 * std::sqrt(2.0) * sigma);
  EXPECT_NEAR(shape_e, 1, 0.03);
  EXPECT_NEAR(scale_e, 5, 0.025 * 5);
  // Too few or equal values: no fit.
  EXPECT_TRUE(std::isnan(towsim::output::weibull_fit({1.0}).first));
  EXPECT_TRUE(std::isnan(towsim::output::weibull_fit({2.0, 2.0, 2.0}).first));
}

// The fit to the upper tail: Rayleigh values y = sigma sqrt(-2 ln U) above
// their 2/3 quantile u, given y > u, are Weibull(2, sqrt(2) sigma) conditioned
// on y > u, so the conditional fit recovers shape 2 and scale sqrt(2) sigma.
// Its standard errors are larger than the plain fit's: over 40 seeds of
// 60000 values (20000 above u) they were 0.036 (shape) and 1.4 % (scale):
// tolerances 0.15 and 6 % (about 4 of them). A mixture whose bulk is not
// Rayleigh (60 % of the values uniform on [0, 0.9], below u, 40 % Rayleigh
// with sigma 3): fitted to every value the shape is far from 2 (0.83), fitted
// to the top third it is the Rayleigh tail's (2.02 measured; same tolerances).
TEST(SeaExtremes, TailFitOfRayleighPeaksHasShape2) {
  std::mt19937_64 g(8);
  const double sigma = 3.0, scale = std::sqrt(2.0) * sigma;
  const std::size_t n = 60000;
  std::vector<double> y(n), mix(n);
  for (auto& v : y) v = sigma * std::sqrt(-2 * std::log(unit(g)));
  for (auto& v : mix) v = unit(g) < 0.6 ? 0.9 * unit(g) : sigma * std::sqrt(-2 * std::log(unit(g)));
  auto threshold = [&](std::vector<double> v) {  // the largest value not in the top third
    std::sort(v.begin(), v.end());
    return v[n - static_cast<std::size_t>(static_cast<double>(n) * towsim::output::kWeibullTail) - 1];
  };
  const auto [shape, sc] = towsim::output::weibull_fit(y, threshold(y));
  const auto [shape_all, sc_all] = towsim::output::weibull_fit(mix);
  const auto [shape_mix, sc_mix] = towsim::output::weibull_fit(mix, threshold(mix));
  std::printf(
      "[measured] tail fit, Rayleigh: shape %.4f (2), scale %.4f (%.4f); mixture: every value %.4f, top third "
      "%.4f, scale %.4f\n",
      shape, sc, scale, shape_all, shape_mix, sc_mix);
  EXPECT_NEAR(shape, 2, 0.15);
  EXPECT_NEAR(sc, scale, 0.06 * scale);
  EXPECT_LT(shape_all, 1.2) << "the bulk pulls the plain fit away from 2";
  EXPECT_NEAR(shape_mix, 2, 0.15);
  EXPECT_NEAR(sc_mix, scale, 0.06 * scale);
  // Above a threshold no value exceeds: no fit.
  EXPECT_TRUE(std::isnan(towsim::output::weibull_fit(y, 1e9).first));
}

// A narrow-band Gaussian process (200 random-phase harmonics of equal
// amplitude on [0.8, 1.2] rad/s, 20000 s at 0.2 s: ~3200 cycles, correlated
// over ~2.5 cycles, so ~1300 independent peaks): its cycle maxima are close
// to Rayleigh, so the Weibull fit to the top third has shape ~2 (about 430
// independent peaks above u; the tail fit's shape error at 1000 independent
// tail values was 0.145 over 40 seeds, so ~0.22 here; measured 2.27;
// tolerance 0.5) and its 3-hour mpm, extrapolated from u (~1.5 std above the
// mean) to ~3.9 std, equals the Rayleigh one to a few % (the fitted shape and
// scale err together, so the mpm varies less than either; measured 1.6 %:
// tolerance 8 %, as for the fit to every peak).
TEST(SeaExtremes, NarrowBandProcessWeibullMpmIsTheRayleighOne) {
  std::mt19937_64 g(7);
  const int n = 200;
  std::vector<double> w(n), ph(n);
  for (int i = 0; i < n; ++i) w[i] = 0.8 + 0.4 * (i + 0.5) / n, ph[i] = 2 * kPi * unit(g);
  std::vector<double> t, x;
  for (int k = 0; k < 100000; ++k) {
    const double tk = 0.2 * k;
    double v = 0;
    for (int i = 0; i < n; ++i) v += std::cos(w[i] * tk + ph[i]);
    t.push_back(tk), x.push_back(10 + v * std::sqrt(2.0 / n));  // std 1
  }
  const auto s = towsim::output::signal_stats(t, x);
  std::printf("[measured] narrow band: %ld peaks, shape %.4f, mpm %.4f, weibull_mpm %.4f\n", s.peaks, s.weibull_shape,
              s.mpm, s.weibull_mpm);
  EXPECT_GT(s.peaks, 3000);
  EXPECT_NEAR(s.weibull_shape, 2, 0.5);
  EXPECT_NEAR(s.weibull_mpm - s.mean, s.mpm - s.mean, 0.08 * (s.mpm - s.mean));
}

// The flag: the same narrow-band record with one sample raised above its
// Rayleigh mpm is flagged, and SeaStatistics says so in a warning; fewer than
// kMinPeaks cycles give no Weibull estimate (NaN).
TEST(SeaExtremes, MaximumAboveTheRayleighMpmIsFlagged) {
  std::vector<double> t, x;
  for (int k = 0; k < 20000; ++k)
    t.push_back(0.05 * k), x.push_back(std::sin(0.7 * t.back()) + 0.3 * std::sin(2.3 * t.back()));
  auto s = towsim::output::signal_stats(t, x);
  EXPECT_FALSE(s.max_above_mpm);
  x[12345] = s.mpm + 0.5;
  s = towsim::output::signal_stats(t, x);
  EXPECT_TRUE(s.max_above_mpm);
  EXPECT_GE(s.peaks, towsim::output::kMinPeaks);
  t.resize(1000), x.resize(1000);  // 50 s: 5 cycles
  s = towsim::output::signal_stats(t, x);
  EXPECT_LT(s.peaks, towsim::output::kMinPeaks);
  EXPECT_TRUE(std::isnan(s.weibull_mpm));
}

}  // namespace
