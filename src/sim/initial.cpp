// The initial state of a run (docs/scenario.md "initial").
#include <algorithm>
#include <cmath>
#include <vector>

#include "towsim/integrators/system.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {

namespace {

/// Elastic elements of a straight chain at rest start at their static
/// stretch: element k carries T_k = -e_k . (W_k/2 + everything's apparent
/// weight below it), W the apparent weights (elements, attachments, bodies),
/// the axial part of its d-equation at rest (docs/theory.md §5.4); vertical
/// and in still water that is the equilibrium, so no axial ringing starts.
void stretch_at_rest(const Model& model, PhysicalState& s) {
  if (!lengths_in_state(model)) return;
  const auto& els = model.cable.elements;
  const double rho = model.fluid.rho, g = model.fluid.g;
  std::vector<double> at_joint(els.size() + 1, 0.0);  // apparent weight lumped at joint k [N]
  for (const Attachment& a : model.cable.attachments)
    at_joint[static_cast<std::size_t>(a.joint)] += (a.mass - rho * a.volume) * g;
  for (const Body& b : model.bodies)
    at_joint[static_cast<std::size_t>(body_joint(model, b))] += (b.mass - rho * b.displaced_volume) * g;
  double below = at_joint.back();  // apparent weight below element k's bottom joint [N, along -z]
  for (std::size_t k = els.size(); k-- > 0;) {
    const double T = std::max(0.0, -s.e[k].z() * (below + 0.5 * els[k].weight));
    if (is_elastic(els[k])) s.length[k] = els[k].length * (1 + T / els[k].axial_stiffness);
    below += els[k].weight + at_joint[k];
  }
}

}  // namespace

PhysicalState initial_state(const Model& model) {
  if (model.initial.kind == Initial::Kind::Steady) return steady_state(model).state;
  PhysicalState s = PhysicalState::hanging(model);
  if (model.initial.kind == Initial::Kind::Direction) s.e.assign(model.cable.n(), model.initial.direction.normalized());
  stretch_at_rest(model, s);
  if (model.tow.mode == Tow::Mode::Motion) {
    // At rest: a tow already moving at t = 0 is a velocity jump, which the
    // run applies as an impulse (apply_tow_jump) before the first step.
    s.r0 = tow_kinematics(model.tow, 0.0).pos;
    s.v0.setZero();
  } else {
    s.r0 = model.tow.start;
  }
  return s;
}

void lean_upright(const Model& model, PhysicalState& s) {
  if (!model.seabed || end_body(model) != nullptr) return;
  constexpr double kLean = 1e-4;                             // [rad]
  const Vec3 leaning(std::sin(kLean), 0, -std::cos(kLean));  // [-, R_g]
  for (Vec3& e : s.e)
    if (e.x() == 0 && e.y() == 0 && e.z() < 0) e = leaning;
}

}  // namespace towsim
