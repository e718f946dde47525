#include "towsim/scenario/compile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "checks.hpp"
#include "reader.hpp"
#include "scalar.hpp"

namespace towsim::scenario {
namespace {

constexpr double kMaxSteps = 1e12;   // duration / time_step
constexpr double kMaxSamples = 1e9;  // duration / output_interval

/// simulation.threads as Simulation::threads: auto -> 0, an integer >= 1
/// (at most INT_MAX: more than 2 run as 2), anything else -> -1.
int threads_of(const std::string& text) {
  if (text == "auto") return 0;
  const auto v = scalar_to_integer(text);
  if (!v || *v < 1) return -1;
  return static_cast<int>(std::min<long long>(*v, std::numeric_limits<int>::max()));
}

void check_environment(const EnvironmentSpec& e, Diagnostics& d) {
  check_non_negative(e.water_density, d);
  check_non_negative(e.gravity, d);
  for (const auto& row : e.current)
    if (row.values[0] < 0)
      d.error(row.where.loc, row.where.path, "depth must be >= 0 (got " + fmt_num(row.values[0]) + ")");
  check_increasing(e.current, "depths", d);
}

/// Report `step` when duration / step exceeds `most` (counts that would
/// overflow, or a step that vanishes next to the simulated time).
/// A step left to its default is reported at the duration, under its own key.
void check_count(const Field<double>& duration, const Field<double>& step, const std::string& key, double most,
                 Diagnostics& d) {
  if (!(duration.value > 0 && step.value > 0)) return;  // reported by check_positive
  if (!(duration.value / step.value > most)) return;
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g", most);
  const std::string problem = "too small for the duration (duration / " + key + " is above " + limit;
  if (step.given)
    d.error(step.where.loc, step.where.path, problem + ")");
  else
    d.error(duration.where.loc, "simulation." + key, problem + "; default " + fmt_num(step.value) + ")");
}

void check_simulation(const SimulationSpec& s, Diagnostics& d) {
  check_positive(s.duration, d);
  check_positive(s.time_step, d);
  check_positive(s.tolerance, d);
  check_positive(s.max_step, d);
  check_positive(s.output_interval, d);
  check_count(s.duration, s.time_step, "time_step", kMaxSteps, d);
  check_count(s.duration, s.output_interval, "output_interval", kMaxSamples, d);
  // The linearly implicit method's stage solve is the O(n) recursion of the default formulation.
  if (s.integrator.value == "rosenbrock" && s.formulation.value == "paper")
    d.error(s.integrator.where.loc, s.integrator.where.path,
            "rosenbrock needs formulation: default (its stage solves use the O(n) recursion)");
  if (s.threads.given && threads_of(s.threads.value) < 0)
    d.error(s.threads.where.loc, s.threads.where.path,
            "expected an integer >= 1 or auto (got '" + s.threads.value + "')");
}

/// Rules between `initial` and `tow`: a steady start takes its velocity from
/// the tow's imposed motion, so it needs tow.mode: motion.
void check_initial(const InitialSpec& init, const TowSpec& tow, Diagnostics& d) {
  if (init.kind.given && init.kind.value == "steady" && tow.mode.value == "force")
    d.error(init.kind.where.loc, init.kind.where.path,
            "steady needs tow.mode: motion (the steady velocity comes from the tow's motion; tow.mode is force)");
}

/// Rules between depth controllers and the simulation: the default
/// formulation carries their state; a fixed RK4 step must resolve the servo.
void check_controls(const ScenarioSpec& s, Diagnostics& d) {
  std::vector<const BodySpec*> bodies{&s.body};
  for (const BodySpec& b : s.cable.inline_bodies) bodies.push_back(&b);
  const SimulationSpec& sim = s.simulation;
  for (const BodySpec* b : bodies) {
    if (!b->present) continue;
    for (const SurfaceSpec& surf : b->surfaces) {
      const DepthControlSpec& c = surf.depth_control;
      if (!c.present) continue;
      if (sim.formulation.value == "paper") {
        d.error(sim.formulation.where.loc, sim.formulation.where.path,
                "the paper formulation has no depth controller (use formulation: default)");
        return;
      }
      const double tau = c.servo_time_constant.value;
      if (sim.integrator.value == "rk4" && tau > 0 && sim.time_step.value > 2 * tau)
        d.error(c.servo_time_constant.given ? c.servo_time_constant.where.loc : c.where.loc,
                join_path(c.where.path, "servo_time_constant"),
                "must be >= simulation.time_step / 2 with integrator rk4 (got " + fmt_num(tau) + " s, time step " +
                    fmt_num(sim.time_step.value) + " s: the servo would be unstable)");
    }
  }
}

Fluid build_fluid(const EnvironmentSpec& e) {
  Fluid f;
  f.rho = e.water_density.value;
  f.g = e.gravity.value;
  for (const auto& row : e.current) {
    f.current_depth.push_back(row.values[0]);
    f.current_velocity.emplace_back(row.values[1], row.values[2], row.values[3]);
  }
  return f;
}

Initial build_initial(const InitialSpec& s) {
  Initial init;
  if (s.kind.value == "steady") init.kind = Initial::Kind::Steady;
  if (s.kind.value == "direction") {
    init.kind = Initial::Kind::Direction;
    init.direction = s.direction.value.normalized();
  }
  return init;
}

Simulation build_simulation(const SimulationSpec& s, bool winch) {
  Simulation sim;
  sim.duration = s.duration.value;
  sim.time_step = s.time_step.value;
  sim.output_interval = s.output_interval.value;
  sim.integrator = integrator_of(s.integrator.value);
  sim.tolerance = s.tolerance.value;
  // rosenbrock (L-stable, steps set by accuracy) is not bounded by the
  // default max_step; with a winch (events detected after each step) it is.
  const bool unbounded = sim.integrator == Integrator::Rosenbrock && !s.max_step.given && !winch;
  sim.max_step = unbounded ? std::numeric_limits<double>::infinity() : s.max_step.value;
  sim.formulation = s.formulation.value == "paper" ? Formulation::Paper : Formulation::Default;
  sim.write_nodes = s.write_nodes.value;
  sim.threads = threads_of(s.threads.value);
  return sim;
}

/// Bodies whose derived volume or mass overflow (a sphere of radius 1e200):
/// valid numbers each, but no run could use them.
void check_finite_bodies(const ScenarioSpec& spec, const Model& m, Diagnostics& d) {
  std::vector<const BodySpec*> specs;  // in the model's body order: in-line bodies, then the end body
  for (const BodySpec& b : spec.cable.inline_bodies) specs.push_back(&b);
  if (spec.body.present) specs.push_back(&spec.body);
  for (std::size_t i = 0; i < m.bodies.size() && i < specs.size(); ++i) {
    const Body& b = m.bodies[i];
    const Where& w = specs[i]->where;
    if (!std::isfinite(b.displaced_volume))
      d.error(w.loc, w.path,
              "the displaced volume is not finite (got " + fmt_num(b.displaced_volume) +
                  " m^3: the sizes overflow double precision)");
    else if (!b.total_mass.allFinite())
      d.error(w.loc, w.path, "the mass matrix is not finite (the masses or sizes overflow double precision)");
  }
}

}  // namespace

std::optional<Model> compile(const ScenarioSpec& spec, Diagnostics& diags) {
  check_environment(spec.environment, diags);
  check_cable(spec.cable, spec.body, spec.simulation, diags);
  if (spec.body.present) check_body(spec.body, diags);
  check_tow(spec.tow, diags);
  check_nonzero(spec.initial.direction, diags);
  check_initial(spec.initial, spec.tow, diags);
  check_simulation(spec.simulation, diags);
  check_controls(spec, diags);
  check_waves(spec, diags);
  if (spec.winch.present) check_winch(spec, diags);
  check_seabed(spec, diags);
  if (!diags.ok()) return std::nullopt;
  Model m;
  m.name = spec.name;
  m.fluid = build_fluid(spec.environment);
  build_chain(spec.cable, spec.body, m);
  m.tow = build_tow(spec.tow);
  if (spec.winch.present) {
    build_winch(spec.winch, m);
    if (!check_winch_model(spec.winch, m, diags)) return std::nullopt;
    check_winch_rk4(spec, m, diags);
    if (!diags.ok()) return std::nullopt;
  }
  check_finite_bodies(spec, m, diags);
  if (!diags.ok()) return std::nullopt;
  m.initial = build_initial(spec.initial);
  m.sim = build_simulation(spec.simulation, spec.winch.present);
  build_seabed(spec.environment.seabed, m);
  attach_waves(spec, m);
  check_seabed_start(spec, m, diags);
  if (!diags.ok()) return std::nullopt;
  return m;
}

}  // namespace towsim::scenario
