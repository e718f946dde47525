// The run loop: integrate, land on output times, check the state, write samples.
#include "towsim/sim/simulate.hpp"

#include <boost/numeric/odeint.hpp>
#include <chrono>
#include <cmath>
#include <sstream>

#include "towsim/integrators/system.hpp"
#include "towsim/sim/statics.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim {

namespace odeint = boost::numeric::odeint;

namespace {

constexpr double kRad2Deg = 180.0 / M_PI;
constexpr double kMaxRate = 1e4;  // an angular velocity beyond this [rad/s] means divergence

/// Output sample of state y at time t; tracks the element length drift.
Sample sample_of(const Model& model, System& sys, const StateVector& y, double t, RunStats& stats) {
  const Workspace& ws = sys.evaluate(y, t);
  Sample out = make_sample(model, sys.physical(y), ws, t);
  for (std::size_t k = 0; k < model.cable.elements.size(); ++k) {
    const int b = ws.body_at[k + 1];
    const Vec3& bottom = b >= 0 ? ws.body[static_cast<std::size_t>(b)].Q : ws.P[k + 1];
    const double L = model.cable.elements[k].length;
    stats.max_element_drift = std::max(stats.max_element_drift, std::abs((bottom - ws.P[k]).norm() / L - 1));
  }
  return out;
}

}  // namespace

Sample make_sample(const Model& model, const PhysicalState& s, const Workspace& ws, double t) {
  Sample out;
  out.t = t;
  out.tow_pos = ws.P.front();
  out.tow_vel = ws.vP.front();
  out.tow_force = ws.acc.tow_force;
  // A node: position, velocity, force through it onto the part below, and
  // that force along the adjacent element e (tension pulls the part below
  // back along -e).
  auto node = [&out](const Vec3& p, const Vec3& v, const Vec3& f, const Vec3& e) {
    out.node_pos.push_back(p);
    out.node_vel.push_back(v);
    out.tension.push_back(f.norm());
    out.axial.push_back(-f.dot(e));
  };
  const std::size_t n = model.cable.elements.size();
  for (std::size_t k = 0; k <= n; ++k) {
    const int b = k == 0 ? -1 : ws.body_at[k];
    const Vec3& e_above = s.e[k == 0 ? 0 : k - 1];
    if (b >= 0 && model.bodies[static_cast<std::size_t>(b)].inline_body) {
      const BodyWork& bw = ws.body[static_cast<std::size_t>(b)];
      node(bw.Q, bw.vQ, ws.acc.link_force[static_cast<std::size_t>(b)], e_above);
      node(ws.P[k], ws.vP[k], ws.acc.joint_force[k], s.e[k]);
    } else {
      node(ws.P[k], ws.vP[k], ws.acc.joint_force[k], e_above);
    }
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyWork& bw = ws.body[b];
    out.bodies.push_back({bw.O, bw.vO, roll_pitch_yaw(s.bodies[b].q) * kRad2Deg, bw.w, ws.acc.link_force[b],
                          ws.acc.lower_link_force[b]});
  }
  if (has_sea(model)) sea_sample(model, t, out);
  return out;
}

namespace {

/// Empty if y is sound; else what went wrong and where.
std::string check_state(const Model& model, const System& sys, const StateVector& y) {
  for (std::size_t i = 0; i < y.size(); ++i)
    if (!std::isfinite(y[i])) return sys.describe(i) + ": state is not finite (NaN or infinity)";
  const PhysicalState s = sys.physical(y);
  for (int k = 0; k < model.cable.n(); ++k)
    if (s.w[k].norm() > kMaxRate)
      return "element " + std::to_string(k + 1) + ": angular velocity diverged (" + std::to_string(s.w[k].norm()) +
             " rad/s); reduce simulation.time_step or use an adaptive integrator";
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (s.bodies[b].w.norm() > kMaxRate)
      return "body " + model.bodies[b].name +
             ": angular velocity diverged; reduce simulation.time_step or use an adaptive integrator";
  return {};
}

/// Advance y from t to `target` (an output time), by fixed RK4 steps or
/// adaptive steps that land on `target`. Returns an error text or empty.
template <class Stepper>
std::string advance_fixed(const Model& model, System& sys, Stepper& rk, StateVector& y, double& t, double target,
                          RunStats& stats) {
  while (t < target - 1e-12 * std::max(1.0, target)) {
    const double h = std::min(model.sim.time_step, target - t);
    sys.set_window(t, t + h);
    rk.do_step(std::ref(sys), y, t, h);
    t = (target - (t + h) < 1e-12 * std::max(1.0, target)) ? target : t + h;
    sys.project(y, t);
    ++stats.steps;
    if (auto err = check_state(model, sys, y); !err.empty()) return err;
  }
  return {};
}

template <class Controlled>
std::string advance_adaptive(const Model& model, System& sys, Controlled& ctrl, StateVector& y, double& t,
                             double target, double& h, RunStats& stats) {
  const double h_min = 1e-12 * std::max(1.0, model.sim.duration);
  while (t < target - 1e-12 * std::max(1.0, target)) {
    const double h_try = std::min({h, model.sim.max_step, target - t});
    double dt = h_try;
    sys.set_window(t, t + h_try);
    const auto res = ctrl.try_step(std::ref(sys), y, t, dt);  // t, dt updated
    if (res == odeint::fail) {
      ++stats.rejected_steps;
      h = dt;
      if (h < h_min) {
        std::ostringstream os;
        os << "step size collapsed below " << h_min << " s (tolerance " << model.sim.tolerance
           << " cannot be met)";
        return os.str();
      }
      continue;
    }
    // Keep the controller's proposal unless this step was shortened to land.
    if (h_try >= h || dt > h) h = dt;
    if (std::abs(target - t) < 1e-12 * std::max(1.0, target)) t = target;
    sys.project(y, t);
    if constexpr (requires { ctrl.reset(); }) ctrl.reset();  // projection changed y: no stale FSAL derivative
    ++stats.steps;
    if (auto err = check_state(model, sys, y); !err.empty()) return err;
  }
  return {};
}

}  // namespace

