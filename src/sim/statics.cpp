// Steady-tow statics (docs/theory.md §7): zero accelerations of the
// dynamics' own equations. The driver: the start, then the strategies its
// plan names (src/sim/statics/plan.cpp), each in its own file under src/sim/statics/.
#include "towsim/sim/statics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "statics/plan.hpp"
#include "statics/problem.hpp"
#include "statics/strategies.hpp"
#include "statics_internal.hpp"

namespace towsim {

Vec3 final_tow_velocity(const Tow& tow) {
  Vec3 v = Vec3::Zero();
  for (const auto& piece : tow.pieces) {
    if (const auto* ramp = std::get_if<Ramp>(&piece)) v += ramp->speed * ramp->direction.normalized();
    if (const auto* track = std::get_if<Track>(&piece); track != nullptr && track->time.size() > 1)
      v += track->at(track->time.back()).vel;
  }
  // Manoeuvres: the course's last speed and heading replace the horizontal part.
  CourseState c;
  if (final_course(tow, c)) {
    v = Vec3(c.U * c.h.x(), c.U * c.h.y(), v.z());
  }
  return v;
}

namespace {

/// One attempt of the plan from the iterate: its relaxation, then the
/// rigid-element solve; the iterations add up over the attempts.
void run_attempt(statics::SteadyProblem& p, const statics::Attempt& a, const volatile int* stop_flag,
                 StaticsResult& out) {
  const int before = out.iterations;
  if (a.relaxation) statics::relax(p, a.relax_target, stop_flag);
  out.message.clear();  // a failed attempt's
  statics::solve_rigid(p, a, stop_flag, out);
  out.iterations += before;
}

/// The result at the equilibrium p.base: the forces of the elastic model's
/// own evaluation there, the sample, and the bodies' balances.
void report(const Model& elastic, statics::SteadyProblem& p, const Vec3& V, StaticsResult& out) {
  // Forces at the equilibrium (the elastic model's own evaluation).
  out.state = p.base;
  out.state.length_rate.assign(out.state.length.size(), 0.0);
  out.tow_velocity = V;
  forward_dynamics(elastic, p.base, 0.0, p.ws);
  out.tow_force = p.ws.acc.tow_force;
  out.link_force = p.ws.acc.link_force;
  out.body_force = p.ws.acc.lower_link_force;
  out.joint_force = p.ws.acc.joint_force;
  out.sample = make_sample(elastic, p.base, p.ws, 0.0);
  if (out.converged) out.equilibria = statics::find_equilibria(elastic, p.base, p.ws, V, out.body_force);
  // Angles balanced but forces overflowed (e.g. mass_per_length 1e200): no equilibrium to report.
  // (components near 1e200 are finite, their norm, the tension, is not).
  bool finite = std::isfinite(out.tow_force.norm());
  for (const std::vector<Vec3>* forces : {&out.link_force, &out.body_force, &out.joint_force})
    for (const Vec3& f : *forces) finite = finite && std::isfinite(f.norm());
  if (out.converged && !finite) {
    out.converged = false;
    out.message =
        "no finite equilibrium: the forces overflow double precision (check the scenario's masses, sizes "
        "and speeds)";
  }
}

}  // namespace

StaticsResult solve_statics(const Model& model, const Vec3& V, const volatile int* stop_flag) {
  // A steady tow holds the winch: the configuration at the current length.
  if (model.winch.active()) {
    StaticsResult r = solve_statics(statics::without_winch(model), V, stop_flag);
    if (elastic_winch(model)) r.state.top_unstretched = model.cable.elements.front().length;  // L_1
    return r;
  }
  // The steady problem (the tow at V in calm water) with rigid elements for
  // Newton; the elastic model kept for the stretch and the forces.
  statics::SteadyProblem p(model, V);
  const Model elastic = p.model;
  p.model = statics::rigid_copy(elastic);
  // The start, and the plan it calls for.
  const statics::StaticsPlan plan = statics::plan_statics(model, V, statics::lay_start(p));
  // The attempts in turn, each after the one before failed (not when interrupted).
  StaticsResult out;
  const statics::Attempt* last = nullptr;
  for (const statics::Attempt& a : plan.attempts) {
    if (last != nullptr && (out.converged || out.interrupted)) break;
    run_attempt(p, a, stop_flag, out);
    last = &a;
  }
  // Elastic elements: the rigid solution stretched, each pass by the attempt that converged.
  if (plan.stretch && out.converged) statics::stretch(elastic, p, *last, stop_flag, out);
  report(elastic, p, V, out);
  return out;
}

BodyEquilibrium classify_body_balance(const Model& model, std::size_t body, const Vec3& Q, const Vec3& V,
                                      const Vec3& f2, const Quat& q) {
  Workspace ws(model);
  return statics::classify_balance(model, model.bodies[body], Q, V, f2, q, ws.body[body]);
}

StaticsResult newton_krylov_statics(const Model& model, const Vec3& V, const PhysicalState& start) {
  statics::SteadyProblem p(model, V);
  p.model = statics::rigid_copy(p.model);  // rigid elements, as solve_statics
  PhysicalState s = start;
  s.r0 = p.model.tow.start;
  s.v0 = V;
  p.accept_state(s);
  StaticsResult out;
  const double floor = statics::residual_floor(p.model);
  const bool rejected = statics::newton_krylov(p, floor, nullptr, out.iterations);
  const Eigen::VectorXd r = p.residual(Eigen::VectorXd::Zero(p.size()));  // p.ws at the result
  out.residual = p.max_alpha(r);
  out.converged = !rejected && statics::good_residual(p, floor, r);
  if (rejected) out.message = "compression";
  out.state = p.base;
  out.tow_velocity = V;
  out.tow_force = p.ws.acc.tow_force;
  out.joint_force = p.ws.acc.joint_force;
  return out;
}

StaticsResult steady_state(const Model& model) {
  StaticsResult res = steady_state(model, nullptr);
  if (!res.converged) throw std::runtime_error(res.message);
  return res;
}

StaticsResult steady_state(const Model& model, const volatile int* stop_flag) {
  if (model.tow.mode != Tow::Mode::Motion)
    throw std::runtime_error("initial: steady needs tow.mode: motion (the steady velocity comes from the tow law)");
  const TowKinematics k = tow_kinematics(model.tow, 0.0);
  StaticsResult res = solve_statics(model, tow_law_kinematics(model.tow, 0.0).vel, stop_flag);  // mean tow velocity
  if (!res.converged && !res.interrupted && model.seabed && res.tow_velocity.norm() > 0)
    res.message += " (a tow moving with cable on the seabed is solved by relaxation, then the dense solve up to " +
                   std::to_string(statics::kDenseLimit / 2) +
                   " elements and Newton-Krylov above: fewer elements, or start at rest or from a direction "
                   "above the bottom)";
  res.state.r0 = k.pos;
  res.state.v0 = k.vel;
  return res;
}

}  // namespace towsim
