// The statics driver's plan (docs/theory.md §7 "Strategies and the driver"):
// which strategies solve_statics tries for a model, in which order and why.
// Internal to the physics library and its tests.
#pragma once

#include <string>
#include <vector>

#include "towsim/sim/statics.hpp"

namespace towsim::statics {

/// Where the starting configuration leaves the cable (lay_start).
enum class Start {
  Aligned,             // each element along the force it carries (no seabed)
  LaidOnSeabed,        // ... and laid along the seabed where it would cross it
  BodyTurnedOnSeabed,  // ... a dragged in-line body on the bottom turned along the cable above it
  DraggedCable,        // the dragged-cable start: the lying length found by shooting (lay_along_bottom)
};

/// One attempt at the rigid elements' equilibrium: the strategies it runs,
/// in this order, each only while the iterate is not yet converged.
struct Attempt {
  bool relaxation = false;      // dynamic relaxation first (relax)
  double relax_target = 0;      // ... until every |alpha| at rest is below this [rad/s^2]
  bool sweeps = false;          // the O(n) sweeps (solve_by_sweeps)
  bool newton_krylov = false;   // Newton-Krylov on all angles (newton_krylov)
  bool dense = false;           // Levenberg-Marquardt on all angles (levenberg_marquardt), at most kDenseLimit unknowns
  bool polish = false;          // ... even from a result converged only to the floor (at most kPolishLimit unknowns)
  int dense_iterations = 0;     // its iterations at most [-]
  bool dense_to_floor = false;  // ... it stops at the residual floor (no sweeps: the seabed's round-off)

  /// The strategies' names in order: "relaxation", "sweeps", "newton-krylov", "levenberg-marquardt".
  std::vector<std::string> strategies() const;
};

/// What solve_statics does for a model (without an active winch: it solves
/// without_winch(model)) and its start: the attempts, each after the one
/// before failed (not when interrupted), then the stretch of elastic elements.
struct StaticsPlan {
  std::vector<Attempt> attempts;
  bool stretch = false;  // elastic elements: the rigid solution stretched (stretch), pass by pass
};

/// The plan for `model` towed at V from `start` (plan.cpp).
StaticsPlan plan_statics(const Model& model, const Vec3& V, Start start);

/// `model` without its winch: a steady tow holds the winch at the current length.
Model without_winch(const Model& model);

/// `model` with rigid elements (axial stiffness 0) at their current lengths: the Newton problem.
Model rigid_copy(const Model& model);

/// The plan solve_statics follows for `model` towed at V: its start laid,
/// then plan_statics (for tests).
StaticsPlan statics_plan(const Model& model, const Vec3& V);

}  // namespace towsim::statics
