// The sums over a sea's harmonics that give the Airy kinematics at one point
// (WaveField::kinematics, docs/theory.md 8 "Evaluation"). Compiled like
// vector_math.cpp: one variant per instruction set, without fused
// multiply-adds, partial sums in vecmath::kLanes fixed lanes
// (vecmath::accumulate): every variant gives the same bits, and the sums are
// not one chain of dependent additions.
#pragma once

#include <cstddef>

#include "towsim/waves/waves.hpp"

namespace towsim {

/// The four sums of the kinematics [m/s, m/s^2]: U = sum a w C cos, W = sum a
/// w S sin, AH = sum a w^2 C sin, AZ = sum a w^2 S cos over the harmonics,
/// C and S the depth factors cosh k(z+h) / sinh kh and sinh k(z+h) / sinh kh
/// (deep water: both e^{kz}), cos and sin of the phase; short-crested seas:
/// U and AH as horizontal vectors along each harmonic's direction (Ux, Uy,
/// Ax, Ay [R_g]), U and AH left 0.
struct HarmonicSums {
  double U = 0, W = 0, AH = 0, AZ = 0;
  double Ux = 0, Uy = 0, Ax = 0, Ay = 0;
};

/// The sums over c[0..n) at the point (x, y) [m, R_g], s = d . (x, y) along
/// the sea's direction [m], the height zc at which the depth factors are
/// taken [m] and the time t [s]; `deep`: infinite depth; `spread`: each
/// harmonic along its own (dx, dy).
HarmonicSums harmonic_sums(const WaveComponent* c, std::size_t n, double x, double y, double s, double zc, double t,
                           bool deep, bool spread);

}  // namespace towsim