RunStats simulate(const Model& model, OutputSink& sink, const ProgressFn& progress, const volatile int* stop_flag) {
  RunStats stats;
  const auto wall0 = std::chrono::steady_clock::now();
  auto sys = make_system(model);
  // A steady start can fail or be interrupted: the run then ends before t = 0.
  PhysicalState s0;
  if (model.initial.kind == Initial::Kind::Steady) {
    const StaticsResult st = steady_state(model, stop_flag);
    if (!st.converged) {
      stats.status = st.interrupted ? "interrupted" : "failed";
      stats.message = st.interrupted ? "interrupted by signal while solving the steady initial state"
                                     : "initial: steady: " + st.message;
      stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      sink.flush();
      return stats;
    }
    s0 = st.state;
  } else {
    s0 = initial_state(model);
  }
  StateVector y = sys->initial(s0, 0.0);
  if (model.initial.kind != Initial::Kind::Steady) sys->apply_tow_jump(y, 0.0);  // at rest, tow at speed
  sys->project(y, 0.0);
  double t = 0;
  sink.write(sample_of(model, *sys, y, t, stats));

  odeint::runge_kutta4<StateVector> rk4;
  auto dopri = odeint::make_controlled(model.sim.tolerance, model.sim.tolerance,
                                       odeint::runge_kutta_dopri5<StateVector>());
  auto cashkarp = odeint::make_controlled(model.sim.tolerance, model.sim.tolerance,
                                          odeint::runge_kutta_cash_karp54<StateVector>());
  double h = model.sim.time_step;
  const double T = model.sim.duration, dT = model.sim.output_interval;
  const long n_out = static_cast<long>(std::ceil(T / dT - 1e-9));
  const std::vector<double> breaks = tow_breakpoints(model.tow);
  auto next_break = breaks.begin();
  for (long k = 1; k <= n_out; ++k) {
    if (stop_flag && *stop_flag) {
      stats.status = "interrupted";
      stats.message = "interrupted by signal at t = " + std::to_string(t) + " s";
      break;
    }
    const double out_time = std::min(T, static_cast<double>(k) * dT);
    std::string err;
    // Land on every breakpoint of the tow law up to the output time; where
    // the tow velocity jumps, give the chain its impulsive response.
    while (err.empty()) {
      const double eps = 1e-12 * std::max(1.0, t);
      while (next_break != breaks.end() && *next_break < t - eps) ++next_break;
      const bool at_break = next_break != breaks.end() && std::abs(*next_break - t) <= eps;
      if (at_break) {
        sys->apply_tow_jump(y, t);
        ++next_break;
      }
      if (t >= out_time - 1e-12 * std::max(1.0, out_time)) break;
      const double target = (next_break != breaks.end() && *next_break < out_time) ? *next_break : out_time;
      switch (model.sim.integrator) {
        case Integrator::RK4: err = advance_fixed(model, *sys, rk4, y, t, target, stats); break;
        case Integrator::DOPRI5: err = advance_adaptive(model, *sys, dopri, y, t, target, h, stats); break;
        case Integrator::CashKarp54: err = advance_adaptive(model, *sys, cashkarp, y, t, target, h, stats); break;
      }
    }
    if (!err.empty()) {
      std::ostringstream os;
      os << "numerical failure at t = " << t << " s: " << err;
      stats.status = "failed";
      stats.message = os.str();
      break;
    }
    sink.write(sample_of(model, *sys, y, t, stats));
    if (progress) progress(t / T);
  }
  stats.end_time = t;
  stats.rhs_evaluations = sys->rhs_evaluations;
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  sink.flush();
  return stats;
}

}  // namespace towsim
