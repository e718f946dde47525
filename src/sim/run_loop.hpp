// The run loop, shared by a chain's run and a network's: integrate, land on
// output times and the tow law's breakpoints, check the state after every
// step, write samples. A rig (the chain or the network) supplies its system,
// checks, events and samples:
//   sim(), winch(), sea(), force_scale(), breakpoints(), sys(),
//   check(sys, y), event_due(sys, y), track(sys, y, t, stats),
//   event(y, t, stats), write(y, t, stats), flush(), and `refusal` (an
//   error text a sample's check sets: the run stops).
#pragma once

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::run {

namespace odeint = boost::numeric::odeint;

/// Before each step at time t [s]: true to stop now. It also reports the
/// progress t / duration, where the Python module polls Ctrl-C.
using StopCheck = std::function<bool(double)>;

/// Advance y from t to `target` (an output time), by fixed RK4 steps or
/// adaptive steps that land on `target`; `s`: storage for the checks'
/// physical state. Returns an error text or empty; returns early (t short
/// of `target`) once `stopping` says so.
template <class Rig, class Stepper>
std::string advance_fixed(Rig& rig, System& sys, Stepper& rk, StateVector& y, double& t, double target, RunStats& stats,
                          bool& event, const StopCheck& stopping) {
  while (t < target - 1e-12 * std::max(1.0, target) && !stopping(t)) {
    const double h = std::min(rig.sim().time_step, target - t);
    rk.do_step(sys.in_window({t, t + h}), y, t, h);
    t = (target - (t + h) < 1e-12 * std::max(1.0, target)) ? target : t + h;
    sys.project(y, t);
    ++stats.steps;
    if (auto err = rig.check(sys, y); !err.empty()) return err;
    if ((event = rig.event_due(sys, y))) return {};
    rig.track(sys, y, t, stats);
  }
  return {};
}

/// Advance y by adaptive steps until t reaches `stop`, never stepping past
/// `land` (>= stop: a breakpoint or the run's end, landed exactly). With
/// land == stop every step lands on stop; with land > stop (dense output)
/// the last step may pass stop. `try_step(y, t, dt)` attempts a step (true:
/// accepted, t and y advanced; dt the proposal for the next step either
/// way); `accepted(y, t)` runs after each accepted step (projection).
/// Returns an error text or empty; returns early once `stopping` says so.
template <class Rig, class TryStep, class Accepted>
std::string advance_adaptive(Rig& rig, System& sys, TryStep&& try_step, Accepted&& accepted, StateVector& y, double& t,
                             double land, double stop, double& h, RunStats& stats, bool& event,
                             const StopCheck& stopping) {
  const double h_min = 1e-12 * std::max(1.0, rig.sim().duration);
  while (t < stop - 1e-12 * std::max(1.0, stop) && !stopping(t)) {
    const double h_try = std::min({h, rig.sim().max_step, land - t});
    double dt = h_try;
    if (!try_step(y, t, dt)) {
      ++stats.rejected_steps;
      h = dt;
      if (h < h_min) {
        std::ostringstream os;
        os << "step size collapsed below " << h_min << " s (tolerance " << rig.sim().tolerance << " cannot be met)";
        return os.str();
      }
      continue;
    }
    // Keep the controller's proposal unless this step was shortened to land.
    if (h_try >= h || dt > h) h = dt;
    // A step ending on `land` or `stop` to round-off ends there.
    if (std::abs(land - t) < 1e-12 * std::max(1.0, land)) t = land;
    if (std::abs(stop - t) < 1e-12 * std::max(1.0, stop)) t = stop;
    accepted(y, t);
    ++stats.steps;
    if (auto err = rig.check(sys, y); !err.empty()) return err;
    if ((event = rig.event_due(sys, y))) return {};
    rig.track(sys, y, t, stats);
  }
  return {};
}

/// The same with an odeint controlled stepper (dopri5, Cash-Karp): the tow
/// law is evaluated inside each trial step's window; accepted steps are
/// projected.
template <class Rig, class Controlled>
std::string advance_odeint(Rig& rig, System& sys, Controlled& ctrl, StateVector& y, double& t, double target, double& h,
                           RunStats& stats, bool& event, const StopCheck& stopping) {
  auto try_step = [&](StateVector& yy, double& tt, double& dt) {
    return ctrl.try_step(sys.in_window({tt, tt + dt}), yy, tt, dt) != odeint::fail;  // tt, dt updated
  };
  auto accepted = [&](StateVector& yy, double tt) {
    sys.project(yy, tt);
    if constexpr (requires { ctrl.reset(); }) ctrl.reset();  // projection changed y: no stale FSAL derivative
  };
  return advance_adaptive(rig, sys, try_step, accepted, y, t, target, target, h, stats, event, stopping);
}

/// The same with Rosenbrock-W steps (error control on state and forces),
/// which do not land on `stop` (an output time): it is sampled by dense output.
template <class Rig>
std::string advance_rosenbrock(Rig& rig, System& sys, RosenbrockW& ros, StateVector& y, double& t, double land,
                               double stop, double& h, RunStats& stats, bool& event, const StopCheck& stopping) {
  auto try_step = [&](StateVector& yy, double& tt, double& dt) { return ros.try_step(yy, tt, dt); };
  auto accepted = [](StateVector&, double) {};
  return advance_adaptive(rig, sys, try_step, accepted, y, t, land, stop, h, stats, event, stopping);
}

/// The largest error estimates so far, kept across winch events (which
/// start a new stepper).
inline void keep_ros_errors(const RosenbrockW& ros, RunStats& stats) {
  stats.error_estimate = std::max(stats.error_estimate, ros.max_error);
  stats.force_error_estimate = std::max(stats.force_error_estimate, ros.max_force_error);
}

/// The run's time stepper (simulation.integrator), built in one place: at
/// the start and again for the chain that a winch event makes (the state
/// changes size; Rosenbrock-W holds its system). rk4 and the odeint
/// controlled steppers size themselves on first use.
class Steppers {
 public:
  /// `winch`: the run has a winch (no W time column); `sea`: waves or a vessel (PI step control).
  Steppers(const Simulation& sim, bool winch, bool sea) : sim_(sim), winch_(winch), sea_(sea) {}

  /// Fresh steppers for the system (its force error's absolute scale
  /// `force_scale` [N]); a Rosenbrock-W stepper's largest errors so far go
  /// into stats first. `check` gets the refusal of an integrator that the
  /// system cannot serve.
  void reset(System& sys, double force_scale, RunStats& stats, std::string& check) {
    const double tol = sim_.tolerance;
    rk4_ = odeint::runge_kutta4<StateVector>();
    dopri_ = odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<StateVector>());
    cashkarp_ = odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<StateVector>());
    if (ros_) keep_ros_errors(*ros_, stats);
    if (sim_.integrator != Integrator::Rosenbrock) return;
    if (!sys.has_stage_solve())
      check = "rosenbrock needs formulation: default (its stage solves use the O(n) recursion)";
    // W's time column (f_t): not with a winch. f_t is right there (fixed
    // steps: more accurate, order 3), but on fish-depth-change it does not
    // pay (docs/performance.md "W's time column", "With a winch"): in the
    // schedule's speed ramps the steps grow up to 2x and the fish's attitude
    // error, ~tol per step and of one sign, adds up (link tension 2.8x less
    // accurate); between them max_step binds, f_t only costs (6 % more
    // evaluations). More evaluations for equal accuracy at every tolerance.
    // Without a winch: by a difference on every other step, extrapolated
    // between (6-8 % fewer evaluations, docs/performance.md "W's time
    // column extrapolated").
    const auto td = winch_ ? RosenbrockW::TimeDerivative::None : RosenbrockW::TimeDerivative::Extrapolated;
    ros_ = std::make_unique<RosenbrockW>(sys, tol, force_scale, RosenbrockW::ForceEstimate::Embedded, td);
    // In a sea state the error varies from step to step with the waves: the PI
    // controller (the plain one rejected 28 % of sea-state-tow's steps).
    if (sea_) ros_->set_step_control(RosenbrockW::StepControl::PI);
  }

  /// Rosenbrock-W steps pass output times (dense output) and land only on
  /// breakpoints and the run's end; the others land on every output time.
  bool dense() const { return sim_.integrator == Integrator::Rosenbrock; }

  /// Advance y from t towards `target` (an output time or a breakpoint),
  /// landing on `land` (dense output; else `target`): see advance_fixed and
  /// advance_adaptive.
  template <class Rig>
  std::string advance(Rig& rig, System& sys, StateVector& y, double& t, double land, double target, double& h,
                      RunStats& stats, bool& event, const StopCheck& stopping) {
    switch (sim_.integrator) {
      case Integrator::RK4:
        return advance_fixed(rig, sys, rk4_, y, t, target, stats, event, stopping);
      case Integrator::DOPRI5:
        return advance_odeint(rig, sys, dopri_, y, t, target, h, stats, event, stopping);
      case Integrator::CashKarp54:
        return advance_odeint(rig, sys, cashkarp_, y, t, target, h, stats, event, stopping);
      case Integrator::Rosenbrock:
        return advance_rosenbrock(rig, sys, *ros_, y, t, land, target, h, stats, event, stopping);
    }
    return "internal: unknown integrator";
  }

  /// At a breakpoint of the tow law: its acceleration (and maybe y) jumps.
  void invalidate() {
    if (ros_) ros_->invalidate();
  }

  /// The state at `time`, passed by the last step (dense output): false when
  /// the stepper has none.
  bool dense_output(double time, StateVector& y) const { return ros_ && ros_->dense_output(time, y); }

  /// At the run's end: the largest error estimates into stats.
  void finish(RunStats& stats) const {
    if (ros_) keep_ros_errors(*ros_, stats);
  }

 private:
  const Simulation& sim_;  // the run's settings
  bool winch_ = false;     // the run has a winch
  bool sea_ = false;       // waves or a vessel
  odeint::runge_kutta4<StateVector> rk4_;
  decltype(odeint::make_controlled(1.0, 1.0, odeint::runge_kutta_dopri5<StateVector>())) dopri_ =
      odeint::make_controlled(1.0, 1.0, odeint::runge_kutta_dopri5<StateVector>());
  decltype(odeint::make_controlled(1.0, 1.0, odeint::runge_kutta_cash_karp54<StateVector>())) cashkarp_ =
      odeint::make_controlled(1.0, 1.0, odeint::runge_kutta_cash_karp54<StateVector>());
  std::unique_ptr<RosenbrockW> ros_;
};

