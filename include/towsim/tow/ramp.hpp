// Tow law `ramp`: a straight tow that sets off at t = 0.
#pragma once

#include "towsim/tow/kinematics.hpp"

namespace towsim {

/// Velocity along `direction` grows linearly from 0 at t = 0 to `speed` at
/// ramp_time (constant acceleration), then stays at `speed`. An offset law:
/// its displacement from the tow start adds to the other offsets'.
struct Ramp {
  Vec3 direction = Vec3::UnitX();  // unit direction [-, R_g]
  double speed = 0;                // final speed [m/s]
  double ramp_time = 0;            // time to reach it [s] (0 = at speed from t = 0)

  bool operator==(const Ramp&) const = default;

  /// Displacement from the tow start, its velocity and acceleration at t.
  TowKinematics at(double t) const;
  /// Times where the law is not smooth: the end of the ramp.
  void breakpoints(std::vector<double>& out) const;
};

}  // namespace towsim
