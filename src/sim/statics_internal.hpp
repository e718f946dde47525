// Internal to the physics library and its tests: not installed, not part of
// the libraries' interface (include/towsim/ is).
#pragma once

#include "towsim/sim/statics.hpp"

namespace towsim {

/// Newton-Krylov alone (solve_statics' step for large problems with a
/// seabed) from the configuration `start`, for tests of its compression
/// guard: `converged` when it reached the residual floor with every element
/// in tension; `message` "compression" when the guard dropped an
/// equilibrium with an element in compression (`state`: the start).
/// tow_force and joint_force at `state`; the sample is left empty.
StaticsResult newton_krylov_statics(const Model& model, const Vec3& V, const PhysicalState& start);

}  // namespace towsim
