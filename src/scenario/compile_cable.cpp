// Checking and building the cable: sections, in-line bodies, attachments
// (docs/scenario.md "cable"). One resolved list of sections serves both the
// single-section form and `cable.sections`.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "checks.hpp"
#include "reader.hpp"
#include "towsim/dynamics/elastic.hpp"

namespace towsim::scenario {
namespace {

constexpr long long kMaxElements = 100000;  // elements in the whole cable

/// A section's properties after inheriting the cable-level values.
struct Resolved {
  Where where;  // the section (or the cable, single-section form)
  std::string name;
  Field<double> length;
  Field<long long> elements;
  Field<double> mass_per_length, diameter, normal_drag, tangential_coef, added_mass, breaking_load;
  Field<std::string> tangential_law;
  Field<double> axial_stiffness, axial_damping;
  Field<double> bending_stiffness;  // EI [N m^2]
  // Faired cable: the laws' tables (rows {phi [deg], f}), empty with the default laws.
  Field<std::string> normal_law;
  const std::vector<RowSpec>* normal_table = nullptr;
  const std::vector<RowSpec>* tangential_table = nullptr;
};

/// Field f of the section if given, else the cable's.
template <class T>
Field<T> pick(const Field<T>& section, const Field<T>& cable) {
  return section.given ? section : cable;
}

/// The sections in order, each with its properties resolved.
std::vector<Resolved> resolve(const CableSpec& c) {
  std::vector<Resolved> out;
  if (c.sections.empty() && c.item_body.empty()) {
    out.push_back({c.where, "cable", c.length, c.elements, c.mass_per_length, c.diameter, c.normal_drag,
                   c.tangential_coef, c.added_mass, c.breaking_load, c.tangential_law, c.axial_stiffness,
                   c.axial_damping, c.bending_stiffness, c.normal_law, &c.normal_table, &c.tangential_table});
    return out;
  }
  for (std::size_t i = 0; i < c.sections.size(); ++i) {
    const SectionSpec& s = c.sections[i];
    Resolved r{s.where,
               s.name.given ? s.name.value : "section " + std::to_string(i),
               s.length,
               s.elements,
               pick(s.mass_per_length, c.mass_per_length),
               pick(s.diameter, c.diameter),
               pick(s.normal_drag, c.normal_drag),
               s.tangential_law.given ? s.tangential_coef : c.tangential_coef,
               pick(s.added_mass, c.added_mass),
               pick(s.breaking_load, c.breaking_load),
               pick(s.tangential_law, c.tangential_law),
               pick(s.axial_stiffness, c.axial_stiffness),
               pick(s.axial_damping, c.axial_damping),
               pick(s.bending_stiffness, c.bending_stiffness),
               pick(s.normal_law, c.normal_law),
               s.normal_law.given ? &s.normal_table : &c.normal_table,
               s.tangential_law.given ? &s.tangential_table : &c.tangential_table};
    out.push_back(r);
  }
  return out;
}

/// The cable's tangential law: that of the first section without a table law (pode if none).
std::string cable_law(const std::vector<Resolved>& secs) {
  for (const Resolved& s : secs)
    if (s.tangential_law.value != "table") return s.tangential_law.value;
  return "pode";
}

/// The table of a law in radians (empty for the default laws).
LoadingTable loading_table(const std::vector<RowSpec>* rows, bool table_law) {
  LoadingTable t;
  if (!table_law || rows == nullptr) return t;
  for (const RowSpec& row : *rows) {
    t.phi.push_back(row.values[0] * std::numbers::pi / 180);
    t.f.push_back(row.values[1]);
  }
  return t;
}

/// A required property that neither the section nor the cable gives.
void require(const Field<double>& f, const Where& section, const std::string& key, Diagnostics& d) {
  if (f.given) return;
  d.error(section.loc, join_path(section.path, key), "missing (give it in the section or at cable level)");
}

/// A faired cable's loading table: angles in [0, 90] deg, strictly increasing; f >= 0.
void check_loading(const std::vector<RowSpec>& rows, const std::string& f, Diagnostics& d) {
  for (const RowSpec& row : rows) {
    if (!(row.values[0] >= 0 && row.values[0] <= 90))
      d.error(row.where.loc, row.where.path,
              "the angle between cable and flow must be within [0, 90] deg (got " + fmt_num(row.values[0]) + ")");
    if (!(row.values[1] >= 0))
      d.error(row.where.loc, row.where.path, f + " must be >= 0 (got " + fmt_num(row.values[1]) + ")");
  }
  check_increasing(rows, "angles", d);
}

void check_section(const Resolved& s, Diagnostics& d, bool sectioned) {
  check_positive(s.length, d);
  check_at_least(s.elements, 1, d);
  check_at_most(s.elements, kMaxElements, d);
  if (sectioned) {  // the single-section form reports them as missing keys
    require(s.mass_per_length, s.where, "mass_per_length", d);
    require(s.diameter, s.where, "diameter", d);
  }
  check_positive(s.mass_per_length, d);
  check_positive(s.diameter, d);
  check_non_negative(s.normal_drag, d);
  check_non_negative(s.tangential_coef, d);
  check_non_negative(s.added_mass, d);
  check_positive(s.breaking_load, d);
  check_positive(s.axial_stiffness, d);
  check_non_negative(s.axial_damping, d);
  check_non_negative(s.bending_stiffness, d);
}

/// v with `digits` significant digits, rounded down (a bound users can copy) or to nearest.
std::string sig(double v, int digits, bool down) {
  const double p = std::pow(10.0, std::floor(std::log10(v)) - (digits - 1));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, (down ? std::floor(v / p) : std::round(v / p)) * p);
  return buf;
}

/// An elastic section: the paper formulation has no stretch, and a fixed RK4
/// step must resolve the axial wave (docs/theory.md §5.4).
void check_elastic(const Resolved& s, const SimulationSpec& sim, Diagnostics& d) {
  if (!s.axial_stiffness.given || !(s.axial_stiffness.value > 0) || !s.length.given || !s.elements.given ||
      s.elements.value < 1 || !(s.mass_per_length.value > 0))
    return;
  if (sim.formulation.value == "paper") {
    d.error(s.axial_stiffness.where.loc, s.axial_stiffness.where.path,
            "the paper formulation has inextensible elements only: an elastic cable needs formulation: default");
    return;
  }
  if (sim.integrator.value != "rk4") return;
  Element el{};
  el.length = s.length.value / static_cast<double>(s.elements.value);
  el.mass = s.mass_per_length.value * el.length;
  el.axial_stiffness = s.axial_stiffness.value;
  el.axial_damping = s.axial_damping.given ? s.axial_damping.value : 0.0;
  const double h_max = rk4_axial_step_limit(el);
  const std::string damping = el.axial_damping > 0 ? ", axial damping " + fmt_num(el.axial_damping) + " N s"
                                                   : std::string();
  if (sim.time_step.value > h_max)
    d.error(s.axial_stiffness.where.loc, s.axial_stiffness.where.path,
            "with integrator: rk4, the axial wave (speed " + sig(axial_wave_speed(el), 4, false) + " m/s over " +
                fmt_num(el.length) + " m elements" + damping +
                ") needs simulation.time_step <= " + sig(h_max, 3, true) + " s (it is " + fmt_num(sim.time_step.value) +
                " s); use integrator: rosenbrock (implicit in the axial mode) or a smaller step");
}

/// The order of sections and bodies: a section first, never two bodies in a
/// row, an in-line body with a lower link, names that make distinct columns.
void check_topology(const CableSpec& c, const BodySpec& end_body, Diagnostics& d) {
  const auto& items = c.item_body;
  if (!items.empty() && items.front() >= 0)
    d.error(c.item_where.front().loc, c.item_where.front().path, "the first item must be a cable section");
  for (std::size_t i = 1; i < items.size(); ++i)
    if (items[i] >= 0 && items[i - 1] >= 0)
      d.error(c.item_where[i].loc, c.item_where[i].path, "a body must hang from a cable section (two bodies in a row)");
  if (!items.empty() && items.back() >= 0)
    d.error(c.item_where.back().loc, c.item_where.back().path,
            "the last item is a body: give the end body as the top-level body: key");
  std::set<std::string> names{"body"};
  for (const BodySpec& b : c.inline_bodies) {
    if (!b.present) continue;
    check_body(b, d);
    if (!b.lower_link_point.given)
      d.error(b.where.loc, join_path(b.where.path, "lower_link_point"), "missing (an in-line body needs it)");
    if (!b.name.given) continue;
    const std::string& n = b.name.value;
    bool ok = !n.empty();
    for (char ch : n) ok = ok && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_');
    if (!ok)
      d.error(b.name.where.loc, b.name.where.path, "must be letters, digits and _ (it prefixes output columns)");
    else if (!names.insert(n).second)
      d.error(b.name.where.loc, b.name.where.path, "'" + n + "' is already used (names must be distinct, not 'body')");
  }
  if (end_body.present && end_body.lower_link_point.given)
    d.error(end_body.lower_link_point.where.loc, end_body.lower_link_point.where.path,
            "only for an in-line body (nothing hangs below the end body)");
}

/// Total elements, and the joint index nearest to arc length s (with the
/// section lengths' element sizes).
int nearest_joint(const std::vector<Resolved>& secs, double s) {
  int joint = 0;
  double top = 0;
  for (const Resolved& r : secs) {
    const double le = r.length.value / static_cast<double>(r.elements.value);
    if (s <= top + r.length.value || &r == &secs.back()) {
      const long long k = std::llround(std::clamp((s - top) / le, 0.0, static_cast<double>(r.elements.value)));
      return joint + static_cast<int>(k);
    }
    joint += static_cast<int>(r.elements.value);
    top += r.length.value;
  }
  return joint;
}

void check_attachments(const CableSpec& c, const std::vector<Resolved>& secs, bool end_body, Diagnostics& d) {
  double total = 0;
  for (const Resolved& r : secs) total += r.length.value;
  // Joints where a body hangs: after each section followed by a body, and the end.
  std::set<int> body_joints;
  int joint = 0;
  for (std::size_t i = 0, s = 0; i < c.item_body.size(); ++i) {
    if (c.item_body[i] >= 0)
      body_joints.insert(joint);
    else
      joint += static_cast<int>(secs[s++].elements.value);
  }
  if (end_body) body_joints.insert(nearest_joint(secs, total));
  for (const AttachmentSpec& a : c.attachments) {
    check_non_negative(a.at, d);
    check_non_negative(a.mass, d);
    check_non_negative(a.volume, d);
    check_non_negative(a.drag_area, d);
    check_non_negative(a.added_mass, d);
    if (a.at.given && a.at.value > total)
      d.error(a.at.where.loc, a.at.where.path,
              "beyond the cable's end (" + fmt_num(a.at.value) + " > " + fmt_num(total) + " m)");
    else if (a.at.given && body_joints.count(nearest_joint(secs, a.at.value)))
      d.error(a.at.where.loc, a.at.where.path,
              "falls on a body's link joint (give its mass to the body, or move it along the cable)");
  }
}

}  // namespace