/// Integrate the rig's state y from t = 0 (its sample at 0 written) to the
/// run's duration, writing a sample at every output time: steps landing on
/// the tow law's breakpoints (the impulsive response at a velocity jump),
/// the rig's events (the state changes size) after the outputs passed are
/// written, dense output for Rosenbrock-W. Never throws on numerical
/// failure: it stops, flushes the rig's sink and reports it in stats.
template <class Rig>
RunStats run_loop(Rig& rig, StateVector& y, RunStats stats, std::chrono::steady_clock::time_point wall0,
                  const ProgressFn& progress, const volatile int* stop_flag) {
  double t = 0;
  std::string& check = rig.refusal;
  Steppers steppers(rig.sim(), rig.winch(), rig.sea());
  steppers.reset(rig.sys(), rig.force_scale(), stats, check);
  double h = rig.sim().time_step;
  const double T = rig.sim().duration, dT = rig.sim().output_interval;
  const long n_out = static_cast<long>(std::ceil(T / dT - 1e-9));
  std::vector<double> breaks = rig.breakpoints();
  std::sort(breaks.begin(), breaks.end());
  auto next_break = breaks.begin();
  // Rosenbrock steps pass output times (dense output) and land only on
  // breakpoints and the run's end; a winch event after a step that passed
  // output times waits until they are written from the old chain.
  const bool dense = steppers.dense();
  bool pending_event = false;
  StateVector y_out;   // dense output state
  double written = t;  // time of the last sample written [s]
  const StopCheck stopping = [&](double tt) {
    if (progress) progress(tt / T);
    return stop_flag != nullptr && *stop_flag != 0;
  };
  for (long k = 1; k <= n_out && check.empty(); ++k) {
    if (stop_flag && *stop_flag) {
      // Stopped at the last sample on disk (a dense-output step may have passed it).
      stats.status = "interrupted";
      stats.message = "interrupted by signal at t = " + std::to_string(written) + " s";
      break;
    }
    const double out_time = std::min(T, static_cast<double>(k) * dT);
    std::string err;
    // Land on every breakpoint of the tow law up to the output time; where
    // the tow velocity jumps, give the chain its impulsive response.
    while (err.empty()) {
      const double eps = 1e-12 * std::max(1.0, t);
      if (pending_event) {
        if (t > out_time + 1e-12 * std::max(1.0, out_time)) break;  // write this output first
        pending_event = false;
        rig.event(y, t, stats);
        steppers.reset(rig.sys(), rig.force_scale(), stats, check);
      }
      while (next_break != breaks.end() && *next_break < t - eps) ++next_break;
      const bool at_break = next_break != breaks.end() && std::abs(*next_break - t) <= eps;
      if (at_break) {
        rig.sys().apply_tow_jump(y, t);
        steppers.invalidate();
        ++next_break;
      }
      if (t >= out_time - 1e-12 * std::max(1.0, out_time)) break;
      const double target = (next_break != breaks.end() && *next_break < out_time) ? *next_break : out_time;
      // Dense output: land on the next breakpoint or the run's end only.
      const double land = dense ? (next_break != breaks.end() ? std::min(*next_break, T) : T) : target;
      bool event = false;
      err = steppers.advance(rig, rig.sys(), y, t, land, target, h, stats, event, stopping);
      // The state changes size: new chain, fresh steppers (sized on first
      // use), at the top of this loop once the outputs passed are written.
      if (event && err.empty()) pending_event = true;
      if (stop_flag && *stop_flag) break;  // checked after every step: a stop between outputs is prompt
    }
    if (!err.empty()) {
      std::ostringstream os;
      os << "numerical failure at t = " << t << " s: " << err;
      stats.status = "failed";
      stats.message = os.str();
      break;
    }
    if (stop_flag && *stop_flag && t < out_time - 1e-12 * std::max(1.0, out_time)) {
      stats.status = "interrupted";  // between output times: the last sample on disk is the end
      stats.message = "interrupted by signal at t = " + std::to_string(written) + " s";
      break;
    }
    if (std::abs(t - out_time) <= 1e-12 * std::max(1.0, out_time)) {
      rig.write(y, out_time, stats);  // a step ended here (to round-off)
    } else if (steppers.dense_output(out_time, y_out)) {
      rig.write(y_out, out_time, stats);  // the step passed out_time
    } else {
      stats.status = "failed";
      stats.message = "internal: no state at output time " + std::to_string(out_time) + " s";
      break;
    }
    written = out_time;
    if (progress) progress(out_time / T);
  }
  if (!check.empty() && stats.status == "ok") {
    stats.status = "failed";
    stats.message = check;
  }
  steppers.finish(stats);
  stats.end_time = stats.status == "interrupted" ? written : t;
  stats.slack.finish(t);
  stats.rhs_evaluations += rig.sys().rhs_evaluations;
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  rig.flush();
  return stats;
}

}  // namespace towsim::run
