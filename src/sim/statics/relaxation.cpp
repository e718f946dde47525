// Dynamic relaxation with kinetic damping (docs/theory.md §7 "Seabed").
#include <cmath>
#include <limits>
#include <memory>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"

namespace towsim::statics {

/// Dynamic relaxation towards the steady tow (docs/theory.md §7 "Seabed"):
/// the dynamics themselves from the iterate, the tow point moving at V,
/// integrated by Rosenbrock-W (the contact springs do not bound its step),
/// with kinetic damping: whenever the chain's rotational kinetic energy
/// (relative to the steady motion) passes a peak, every element and body
/// rotation rate is set to zero, which leaves every point moving at V again.
/// The water's drag and the bottom's friction damp as well. Stops when the
/// angular accelerations of the state at rest fall below `target`, after
/// kMaxRelaxSteps steps, or on the stop flag. p.base: the result (tow
/// point back at its start: a flat bottom is the same everywhere).
void relax(SteadyProblem& p, double target, const volatile int* stop_flag) {
  constexpr int kMaxRelaxSteps = 20000;     // accepted steps [-]
  constexpr int kCheckEvery = 20;           // steps between residual checks [-]
  constexpr double kRelaxTolerance = 1e-5;  // local error target of the steps [-]
  constexpr double kSharpSlip = 0.1;        // the relaxation's v_s' / U, at most [-]
  constexpr int kStallChecks = 50;          // checks (1000 steps) without the residual halving: stalled [-]
  Model rm = p.model;
  const double U = p.V.norm();
  // At rest the friction vanishes at the equilibrium; left in, its viscous
  // slope mu N / v_s makes the lying cable only creep: relax without it.
  if (!(U > 0) && rm.seabed) rm.seabed->friction = 0;
  // Moving near the smoothing speed v_s the same slope makes the lying
  // length creep as well: relax with a sharper law, v_s' = U / 10, scaled
  // to the same friction at the steady slip U (so the same equilibrium).
  if (U > 0 && rm.seabed && rm.seabed->slip_speed > kSharpSlip * U) {
    Seabed& sb = *rm.seabed;
    const double sharp = kSharpSlip * U;
    sb.friction *= std::hypot(U, sharp) / std::hypot(U, sb.slip_speed);
    sb.slip_speed = sharp;
  }
  rm.tow.pieces.clear();
  if (U > 0) rm.tow.pieces.emplace_back(Ramp{p.V / U, U, 0.0});
  finalize_tow(rm.tow);
  // The bodies' own stiffness only in W: with the pull of the cable below
  // in it, a depressor resting on the bottom rolled over on the way
  // (docs/theory.md §6.3).
  rm.sim.line_pull_stiffness = false;
  const std::unique_ptr<System> sys = make_system(rm);
  if (!sys->has_stage_solve()) return;
  double weight = 1.0;  // force scale of the error norm: the chain's apparent weight [N]
  for (const Element& el : rm.cable.elements) weight += std::abs(el.weight);
  // No rotation rates: every point moving at V.
  auto stop_rotations = [](PhysicalState& st) {
    for (auto& w : st.w) w.setZero();
    for (auto& b : st.bodies) b.w.setZero();
  };
  // The iterate handed back: at rest, the tow point at its start.
  auto accept = [&](PhysicalState st) {
    stop_rotations(st);
    st.r0 = rm.tow.start;
    st.v0 = p.V;
    p.accept_state(st);
  };
  PhysicalState s = p.base;
  s.r0 = rm.tow.start;
  s.v0 = p.V;
  stop_rotations(s);
  StateVector y = sys->initial(s, 0.0);
  RosenbrockW ros(*sys, kRelaxTolerance, weight, RosenbrockW::ForceEstimate::Filtered,
                  RosenbrockW::TimeDerivative::None);  // the path does not matter: no f_t evaluations
  double t = 0, h = 1e-3, previous = 0;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p.size());
  double best = std::numeric_limits<double>::infinity(), anchor = best;  // residuals at the checks [rad/s^2]
  PhysicalState best_state = p.base;
  int since = 0;  // checks since the residual last halved
  for (int step = 0; step < kMaxRelaxSteps && !stopped(stop_flag);) {
    if (!ros.try_step(y, t, h)) {
      if (!(h > 1e-12)) break;
      continue;
    }
    ++step;
    s = sys->physical(y);
    double ke = 0;  // rotational kinetic energy about each part's joint [J]
    for (int k = 0; k < p.n; ++k) ke += p.scale[static_cast<std::size_t>(k)] * s.w[k].squaredNorm();
    for (int b = 0; b < p.nb; ++b)
      ke += p.scale[static_cast<std::size_t>(p.n + b)] * s.bodies[static_cast<std::size_t>(b)].w.squaredNorm();
    const bool peak = ke < previous;
    previous = peak ? 0.0 : ke;
    if (peak) {
      stop_rotations(s);
      y = sys->initial(s, t);
      ros.invalidate();
    }
    if (step % kCheckEvery == 0) {
      accept(s);
      const double res = p.max_alpha(p.residual(zero));
      if (res < target) return;
      // At rest, stalled: the residual has not halved in kStallChecks checks
      // (the in-line depressors of test_seabed.cpp stop near 1e-4 rad/s^2):
      // hand the best iterate to the dense solve instead of using up
      // kMaxRelaxSteps. Not when moving: the dragged in-line clump wanders
      // near 0.3 rad/s^2 for 20000 steps, and the dense solve converges
      // from where that leaves it, not from its best iterate after 1000.
      if (res < best) best = res, best_state = p.base;
      if (best < 0.5 * anchor) {
        anchor = best;
        since = 0;
      } else if (!(U > 0) && ++since >= kStallChecks) {
        p.accept_state(best_state);
        return;
      }
    }
  }
  accept(sys->physical(y));
}

}  // namespace towsim::statics
