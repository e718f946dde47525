// The vectorised sin, cos and exp of the wave sums (towsim/waves/vector_math.hpp)
// against the C library's, over the ranges the sums use.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "towsim/waves/vector_math.hpp"

namespace {

double uniform(std::mt19937_64& g, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(g() >> 11) * 0x1.0p-53;
}

// sin and cos within 4.5e-16 absolute (2 ulp of 1: the C library's own error
// is below 1 ulp, the polynomials' about 1 ulp) for phases up to 1e6 rad (a
// 3-hour record at 3 rad/s reaches 3.2e4 rad); beyond, and for NaN, the C
// library's values exactly.
TEST(VectorMath, SinCosWithinTwoUlpOfTheCLibrary) {
  std::mt19937_64 g(11);
  double worst = 0;
  for (double range : {1.0, 10.0, 1e3, 3.3e4, 1e6}) {
    std::vector<double> x(1000), s(x.size()), c(x.size());
    for (auto& v : x) v = uniform(g, -range, range);
    towsim::vecmath::sincos_n(x.size(), x.data(), s.data(), c.data());
    for (std::size_t i = 0; i < x.size(); ++i)
      worst = std::max(worst, std::max(std::abs(s[i] - std::sin(x[i])), std::abs(c[i] - std::cos(x[i]))));
  }
  std::printf("[measured] max |sincos_n - libm| %.3e (tol 4.5e-16)\n", worst);
  EXPECT_LE(worst, 4.5e-16);
  const std::vector<double> far = {3e6, -1e12, std::numeric_limits<double>::quiet_NaN()};
  std::vector<double> s(far.size()), c(far.size());
  towsim::vecmath::sincos_n(far.size(), far.data(), s.data(), c.data());
  EXPECT_EQ(s[0], std::sin(far[0]));
  EXPECT_EQ(c[1], std::cos(far[1]));
  EXPECT_TRUE(std::isnan(s[2]) && std::isnan(c[2]));
}

// exp within 4 ulp relative (4.5e-16 * 2) on the depth exponents k z the
// sums use ([-745, 0]: clamped at -708, where the value is below 1e-307),
// and above, to 709; NaN stays NaN.
TEST(VectorMath, ExpWithinFourUlpOfTheCLibrary) {
  std::mt19937_64 g(12);
  double worst = 0;
  for (auto [lo, hi] : {std::pair{-1.0, 1.0}, std::pair{-30.0, 0.0}, std::pair{-708.0, 709.0}}) {
    std::vector<double> x(1000), e(x.size());
    for (auto& v : x) v = uniform(g, lo, hi);
    towsim::vecmath::exp_n(x.size(), x.data(), e.data());
    for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(e[i] / std::exp(x[i]) - 1));
  }
  std::printf("[measured] max relative |exp_n / libm - 1| %.3e (tol 9e-16)\n", worst);
  EXPECT_LE(worst, 9e-16);
  const std::vector<double> x = {0.0, -800.0, std::numeric_limits<double>::quiet_NaN()};
  std::vector<double> e(x.size());
  towsim::vecmath::exp_n(x.size(), x.data(), e.data());
  EXPECT_EQ(e[0], 1.0);
  EXPECT_LE(e[1], 1e-307);
  EXPECT_TRUE(std::isnan(e[2]));
}

}  // namespace
