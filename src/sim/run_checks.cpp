// Checks of a run's state after each step and at each sample, shared by
// a chain's run and a network's (src/sim/run_checks.hpp).
#include "run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "towsim/hydro/loads.hpp"

namespace towsim::run {

namespace {

constexpr double kRad2Deg = 180.0 / M_PI;
constexpr double kMaxRate = 1e4;  // an angular velocity beyond this [rad/s] means divergence
// A slack elastic element shorter than this fraction of its length [-]: the
// straight-rod model of a folded cable has broken down (l -> 0 is singular).
constexpr double kMinLength = 0.05;

}  // namespace

/// After an accepted step at t: slack episodes and peak tensions of an elastic cable.
void track_elastic(const Model& model, const System& sys, const StateVector& y, double t, RunStats& stats) {
  if (!lengths_in_state(model)) return;
  PhysicalState s = sys.physical(y);
  double top_unstretched = 0;  // L_1 when the winch sets it [m]
  if (elastic_winch(model)) {
    top_unstretched = s.top_unstretched;
    // The winch's top element at the strain l_1/L_1 of the model's L:
    // equivalent length and rate (its pay-out's damping term left out).
    const double scale = model.cable.elements[0].length / s.top_unstretched;
    s.length[0] *= scale;
    s.length_rate[0] *= scale;
  }
  stats.slack.update(model, s.length, s.length_rate, t, top_unstretched);
}

/// RK4 only: compare the step with the stability limit at this sample. Beyond
/// 0.9 times it (the estimate is within 10 % of the measured limits): a
/// warning (once); beyond 1.5 times it: an error text (the run stops).
std::string check_rk4_step(const Model& model, const Workspace& ws, double t, RunStats& stats) {
  if (model.sim.integrator != Integrator::RK4) return {};
  int k = 0;
  double T = 0;
  const double lim = rk4_step_limit(model, ws, t, &k, &T);
  if (!(lim > 0) || std::isinf(lim)) return {};
  if (stats.rk4_step_limit < 0 || lim < stats.rk4_step_limit) stats.rk4_step_limit = lim;
  const double h = model.sim.time_step;
  if (h <= 0.9 * lim) return {};
  // The estimate is within 10 % of the measured limit (tests): 1.5 times
  // it is clearly unstable.
  const bool refuse = h > 1.5 * lim;
  std::ostringstream os;
  os << (refuse ? "refused: " : "") << "rk4 time_step " << h << " s is above " << (refuse ? "1.5" : "0.9")
     << " times the estimated stability limit " << lim << " s at t = " << t << " s (element " << k << ", tension " << T
     << " N): " << (refuse ? "the run would diverge or be wrong" : "forces may be wrong")
     << "; use simulation.time_step <= " << 0.9 * lim << " or simulation.integrator: rosenbrock";
  if (refuse) return os.str();
  if (stats.warnings.empty() || stats.warnings.back().rfind("rk4 time_step", 0) != 0)
    stats.warnings.push_back(os.str());
  return {};
}

/// The first time each lifting surface is seen stalled (|angle of attack|
/// beyond its stall angle) at an output sample: a warning with the time.
void check_stall(const Model& model, const Workspace& ws, double t, RunStats& stats) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const Body& body = model.bodies[b];
    for (std::size_t j = 0; j < body.surfaces.size(); ++j) {
      const LiftingSurface& ls = body.surfaces[j];
      const SurfaceFlow f = surface_flow(model.fluid, ls, current_deflection(body, j, ws.body[b], t), t, ws.body[b]);
      if (f.speed < 1e-6 || std::abs(f.alpha) <= ls.stall_angle) continue;
      // A body by its name (an in-line body, a network's bodies), a chain's end body ("body") as "the body".
      const bool named = body.inline_body || body.name != "body";
      const std::string who = (named ? "body " + body.name + "'s" : std::string("the body's")) + " surface " +
                              std::to_string(j);
      if (std::any_of(stats.warnings.begin(), stats.warnings.end(),
                      [&](const std::string& w) { return w.rfind(who + " stalled", 0) == 0; }))
        continue;
      std::ostringstream os;
      os << who << " stalled at t = " << t << " s: angle of attack " << f.alpha * kRad2Deg
         << " deg beyond its stall angle " << ls.stall_angle * kRad2Deg
         << " deg (its lift falls off; check the body's trim, link point and deflections)";
      stats.warnings.push_back(os.str());
    }
  }
}

