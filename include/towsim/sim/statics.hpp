// Steady-tow statics: the equilibrium of cable and body for a steady tow.
#pragma once

#include <string>

#include "towsim/dynamics/state.hpp"

namespace towsim {

/// Result of a statics solve.
struct StaticsResult {
  PhysicalState state;      // configuration, moving with the tow velocity
  Vec3 tow_velocity;        // steady velocity of the tow point [m/s, R_g]
  Vec3 tow_force;           // F_R [N, R_g]
  Vec3 link_force;          // F_L [N, R_g]
  double residual = 0;      // largest |acceleration| left [rad/s^2]
  int iterations = 0;
  bool converged = false;
  std::string message;
};

/// Equilibrium for the tow's velocity at t = 0 (Motion mode: the tow law's
/// final steady velocity if it starts at rest) in the model's current.
StaticsResult steady_state(const Model& model);

}  // namespace towsim
