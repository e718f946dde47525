// Tow law `heave`: a vertical oscillation of the tow point.
#pragma once

#include "towsim/tow/kinematics.hpp"

namespace towsim {

/// z += amplitude sin(2 pi (t - start_time) / period) after start_time
/// (rising first); nothing before. An offset law.
struct Heave {
  double amplitude = 0;   // [m]
  double period = 1;      // [s]
  double start_time = 0;  // [s]

  bool operator==(const Heave&) const = default;

  /// Displacement (along z), its velocity and acceleration at t.
  TowKinematics at(double t) const;
  /// Times where the law is not smooth: its start.
  void breakpoints(std::vector<double>& out) const;
};

}  // namespace towsim
