#include "towsim/scenario/parse.hpp"

#include <algorithm>

#include "parse_sections.hpp"

namespace towsim::scenario {
namespace {

/// initial: hanging | steady | {direction: [x, y, z]}.
void parse_initial(const YNode* n, InitialSpec& init, Diagnostics& d) {
  if (n == nullptr) return;
  const Where w{n->loc, "initial"};
  if (n->is_scalar()) {
    Field<std::string> f;
    f.value = n->scalar;
    f.where = w;
    if (check_choice(n->scalar, {"hanging", "steady"}, w, d)) {
      f.given = true;
      init.kind = f;
    }
    return;
  }
  if (n->is_map()) {
    MapReader r(n, "initial", d);
    r.read("direction", init.direction, true);
    r.finish();
    init.kind.value = "direction";
    init.kind.where = w;
    init.kind.given = init.direction.given;
    return;
  }
  d.error(n->loc, "initial", "expected hanging, steady or {direction: [x, y, z]} (got " + n->describe() + ")");
}

}  // namespace

namespace {

/// environment.seabed: {depth: D | [[x, D], ...], stiffness, damping, friction, contact}.
void parse_seabed(MapReader& r, SeabedSpec& sb, Diagnostics& d) {
  sb.where = r.where();
  r.read("stiffness", sb.stiffness);
  r.read("damping", sb.damping);
  r.read("friction", sb.friction);
  r.choice("contact", sb.contact, {"joints", "elements"});
  const YNode* n = r.get("depth", true);
  if (n == nullptr) return;
  sb.depth_where = r.where(*n, "depth");
  if (n->is_scalar()) {
    double v = 0;
    if (convert(*n, sb.depth_where.path, d, v)) sb.depth.push_back(RowSpec{{0.0, v}, sb.depth_where});
    return;
  }
  if (!read_table(*n, sb.depth_where.path, 2, d, sb.depth)) sb.depth.clear();
}

}  // namespace

void parse_environment(MapReader& r, EnvironmentSpec& env, Diagnostics& d) {
  r.read("water_density", env.water_density);
  r.read("gravity", env.gravity);
  if (const YNode* sbn = r.get("seabed")) {
    MapReader sr(sbn, r.sub("seabed"), d);
    env.seabed.present = sr.present();
    if (env.seabed.present) parse_seabed(sr, env.seabed, d);
    sr.finish();
  }
  // current (m/s) or current_kn (knots): a vector, or rows {depth, velocity | velocity_kn}.
  const YNode* c = r.get("current");
  const YNode* c_kn = r.get("current_kn");
  if (c != nullptr && c_kn != nullptr) {
    d.error(c_kn->key_loc, "environment.current_kn", "give either 'current' or 'current_kn', not both");
    return;
  }
  const bool knots = c_kn != nullptr;
  const auto to_mps = [knots](const Vec3& u) {  // [m/s]
    return knots ? Vec3(knots_to_mps(u.x()), knots_to_mps(u.y()), knots_to_mps(u.z())) : u;
  };
  if (c == nullptr) c = c_kn;
  if (c == nullptr) return;
  env.current_given = true;
  env.current_where = r.where(*c, knots ? "current_kn" : "current");
  const std::string path = env.current_where.path;
  if (c->is_seq() && !c->items.empty() && c->items[0].is_map()) {
    const std::size_t errors_before = d.size();
    for (std::size_t i = 0; i < c->items.size(); ++i) {
      MapReader row(&c->items[i], join_path(path, std::to_string(i)), d);
      Field<double> depth;
      Field<Vec3> vel;
      row.read("depth", depth, row.present());
      row.read(knots ? "velocity_kn" : "velocity", vel, row.present());
      row.finish();
      const Vec3 u = to_mps(vel.value);
      if (depth.given && vel.given) env.current.push_back(RowSpec{{depth.value, u.x(), u.y(), u.z()}, depth.where});
    }
    if (d.size() != errors_before) env.current.clear();  // no order checks on a partial table
    return;
  }
  Vec3 u;
  if (!convert(*c, path, d, u)) return;
  u = to_mps(u);
  env.current.push_back(RowSpec{{0.0, u.x(), u.y(), u.z()}, env.current_where});
}

namespace {

/// A faired cable's loading table [[phi_deg, f], ...] under `key` (required).
void read_loading(MapReader& r, const std::string& key, std::vector<RowSpec>& rows, Diagnostics& d) {
  const YNode* n = r.get(key, true);
  if (n == nullptr) return;
  if (!read_table(*n, r.sub(key), 2, d, rows)) rows.clear();
}

/// True when `law` is given but is none of `choices` (reported already): the
/// caller then accepts every law's keys silently instead of adding errors.
bool unknown_law(const YNode& map, const std::vector<std::string>& choices) {
  const YNode* law = map.find("law");
  if (law == nullptr || !law->is_scalar()) return false;
  return std::find(choices.begin(), choices.end(), law->scalar) == choices.end();
}

/// tangential_drag: {law: pode, f: ...}, {law: skin, ct: ...} or {law: table, ft: [[phi_deg, ft], ...]}.
void parse_tangential(MapReader& r, Field<std::string>& law, Field<double>& coef, std::vector<RowSpec>& table,
                      Diagnostics& d) {
  const YNode* t = r.get("tangential_drag");
  if (t == nullptr) return;
  MapReader tr(t, r.sub("tangential_drag"), d);
  tr.choice("law", law, {"pode", "skin", "table"});
  if (unknown_law(*t, {"pode", "skin", "table"}))
    for (const char* key : {"f", "ct", "ft"}) tr.get(key);
  coef.value = law.value == "skin" ? 0.008 : 0.0;
  coef.given = law.given;  // the law's default coefficient goes with it
  if (law.value == "skin")
    tr.read("ct", coef);
  else if (law.value == "table")
    read_loading(tr, "ft", table, d);
  else
    tr.read("f", coef);
  tr.finish();
}

/// normal_drag: Cd, or {law: cross_flow, cd: ...} or {law: table, cd: ..., fn: [[phi_deg, fn], ...]}.
/// A map sets the law (and its table) even without cd; cd then comes from the cable level or its default.
void parse_normal(MapReader& r, Field<double>& cd, Field<std::string>& law, std::vector<RowSpec>& table,
                  Diagnostics& d) {
  const YNode* n = r.get("normal_drag");
  if (n == nullptr) return;
  if (!n->is_map()) {
    r.read("normal_drag", cd);
    law.value = "cross_flow";
    law.where = cd.where;
    law.given = cd.given;
    return;
  }
  MapReader nr(n, r.sub("normal_drag"), d);
  law.value = "cross_flow";
  law.where = r.where(*n, "normal_drag");
  law.given = true;
  nr.choice("law", law, {"cross_flow", "table"});
  if (unknown_law(*n, {"cross_flow", "table"})) nr.get("fn");
  nr.read("cd", cd);
  if (law.value == "table") read_loading(nr, "fn", table, d);
  nr.finish();
}

/// One cable.sections item that is a section (not a body).
void parse_section(MapReader& r, SectionSpec& sec, Diagnostics& d) {
  sec.where = r.where();
  r.read("name", sec.name);
  r.read("length", sec.length, true);
  r.read("elements", sec.elements, true);
  r.read("mass_per_length", sec.mass_per_length);
  r.read("diameter", sec.diameter);
  parse_normal(r, sec.normal_drag, sec.normal_law, sec.normal_table, d);
  parse_tangential(r, sec.tangential_law, sec.tangential_coef, sec.tangential_table, d);
  r.read("added_mass", sec.added_mass);
  r.read("axial_stiffness", sec.axial_stiffness);
  r.read("axial_damping", sec.axial_damping);
  r.read("bending_stiffness", sec.bending_stiffness);
  r.read("breaking_load", sec.breaking_load);
}

void parse_attachment(MapReader& r, AttachmentSpec& a) {
  a.where = r.where();
  r.read("at", a.at, true);
  r.read("mass", a.mass);
  r.read("volume", a.volume);
  r.read("drag_area", a.drag_area);
  r.read("added_mass", a.added_mass);
}

}  // namespace

void parse_cable(MapReader& r, CableSpec& cable, Diagnostics& d) {
  cable.where = r.where();
  const bool sectioned = r.has("sections");
  r.read("length", cable.length, !sectioned);
  r.read("elements", cable.elements, !sectioned);
  r.read("mass_per_length", cable.mass_per_length, !sectioned);
  r.read("diameter", cable.diameter, !sectioned);
  parse_normal(r, cable.normal_drag, cable.normal_law, cable.normal_table, d);
  parse_tangential(r, cable.tangential_law, cable.tangential_coef, cable.tangential_table, d);
  r.read("added_mass", cable.added_mass);
  r.choice("added_mass_model", cable.added_mass_model, {"ideal_fluid", "morison"});
  r.read_speed("sign_smoothing_speed", cable.sign_smoothing_speed);
  r.read("breaking_load", cable.breaking_load);
  r.read("axial_stiffness", cable.axial_stiffness);
  r.read("axial_damping", cable.axial_damping);
  r.read("bending_stiffness", cable.bending_stiffness);
  if (const YNode* n = r.get("sections")) {
    cable.sections_where = r.where(*n, "sections");  // after the single form's keys
    // An empty list has no cable; length and elements belong to each section.
    if (n->is_seq() && n->items.empty())
      d.error(n->loc, r.sub("sections"), "the list is empty (give at least one section, or leave sections out)");
    const std::string own = "not used with cable.sections (each section gives its own)";
    if (cable.length.given) d.error(cable.length.where.loc, cable.length.where.path, own);
    if (cable.elements.given) d.error(cable.elements.where.loc, cable.elements.where.path, own);
  }
  // Sections top to bottom; an item {body: {...}} is an in-line body.
  r.list("sections", [&](MapReader& item, std::size_t) {
    cable.item_where.push_back(item.where());
    if (const YNode* b = item.get("body")) {
      cable.item_body.push_back(static_cast<int>(cable.inline_bodies.size()));
      cable.inline_bodies.emplace_back();
      MapReader br(b, item.sub("body"), d);
      cable.inline_bodies.back().present = br.present();
      if (br.present()) parse_body(br, cable.inline_bodies.back(), d);
      br.finish();
      return;
    }
    cable.item_body.push_back(-1);
    cable.sections.emplace_back();
    parse_section(item, cable.sections.back(), d);
  });
  r.list("attachments", [&](MapReader& item, std::size_t) {
    cable.attachments.emplace_back();
    parse_attachment(item, cable.attachments.back());
  });
}

void parse_simulation(MapReader& r, SimulationSpec& sim) {
  sim.where = r.where();
  r.read("duration", sim.duration, true);
  r.read("time_step", sim.time_step);
  r.choice("integrator", sim.integrator, {"rk4", "dopri5", "cash_karp54", "rosenbrock"});
  r.read("tolerance", sim.tolerance);
  r.read("max_step", sim.max_step);
  r.choice("formulation", sim.formulation, {"default", "paper"});
  r.read("output_interval", sim.output_interval);
  r.read("write_nodes", sim.write_nodes);
  r.read("threads", sim.threads);
  // Absent integrator and tolerance: the defaults for the formulation and the integrator.
  const Formulation f = sim.formulation.value == "paper" ? Formulation::Paper : Formulation::Default;
  if (!sim.integrator.given) sim.integrator.value = integrator_key(default_integrator(f));
  if (!sim.tolerance.given) sim.tolerance.value = default_tolerance(integrator_of(sim.integrator.value));
}

ScenarioSpec parse_scenario(const YNode& root, const std::string& base_dir, Diagnostics& d) {
  ScenarioSpec s;
  s.base_dir = base_dir;
  s.root = Where{root.loc, "(root)"};
  if (root.is_null()) {
    d.error(root.loc, "(root)", "the scenario is empty (expected cable:, simulation:, ...)");
    return s;
  }
  MapReader r(&root, "", d);
  if (!r.present()) return s;
  Field<std::string> text;
  r.read("name", text);
  if (text.given) s.name = text.value;
  text = Field<std::string>{};
  r.read("description", text);
  if (text.given) s.description = text.value;
  MapReader env(r.get("environment"), "environment", d);
  parse_environment(env, s.environment, d);
  env.finish();
  // A network (lines:) instead of cable: and body:.
  s.network = root.find("lines") != nullptr;
  if (s.network) {
    r.get("cable");
    r.get("body");
  } else {
    MapReader cable(r.get("cable", true), "cable", d);
    parse_cable(cable, s.cable, d);
    cable.finish();
    const YNode* body_node = r.get("body");
    MapReader body(body_node, "body", d);
    s.body.present = body.present();
    if (s.body.present) parse_body(body, s.body, d);
    body.finish();
  }
  parse_network(r, root, s, d);
  MapReader tow(r.get("tow"), "tow", d);
  parse_tow(tow, s.tow, base_dir, d);
  tow.finish();
  parse_initial(r.get("initial"), s.initial, d);
  MapReader sim(r.get("simulation", true), "simulation", d);
  parse_simulation(sim, s.simulation);
  sim.finish();
  MapReader waves(r.get("waves"), "waves", d);
  s.waves.present = waves.present();
  if (s.waves.present) parse_waves(waves, s.waves, d);
  waves.finish();
  MapReader vessel(r.get("vessel"), "vessel", d);
  s.vessel.present = vessel.present();
  if (s.vessel.present) parse_vessel(vessel, s.vessel, base_dir, d);
  if (s.vessel.present) parse_tow_points(vessel, r.get("vessel"), s, d);
  vessel.finish();
  MapReader winch(r.get("winch"), "winch", d);
  s.winch.present = winch.present();
  if (s.winch.present) parse_winch(winch, s.winch, d);
  winch.finish();
  r.finish();
  return s;
}

}  // namespace towsim::scenario