void check_cable(const CableSpec& c, const BodySpec& end_body, const SimulationSpec& sim, Diagnostics& d) {
  const std::vector<Resolved> secs = resolve(c);
  long long total = 0;
  for (const Resolved& s : secs) {
    check_section(s, d, !c.item_body.empty());
    check_elastic(s, sim, d);
    total += std::max(0LL, s.elements.value);
  }
  check_positive(c.sign_smoothing_speed, d);
  // Loading tables where they are written (inherited ones once).
  check_loading(c.normal_table, "fn", d);
  check_loading(c.tangential_table, "ft", d);
  for (const SectionSpec& s : c.sections) {
    check_loading(s.normal_table, "fn", d);
    check_loading(s.tangential_table, "ft", d);
  }
  if (secs.size() > 1 && total > kMaxElements)
    d.error(c.sections_where.loc, c.sections_where.path,
            "too many elements in all (" + std::to_string(total) + " > " + std::to_string(kMaxElements) + ")");
  // One tangential law for the whole cable (element loads take the cable's);
  // a section's table law replaces it there.
  const std::string law = cable_law(secs);
  for (const Resolved& s : secs)
    if (s.tangential_law.value != "table" && s.tangential_law.value != law && s.tangential_law.given)
      d.error(s.tangential_law.where.loc, s.tangential_law.where.path,
              "all sections must use the same tangential drag law (the first uses " + law + ")");
  check_topology(c, end_body, d);
  if (!d.ok()) return;
  check_attachments(c, secs, end_body.present, d);
  // The paper's dense form has one cable and at most one body, at its end.
  const bool chain = !c.inline_bodies.empty() || !c.attachments.empty();
  if (chain && sim.formulation.value == "paper")
    d.error(sim.formulation.where.loc, sim.formulation.where.path,
            "the paper formulation has no in-line bodies or attachments (use formulation: default)");
}

