// sin, cos and exp over arrays, written so that the compiler vectorises the
// loops (no calls, no branches, no tables): the wave sums evaluate them for
// every harmonic at every point (docs/theory.md 8 "Evaluation"). On x86-64
// Linux they are compiled for AVX-512, AVX2 and the baseline, chosen when the
// program starts; without contraction into fused multiply-adds every variant
// gives the same bits (IEEE operations element by element).
//
// Accuracy, measured against the C library in tests/unit/test_vector_math.cpp:
// sin and cos within 4.5e-16 absolute for |x| <= kSinCosRange, exp within
// 4 ulp (relative 9e-16) on [-708, 709], the C library's value outside.
#pragma once

#include <array>
#include <cstddef>

namespace towsim::vecmath {

/// Largest |x| [rad] for which the three-part reduction by pi/2 is exact to
/// round-off (the quadrant count times the 33-bit first part stays exact);
/// beyond it sincos_n falls back to std::sin and std::cos.
inline constexpr double kSinCosRange = 1e6;

/// s[i] = sin(x[i]), c[i] = cos(x[i]) for i < n (arrays must not overlap).
void sincos_n(std::size_t n, const double* __restrict x, double* __restrict s, double* __restrict c);

/// e[i] = exp(x[i]) for i < n (arrays must not overlap); outside [-708, 709]
/// and for NaN, std::exp's value.
void exp_n(std::size_t n, const double* __restrict x, double* __restrict e);

/// Partial sums of a series in kLanes fixed lanes: term j in lane j mod kLanes
/// (each lane in the terms' order), the lanes then combined pairwise in a
/// fixed order. The same bits in every instruction set, and kLanes independent
/// chains of additions instead of one.
inline constexpr std::size_t kLanes = 8;
using Lanes = std::array<double, kLanes>;

/// acc[j mod kLanes] += v[j] for j < m (the first term in lane 0).
inline void accumulate(Lanes& acc, const double* v, std::size_t m) {
  std::size_t j = 0;
  for (; j + kLanes <= m; j += kLanes)
    for (std::size_t l = 0; l < kLanes; ++l) acc[l] += v[j + l];
  for (std::size_t l = 0; j < m; ++j, ++l) acc[l] += v[j];
}

/// The lanes' sum ((0+1)+(2+3))+((4+5)+(6+7)).
inline double total(const Lanes& a) { return ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7])); }
static_assert(kLanes == 8, "total() combines 8 lanes");

}  // namespace towsim::vecmath
