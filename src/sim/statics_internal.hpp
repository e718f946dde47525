// Internal to the physics library and its tests: not installed, not part of
// the libraries' interface (include/towsim/ is).
#pragma once

#include "statics/plan.hpp"  // the driver's plan (statics::statics_plan)
#include "towsim/sim/statics.hpp"

namespace towsim {

/// Newton-Krylov alone (solve_statics' step for large problems with a
/// seabed) from the configuration `start`, for tests of its compression
/// guard: `converged` when it reached the residual floor with every element
/// in tension; `message` "compression" when the guard dropped an
/// equilibrium with an element in compression (`state`: the start).
/// tow_force and joint_force at `state`; the sample is left empty.
StaticsResult newton_krylov_statics(const Model& model, const Vec3& V, const PhysicalState& start);

/// The classification BodyEquilibria gives body `body` of `model` (its
/// first control surfaces' state) at attitude q, its link at Q, towed at V,
/// the cable below pulled by f2 at its lower link (in-line bodies).
BodyEquilibrium classify_body_balance(const Model& model, std::size_t body, const Vec3& Q, const Vec3& V,
                                      const Vec3& f2, const Quat& q);

}  // namespace towsim
