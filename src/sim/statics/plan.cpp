// The statics driver's plan (docs/theory.md §7 "Strategies and the driver").
#include "plan.hpp"

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/dynamics/bending.hpp"

namespace towsim::statics {

namespace {

/// The rigid-element solve of `model`'s Newton problem, with or without the
/// sweeps first: Newton-Krylov where the dense solve cannot go (or, after a
/// relaxation, above its polish size) when the parts are coupled beyond
/// what the sweeps balance (seabed contact, bending springs); Levenberg-
/// Marquardt up to its size limit, to 60 iterations after the sweeps, to
/// 1000 alone (a moving tow on the bottom: the contact springs make it
/// ill-conditioned), stopping at the seabed's round-off floor.
Attempt rigid_solve(const Model& model, bool sweeps) {
  const int N = 2 * model.cable.n() + 3 * static_cast<int>(model.bodies.size());  // unknowns [-]
  const bool coupled = model.seabed.has_value() || has_bending(model);
  Attempt a;
  a.sweeps = sweeps;
  a.newton_krylov = coupled && (N > kDenseLimit || (!sweeps && N > kPolishLimit));
  a.dense = N <= kDenseLimit;
  a.polish = N <= kPolishLimit;
  a.dense_iterations = sweeps ? kMaxIterations : kMaxDenseOnlyIterations;
  a.dense_to_floor = !sweeps;
  return a;
}

/// Relaxation, then the rigid solve without the sweeps: moving, to 1e-3
/// rad/s^2 (the dense solve polishes from there), at rest to 1e-6
/// (frictionless, it usually reaches the floor).
Attempt relaxed(const Model& model, const Vec3& V) {
  Attempt a = rigid_solve(model, false);
  a.relaxation = true;
  a.relax_target = V.norm() > 0 ? 1e-3 : 1e-6;
  return a;
}

}  // namespace

std::vector<std::string> Attempt::strategies() const {
  std::vector<std::string> out;
  if (relaxation) out.emplace_back("relaxation");
  if (sweeps) out.emplace_back("sweeps");
  if (newton_krylov) out.emplace_back("newton-krylov");
  if (dense) out.emplace_back("levenberg-marquardt");
  return out;
}

StaticsPlan plan_statics(const Model& model, const Vec3& V, Start start) {
  StaticsPlan plan;
  if (start == Start::DraggedCable || start == Start::BodyTurnedOnSeabed) {
    // Cable (or a body) laid on the bottom: the sweeps leave the contact
    // out and would lift it off. Relax, then solve without them.
    plan.attempts.push_back(relaxed(model, V));
  } else {
    // The sweeps, then Newton on all angles where they stop short.
    plan.attempts.push_back(rigid_solve(model, true));
    // On the bottom, when that fails (the contact left out of the sweeps):
    // relax from the better iterate, then solve without the sweeps.
    if (start == Start::LaidOnSeabed) plan.attempts.push_back(relaxed(model, V));
  }
  // Elastic elements: the rigid solution stretched by its tensions.
  plan.stretch = lengths_in_state(model);
  return plan;
}

Model without_winch(const Model& model) {
  Model held = model;
  held.winch = Winch{};
  return held;
}

Model rigid_copy(const Model& model) {
  Model rigid = model;
  for (Element& el : rigid.cable.elements) el.axial_stiffness = 0;
  return rigid;
}

StaticsPlan statics_plan(const Model& model, const Vec3& V) {
  if (model.winch.active()) return statics_plan(without_winch(model), V);
  SteadyProblem p(model, V);
  p.model = rigid_copy(p.model);
  return plan_statics(model, V, lay_start(p));
}

}  // namespace towsim::statics
