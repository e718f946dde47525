// Tow law `track`: a tabulated path, interpolated by a natural cubic spline.
#pragma once

#include "towsim/tow/kinematics.hpp"

namespace towsim {

/// Positions at times, relative to the tow start, joined by the natural cubic
/// spline (velocity and acceleration continuous; zero acceleration at both
/// ends). Before the first row and after the last one the tow point moves in
/// a straight line at the spline's end velocity (so the acceleration stays
/// continuous: it is zero at the ends of a natural spline). An offset law.
struct Track {
  std::vector<double> time;  // [s], strictly increasing
  std::vector<Vec3> pos;     // [m, R_g], relative to the tow start
  std::vector<Vec3> curv;    // spline second derivatives at the rows [m/s^2, R_g] (prepare())

  bool operator==(const Track&) const = default;

  /// A track through these rows, with its spline prepared.
  static Track make(std::vector<double> time, std::vector<Vec3> pos);
  /// Compute `curv`, so that evaluating costs O(log rows) with no allocation.
  /// A track without it is still evaluated correctly, recomputing the spline per call.
  void prepare();

  /// Displacement, velocity and acceleration at t.
  TowKinematics at(double t) const;
  /// Times where the law is not smooth: its first and last rows.
  void breakpoints(std::vector<double>& out) const;
};

}  // namespace towsim
