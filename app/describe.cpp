// `towsim check`: the derived quantities of a compiled model.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>

#include "commands.hpp"
#include "describe_sea.hpp"
#include "towsim/dynamics/elastic.hpp"
#include "towsim/scenario/spec.hpp"
#include "towsim/sim/discretisation.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;
namespace {

std::string vec(const Vec3& v) { return "[" + fmt_num(v[0]) + ", " + fmt_num(v[1]) + ", " + fmt_num(v[2]) + "]"; }

/// One "  label   value" line.
void line(std::ostream& out, const std::string& label, const std::string& value) {
  out << "  " << label << std::string(label.size() < 28 ? 28 - label.size() : 1, ' ') << value << "\n";
}

/// "sinks", "floats" or "neutral" (|weight| below 1e-6 of the weight in air).
std::string sinks(double weight, double weight_in_air) {
  if (std::abs(weight) <= 1e-6 * std::abs(weight_in_air)) return "neutral";
  return weight > 0 ? "sinks" : "floats";
}

/// "1 sphere", "2 spheres".
std::string count(std::size_t n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

void describe_fluid(const Fluid& f, std::ostream& out) {
  out << "fluid\n";
  line(out, "water density", fmt_num(f.rho) + " kg/m^3" + (f.rho == 0 ? " (no fluid)" : ""));
  line(out, "gravity", fmt_num(f.g) + " m/s^2");
  if (!f.has_current()) {
    line(out, "current", "none");
    return;
  }
  for (std::size_t i = 0; i < f.current_velocity.size(); ++i)
    line(out, i == 0 ? "current" : "",
         vec(f.current_velocity[i]) + " m/s at depth " + fmt_num(f.current_depth[i]) + " m");
}

/// The seabed: depth (or its table) and contact law.
void describe_seabed(const Model& m, std::ostream& out) {
  if (!m.seabed) return;
  const Seabed& sb = *m.seabed;
  out << "seabed\n";
  if (sb.depth.size() == 1)
    line(out, "depth", fmt_num(sb.depth[0]) + " m (flat)");
  else
    for (std::size_t i = 0; i < sb.depth.size(); ++i)
      line(out, i == 0 ? "depth" : "", fmt_num(sb.depth[i]) + " m at x = " + fmt_num(sb.x[i]) + " m");
  line(out, "stiffness", fmt_num(sb.stiffness) + " N/m per m in contact");
  line(out, "damping", fmt_num(sb.damping) + " N s/m per m in contact");
  line(out, "friction", fmt_num(sb.friction) + " (smoothed below " + fmt_num(sb.slip_speed) + " m/s)");
  line(out, "cable contact",
       sb.along_elements ? "along each element (contact: elements)" : "at the joints (contact: joints)");
}

/// The properties of one run of equal elements (e: its first element).
void describe_elements(const Cable& c, const Section* sec, const Element& e, int count, std::ostream& out) {
  line(out, "element length", fmt_num(e.length) + " m");
  line(out, "diameter", fmt_num(e.diameter) + " m");
  line(out, "mass in air",
       fmt_num(e.mass / e.length) + " kg/m, " + fmt_num(e.mass) + " kg per element, " + fmt_num(e.mass * count) +
           " kg in all");
  line(out, "apparent weight in water",
       fmt_num(e.weight / e.length) + " N/m, " + fmt_num(e.weight) + " N per element (" +
           sinks(e.weight, e.mass * 9.81) + ")");
  line(out, "added mass (normal)",
       fmt_num(e.added_mass / e.length) + " kg/m, " + fmt_num(e.added_mass) + " kg per element (" +
           (c.added_mass_model == AddedMassModel::Morison ? "morison" : "ideal_fluid") + ")");
  line(out, "normal drag factor", "1/2 rho Cd D = " + fmt_num(e.drag_factor / e.length) + " kg/m^2");
  // The section's breaking load, in its own block.
  if (sec != nullptr && sec->breaking_load > 0) line(out, "breaking load", fmt_num(sec->breaking_load) + " N");
  // Faired cable: a table replaces a default law.
  auto table = [](const LoadingTable& t, const char* f) {
    return std::string("table ") + f + "(phi), " + std::to_string(t.f.size()) + " rows, times 1/2 rho Cd D |u|^2";
  };
  if (sec != nullptr && !sec->normal_loading.empty()) line(out, "normal loading", table(sec->normal_loading, "fn"));
  if (sec != nullptr && !sec->tangential_loading.empty()) {
    line(out, "tangential drag", table(sec->tangential_loading, "ft"));
    return;
  }
  line(out, "tangential drag",
       std::string(c.tangential_law == TangentialLaw::Skin ? "skin: 1/2 rho pi D Ct" : "pode: 1/2 rho Cd f D") + " = " +
           fmt_num(e.friction_factor / e.length) + " kg/m^2");
  if (is_elastic(e))
    line(out, "axial stiffness",
         "EA = " + fmt_num(e.axial_stiffness) + " N, damping " + fmt_num(e.axial_damping) + " N s; wave speed " +
             fmt_num(axial_wave_speed(e)) + " m/s, rk4 step <= " + fmt_num(rk4_axial_step_limit(e)) + " s");
  else
    line(out, "axial stiffness", "inextensible");
  // Bending: the joint spring between two such elements (only when given).
  if (e.bending_stiffness > 0)
    line(out, "bending stiffness",
         "EI = " + fmt_num(e.bending_stiffness) +
             " N m^2; joint spring EI/L = " + fmt_num(e.bending_stiffness / e.length) + " N m/rad");
}

/// Arc length from the tow point to joint k [m].
double arc_length(const Cable& c, int k) {
  double s = 0;
  for (int i = 0; i < k; ++i) s += c.elements[static_cast<std::size_t>(i)].length;
  return s;
}

void describe_cable(const Cable& c, std::ostream& out) {
  const double total = c.total_length();
  out << "cable: " << fmt_num(total) << " m in " << c.n() << " elements\n";
  if (c.sections.size() <= 1) {
    describe_elements(c, c.sections.empty() ? nullptr : &c.sections.front(), c.elements.front(), c.n(), out);
  } else {
    for (const Section& s : c.sections) {
      // A default name is already "section <i>"; a given one is prefixed.
      out << (s.name.rfind("section ", 0) == 0 ? "" : "section ") << s.name << ": " << fmt_num(s.length) << " m in "
          << s.elements << " elements, from " << fmt_num(arc_length(c, s.first_element)) << " m\n";
      describe_elements(c, &s, c.elements[static_cast<std::size_t>(s.first_element)], s.elements, out);
    }
  }
  for (const Attachment& a : c.attachments)
    line(out, "attachment at " + fmt_num(a.at) + " m",
         "at joint " + std::to_string(a.joint) + " (" + fmt_num(arc_length(c, a.joint)) + " m): mass " +
             fmt_num(a.mass) + " kg, volume " + fmt_num(a.volume) + " m^3, CdA " + fmt_num(a.drag_area) +
             " m^2, added mass " + fmt_num(a.added_mass) + " kg");
}

void describe_body(const Body& b, const Cable& c, const Fluid& f, std::ostream& out, bool named = false) {
  const double weight = (b.mass - f.rho * b.displaced_volume) * f.g;
  if (b.inline_body)
    out << "in-line body " << b.name << ": at joint " << b.joint << " (" << fmt_num(arc_length(c, b.joint)) << " m)\n";
  else
    out << (named ? "body " + b.name + ": at the line's end" : std::string("body")) << "\n";
  line(out, "mass", fmt_num(b.mass) + " kg");
  line(out, "displaced volume", fmt_num(b.displaced_volume) + " m^3");
  line(out, "apparent weight in water", fmt_num(weight) + " N (" + sinks(weight, b.mass * f.g) + ")");
  line(out, "centre of gravity", vec(b.cg) + " m (body axes)");
  line(out, "centre of buoyancy", vec(b.buoyancy_center) + " m (body axes)");
  line(out, "link point Q", vec(b.link_point) + " m (body axes)");
  if (b.inline_body) line(out, "lower link point Q2", vec(b.lower_link_point) + " m (body axes)");
  line(out, "load models",
       count(b.spheres.size(), "sphere") + ", " + count(b.cylinders.size(), "cylinder") + ", " +
           count(b.surfaces.size(), "surface"));
  // Depth controllers (gains back in the keys' units, per degree).
  constexpr double deg = 180 / 3.14159265358979323846;
  for (std::size_t j = 0; j < b.surfaces.size(); ++j)
    if (const auto& c = b.surfaces[j].depth_control)
      line(out, "depth control (surface " + std::to_string(j) + ")",
           "target " + fmt_num(c->target_depth) + " m; kp " + fmt_num(c->kp * deg) + " deg/m, ki " +
               fmt_num(c->ki * deg) + " deg/(m s), kd " + fmt_num(c->kd * deg) + " deg s/m; limits +-" +
               fmt_num(c->max_deflection * deg) + " deg, " + fmt_num(c->max_rate * deg) + " deg/s; servo " +
               fmt_num(c->servo_time_constant) + " s, anti-windup " + fmt_num(c->tracking_time) + " s");
}

std::string piece_text(const Ramp& p) {
  return "ramp along " + vec(p.direction) + " to " + fmt_num(p.speed) + " m/s in " + fmt_num(p.ramp_time) + " s";
}
std::string piece_text(const Heave& p) {
  return "heave " + fmt_num(p.amplitude) + " m, period " + fmt_num(p.period) + " s, from t = " + fmt_num(p.start_time) +
         " s";
}
std::string piece_text(const Turn& p) {
  std::string s = std::string("turn to ") + (p.port ? "port" : "starboard") + ", radius " + fmt_num(p.radius) +
                  " m, from t = " + fmt_num(p.start_time) + " s";
  if (std::isfinite(p.angle)) s += ", by " + fmt_num(p.angle * 180 / std::numbers::pi) + " deg";
  return s;
}
std::string piece_text(const SpeedChange& p) {
  return "speed change to " + fmt_num(p.speed) + " m/s over " + fmt_num(p.ramp_time) +
         " s, from t = " + fmt_num(p.start_time) + " s";
}
std::string piece_text(const Track& p) {
  return "track of " + std::to_string(p.time.size()) + " points, t = " + fmt_num(p.time.front()) + " to " +
         fmt_num(p.time.back()) + " s";
}

void describe_tow(const Tow& t, std::ostream& out) {
  if (t.mode == Tow::Mode::Force) {
    out << "tow: imposed force, starting at " << vec(t.start) << " m\n";
    if (t.force_value.size() == 1)
      line(out, "force", vec(t.force_value[0]) + " N, constant");
    else
      line(out, "force",
           "table of " + std::to_string(t.force_time.size()) + " rows, t = " + fmt_num(t.force_time.front()) + " to " +
               fmt_num(t.force_time.back()) + " s");
    return;
  }
  out << "tow: imposed motion from " << vec(t.start) << " m\n";
  if (t.pieces.empty()) line(out, "motion", "none (fixed tow point)");
  for (const auto& p : t.pieces) line(out, "motion", std::visit([](const auto& law) { return piece_text(law); }, p));
}

void describe_winch(const Winch& w, std::ostream& out) {
  if (!w.active()) return;
  if (w.mode == Winch::Mode::Tension) {
    out << "winch: constant tension " << fmt_num(w.tension) << " N\n";
    line(out, "drum", fmt_num(w.drum_inertia) + " kg at the rim, damping " + fmt_num(w.damping) + " N s/m");
  } else {
    const WinchKinematics end = winch_kinematics(w, w.schedule.back().t0);
    out << "winch: imposed length, " << w.schedule.size() << " pieces, " << fmt_num(end.length)
        << " m from t = " << fmt_num(w.schedule.back().t0) << " s\n";
  }
  const auto lim = [](double v, const char* unit) { return std::isfinite(v) ? fmt_num(v) + " " + unit : "none"; };
  line(out, "length limits", fmt_num(w.min_length) + " to " + lim(w.max_length, "m"));
  line(out, "speed limit", lim(w.max_speed, "m/s"));
  line(out, "elements",
       fmt_num(w.nominal_length) + " m, split above " + fmt_num(w.split_at * w.nominal_length) + " m, removed below " +
           fmt_num(w.remove_at * w.nominal_length) + " m");
  if (w.rating > 0) line(out, "rating", fmt_num(w.rating) + " N");
}

void describe_run(const Model& m, std::ostream& out) {
  const auto& s = m.sim;
  const char* init[] = {"hanging", "steady", "direction"};
  out << "initial: " << init[static_cast<int>(m.initial.kind)];
  if (m.initial.kind == Initial::Kind::Direction) out << " " << vec(m.initial.direction);
  out << "\nsimulation\n";
  line(out, "integrator",
       std::string(integrator_key(s.integrator)) +
           (s.integrator == Integrator::RK4
                ? ""
                : ", tolerance " + fmt_num(s.tolerance) +
                      (std::isfinite(s.max_step) ? ", max step " + fmt_num(s.max_step) + " s"
                                                 : std::string(", no max step"))));
  line(out, "formulation", s.formulation == Formulation::Paper ? "paper" : "default");
  line(out, s.integrator == Integrator::RK4 ? "time step" : "first step", fmt_num(s.time_step) + " s");
  line(out, "duration", fmt_num(s.duration) + " s");
  const long samples = static_cast<long>(std::floor(s.duration / s.output_interval + 1e-9)) + 1;
  line(out, "output interval",
       fmt_num(s.output_interval) + " s (" + std::to_string(samples) + " samples" +
           (s.write_nodes ? ", with nodes.csv)" : ", no nodes.csv)"));
}

/// The element count's share of the tow tension's error and the count for
/// kAdvisedAccuracy (two steady tows: include/towsim/sim/discretisation.hpp).
void describe_accuracy(const Model& m, std::ostream& out) {
  constexpr int kCheckRefinement = 64;  // the advice's largest refinement of the cable [-]
  out << "accuracy\n";
  const DiscretisationEstimate d = estimate_discretisation_error(m);
  if (!d.available()) {
    line(out, "discretisation error", "no estimate: " + d.message);
    return;
  }
  char pct[32];
  std::snprintf(pct, sizeof pct, "%.2g %%", 100 * d.estimate);
  line(out, "discretisation error",
       std::string(pct) + " of the steady tow tension at " + fmt_num(d.speed) + " m/s (" + fmt_num(d.tension) + " N; " +
           fmt_num(d.refined_tension) + " N with " + std::to_string(2 * d.elements) + " elements)");
  std::snprintf(pct, sizeof pct, "%.2g %%", 100 * kAdvisedAccuracy);
  const std::string label = "elements for " + std::string(pct) + " tension";
  const ElementAdvice a = advise_elements(m, d, kAdvisedAccuracy, kCheckRefinement);
  if (a.elements < 0) {
    line(out, label, "no advice: a steady tow on a refined cable did not converge");
  } else if (a.enough) {
    line(out, label, "the present " + std::to_string(d.elements) + " are enough");
  } else {
    std::string advice = (a.beyond ? "more than " : "about ") + std::to_string(a.elements);
    if (m.cable.sections.size() > 1)
      advice += " in all (each section's elements times " + fmt_num(std::ceil(100.0 * a.elements / d.elements) / 100) +
                ")";
    line(out, label, advice);
  }
  if (d.proxy) line(out, "basis", "the steady tow at the final speed, standing in for this run's unsteady conditions");
}

}  // namespace

void describe_model(const Model& m, std::ostream& out, bool accuracy) {
  out << "scenario " << m.name << ": valid\n";
  describe_fluid(m.fluid, out);
  describe_seabed(m, out);
  describe_cable(m.cable, out);
  for (const Body& b : m.bodies) describe_body(b, m.cable, m.fluid, out);
  if (!end_body(m)) out << "body: none (free cable end)\n";
  describe_tow(m.tow, out);
  describe_sea(m, out);
  describe_winch(m.winch, out);
  describe_run(m, out);
  if (accuracy) describe_accuracy(m, out);
}

void describe_network(const LoadedScenario& sc, std::ostream& out) {
  const Network& net = *sc.network;
  const TreeModel& tree = net.tree;
  const Model& first = net.settings();
  const std::size_t nl = tree.lines.size();
  out << "scenario " << net.name << ": valid (a network of " << count(nl, "line") << ", "
      << count(net.junctions.size(), "junction") << ", " << count(tree.loops.size(), "loop") << ")\n";
  describe_fluid(first.fluid, out);
  describe_seabed(first, out);
  describe_tow(first.tow, out);
  Model sea = first;  // the waves (once); the tow points are the lines'
  sea.tow.vessel.reset();
  describe_sea(sea, out);
  const VesselSpec& vs = sc.spec.vessel;
  const bool moving = vs.present && (vs.raos_given || vs.motions_given);
  out << "vessel\n";
  line(out, "motion",
       !moving         ? std::string("none (the tow points move with the tow law, turned to its course)")
       : vs.raos_given ? std::string("RAOs at the encounter frequency")
                       : std::string("measured record (cubic spline)"));
  for (const NamedPointSpec& tp : vs.tow_points)
    line(out, "tow point " + tp.name.value,
         vec(tp.point.value) + " m (vessel axes, from the " + (moving ? "RAO origin" : "tow law's point") + ")");
  // The tree: each line's ends and where its top hangs.
  const auto node_text = [&](int line_index, int body, const Vec3& point) {
    const Model& m = tree.lines[static_cast<std::size_t>(line_index)];
    const std::string& name = net.line_names[static_cast<std::size_t>(line_index)];
    if (body < 0) return "the end of line " + name;
    return "body " + m.bodies[static_cast<std::size_t>(body)].name + " of line " + name + " at " + vec(point) + " m";
  };
  out << "network\n";
  for (std::size_t t = 0; t < nl; ++t) {
    const Model& m = tree.lines[t];
    const LineTop& top = tree.tops[t];
    std::string where = top.line < 0 ? "tow point " + net.tow_point[t] + " " +
                                           vec(m.tow.vessel ? m.tow.vessel->sheave() : Vec3::Zero()) + " m"
                                     : "hangs from " + node_text(top.line, top.body, top.point);
    line(out, "line " + net.line_names[t],
         net.line_from[t] + " -> " + net.line_to[t] + ": " + fmt_num(m.cable.total_length()) + " m in " +
             std::to_string(m.cable.n()) + " elements; " + where);
  }
  for (const NetworkJunction& j : net.junctions)
    line(out, "junction " + j.name, "the end of line " + net.line_names[static_cast<std::size_t>(j.line)]);
  for (const LoopJoint& l : tree.loops)
    line(out, "loop",
         "the end of line " + net.line_names[static_cast<std::size_t>(l.line)] + " joined to " +
             node_text(l.node_line, l.body, l.point));
  // Each line as a chain.
  for (std::size_t t = 0; t < nl; ++t) {
    const Model& m = tree.lines[t];
    out << "line " << net.line_names[t] << ": " << net.line_from[t] << " -> " << net.line_to[t] << "\n";
    describe_cable(m.cable, out);
    for (const Body& b : m.bodies) describe_body(b, m.cable, m.fluid, out, true);
    describe_winch(m.winch, out);
  }
  describe_run(first, out);
}

}  // namespace towsim::cli
