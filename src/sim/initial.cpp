// The initial state of a run (docs/scenario.md "initial").
#include "towsim/integrators/system.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {

PhysicalState initial_state(const Model& model) {
  if (model.initial.kind == Initial::Kind::Steady) return steady_state(model).state;
  PhysicalState s = PhysicalState::hanging(model);
  if (model.initial.kind == Initial::Kind::Direction) s.e.assign(model.cable.n(), model.initial.direction.normalized());
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

}  // namespace towsim
