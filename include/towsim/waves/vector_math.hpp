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

}  // namespace towsim::vecmath