void build_chain(const CableSpec& c, const BodySpec& end_body, Model& m) {
  const std::vector<Resolved> secs = resolve(c);
  Cable& cable = m.cable;
  cable.tangential_law = cable_law(secs) == "skin" ? TangentialLaw::Skin : TangentialLaw::Pode;
  cable.added_mass_model = c.added_mass_model.value == "morison" ? AddedMassModel::Morison : AddedMassModel::IdealFluid;
  cable.sign_smoothing_speed = c.sign_smoothing_speed.value;
  // Sections in order; after each but the last, the in-line body between.
  std::size_t section = 0;
  for (std::size_t item = 0; item < std::max<std::size_t>(1, c.item_body.size()); ++item) {
    const int bi = c.item_body.empty() ? -1 : c.item_body[item];
    if (bi >= 0) {
      Body body = build_body(c.inline_bodies[static_cast<std::size_t>(bi)], m.fluid);
      if (!c.inline_bodies[static_cast<std::size_t>(bi)].name.given)
        body.name = "body" + std::to_string(m.bodies.size() + 1);
      body.inline_body = true;
      body.joint = cable.n();
      m.bodies.push_back(body);
      continue;
    }
    const Resolved& s = secs[section];
    const long long n = s.elements.value;
    const double le = s.length.value / static_cast<double>(n);
    cable.sections.push_back({s.name, cable.n(), static_cast<int>(n), s.length.value,
                              s.breaking_load.given ? s.breaking_load.value : 0.0,
                              loading_table(s.normal_table, s.normal_law.value == "table"),
                              loading_table(s.tangential_table, s.tangential_law.value == "table")});
    for (long long i = 0; i < n; ++i) {
      Element el = make_element(le, s.mass_per_length.value, s.diameter.value, s.normal_drag.value,
                                s.tangential_coef.value, cable.tangential_law, s.added_mass.value, m.fluid);
      el.section = static_cast<int>(section);
      if (s.axial_stiffness.given) {
        el.axial_stiffness = s.axial_stiffness.value;
        el.axial_damping = s.axial_damping.value;
      }
      el.bending_stiffness = s.bending_stiffness.value;
      cable.elements.push_back(el);
    }
    ++section;
  }
  if (end_body.present) {
    m.bodies.push_back(build_body(end_body, m.fluid));
    m.bodies.back().name = "body";
  }
  // Attachments at the nearest joint, sorted by joint.
  for (const AttachmentSpec& a : c.attachments)
    cable.attachments.push_back({nearest_joint(secs, a.at.value), a.at.value, a.mass.value, a.volume.value,
                                 a.drag_area.value, a.added_mass.value});
  std::stable_sort(cable.attachments.begin(), cable.attachments.end(),
                   [](const Attachment& x, const Attachment& y) { return x.joint < y.joint; });
}

}  // namespace towsim::scenario