/// The first output time the cable (a joint below the tow point: a vessel's
/// tow point may stand above the water) or a body is above the mean water
/// surface z = 0: a warning, once per part. The water's loads act there as
/// under water; such results are not physical (docs/theory.md §3).
void check_surface(const Model& model, const Sample& s, RunStats& stats) {
  const auto warn = [&stats, &s](const std::string& who, const std::string& where, double z) {
    if (std::any_of(stats.warnings.begin(), stats.warnings.end(),
                    [&](const std::string& w) { return w.rfind(who + " rose above", 0) == 0; }))
      return;
    std::ostringstream os;
    os << who << " rose above the water surface at t = " << s.t << " s (" << where << "z = " << z
       << " m): the water's loads (buoyancy, drag, added mass) still act there, so results above z = 0 are not "
          "physical";
    stats.warnings.push_back(os.str());
  };
  for (std::size_t k = 1; k < s.node_pos.size(); ++k)
    if (s.node_pos[k].z() > 0) {
      warn("the cable", "joint " + std::to_string(k) + " at ", s.node_pos[k].z());
      break;
    }
  for (std::size_t b = 0; b < model.bodies.size() && b < s.bodies.size(); ++b)
    if (s.bodies[b].pos.z() > 0)
      warn(model.bodies[b].inline_body ? "body " + model.bodies[b].name : std::string("the body"), "",
           s.bodies[b].pos.z());
}

std::string check_finite(const System& sys, const StateVector& y) {
  for (std::size_t i = 0; i < y.size(); ++i)
    if (!std::isfinite(y[i])) return sys.describe(i) + ": state is not finite (NaN or infinity)";
  return {};
}

std::string check_chain(const Model& model, const PhysicalState& s) {
  for (int k = 0; k < model.cable.n(); ++k)
    if (s.w[k].norm() > kMaxRate)
      return "element " + std::to_string(k + 1) + ": angular velocity diverged (" + std::to_string(s.w[k].norm()) +
             " rad/s); reduce simulation.time_step or use an adaptive integrator";
  for (std::size_t k = 0; k < s.length.size(); ++k) {
    // Unstretched length: the model's, or the winch's paid-out L_1.
    const double L = k == 0 && elastic_winch(model) ? s.top_unstretched : model.cable.elements[k].length;
    if (is_elastic(model.cable.elements[k]) && !(s.length[k] > kMinLength * L))
      return "element " + std::to_string(k + 1) + ": a slack element shortened to " +
             std::to_string(s.length[k] / L * 100) +
             " % of its length (the cable folded on itself); reduce simulation.time_step or refine the cable";
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (s.bodies[b].w.norm() > kMaxRate)
      return "body " + model.bodies[b].name +
             ": angular velocity diverged; reduce simulation.time_step or use an adaptive integrator";
  return {};
}

/// Absolute force scale of the force error norm: the chain's apparent weight [N].
double force_scale(const Model& model) {
  double w = 0;
  for (const Element& el : model.cable.elements) w += std::abs(el.weight);
  for (const Body& b : model.bodies) w += std::abs(b.mass - model.fluid.rho * b.displaced_volume) * model.fluid.g;
  for (const Attachment& a : model.cable.attachments)
    w += std::abs(a.mass - model.fluid.rho * a.volume) * model.fluid.g;
  return std::max(w, 1.0);
}

void tolerance_warnings(const Simulation& sim, RunStats& stats) {
  // A loose tolerance passes large errors as "ok" (dopri5 at 0.1: a peak tension 6.5 times the converged one).
  constexpr double kLooseTolerance = 1e-2;     // [-]
  constexpr double kAccurateTolerance = 1e-4;  // the largest for 0.1 % of the peak tow force [-]
  if (sim.integrator != Integrator::RK4 && sim.tolerance > kLooseTolerance) {
    std::ostringstream os;
    os << "simulation.tolerance " << sim.tolerance << " is loose (above " << kLooseTolerance
       << "): the results may be far from converged; check them at a tolerance 10 times smaller";
    stats.warnings.push_back(os.str());
  } else if (sim.integrator != Integrator::RK4 && sim.tolerance > kAccurateTolerance) {
    // Above it the time step's share of the tow force's error may pass 0.1 % of its peak
    // (measured, rosenbrock on the shipped examples: 4.8e-5 to 7.8e-4 at 1e-4, up to 2.5e-3 at 3e-4).
    std::ostringstream os;
    os << "simulation.tolerance " << sim.tolerance << " is above " << kAccurateTolerance
       << ": the time step's error of the tow force may pass 0.1 % of its peak (up to 9 times the tolerance on "
          "the shipped examples at 3e-4); "
       << kAccurateTolerance << " (the default) or less keeps it within 0.1 %";
    stats.warnings.push_back(os.str());
  }
}

void sample_checks(const Model& model, const PhysicalState& s, const Workspace& ws, double t, RunStats& stats,
                   Sample& out, std::string* err) {
  if (err) *err = check_rk4_step(model, ws, t, stats);
  check_stall(model, ws, t, stats);
  make_sample(model, s, ws, t, out);
  check_surface(model, out, stats);
  for (std::size_t k = 0; k < model.cable.elements.size(); ++k) {
    const int b = ws.body_at[k + 1];
    const Vec3& bottom = b >= 0 ? ws.body[static_cast<std::size_t>(b)].Q : ws.P[k + 1];
    const double L = ws.L[k];  // the state's length (winch, elastic)
    stats.max_element_drift = std::max(stats.max_element_drift, std::abs((bottom - ws.P[k]).norm() / L - 1));
  }
}

}  // namespace towsim::run
