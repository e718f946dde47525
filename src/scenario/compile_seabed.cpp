// Checking `environment.seabed` and building the Seabed; refusing a start
// below the bottom (INTERFACE.md "Elastic cable and seabed").
#include <cmath>
#include <string>

#include "checks.hpp"
#include "towsim/dynamics/state.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/integrators/system.hpp"

namespace towsim::scenario {

namespace {

/// "(z = Z m; the bottom is at z = B m there)".
std::string below_text(const Seabed& sb, const Vec3& p) {
  return "(z = " + fmt_num(p.z()) + " m; the bottom is at z = " + fmt_num(sb.bottom_z(p.x())) + " m there)";
}

}  // namespace

void check_seabed(const ScenarioSpec& s, Diagnostics& d) {
  const SeabedSpec& sb = s.environment.seabed;
  if (!sb.present) return;
  for (const RowSpec& row : sb.depth)
    if (!(row.values[1] > 0))
      d.error(row.where.loc, row.where.path, "depth must be > 0 (got " + fmt_num(row.values[1]) + ")");
  check_increasing(sb.depth, "x values", d);
  check_positive(sb.stiffness, d);
  check_non_negative(sb.damping, d);
  check_non_negative(sb.friction, d);
  const Field<std::string>& f = s.simulation.formulation;
  if (f.value == "paper")
    d.error(f.where.loc, f.where.path, "the paper formulation has no seabed contact (use formulation: default)");
  // One depth for the waves: the seabed's, unless a table leaves the choice to water_depth.
  const Field<double>& wd = s.waves.water_depth;
  if (wd.given && sb.depth.size() == 1 && wd.value != sb.depth[0].values[1])
    d.error(wd.where.loc, wd.where.path,
            "differs from environment.seabed.depth (" + fmt_num(sb.depth[0].values[1]) +
                "): the waves take the seabed's depth (leave water_depth out)");
}

void build_seabed(const SeabedSpec& spec, Model& m) {
  if (!spec.present) return;
  Seabed sb;
  for (const RowSpec& row : spec.depth) {
    sb.x.push_back(row.values[0]);
    sb.depth.push_back(row.values[1]);
  }
  sb.stiffness = spec.stiffness.value;
  sb.damping = spec.damping.value;
  sb.friction = spec.friction.value;
  sb.along_elements = spec.contact.value == "elements";
  m.seabed = sb;
}

void check_seabed_start(const ScenarioSpec& s, const Model& m, Diagnostics& d) {
  if (!m.seabed) return;
  const Seabed& sb = *m.seabed;
  const SeabedSpec& spec = s.environment.seabed;
  // The tow point at t = 0 (the tow law and the vessel's motion included).
  const Vec3 r0 = m.tow.mode == Tow::Mode::Motion ? tow_kinematics(m.tow, 0.0).pos : m.tow.start;
  if (sb.gap(r0) < 0) {
    const Where& w = s.tow.start.given ? s.tow.start.where : spec.depth_where;
    d.error(w.loc, w.path, "the tow point starts below the seabed " + below_text(sb, r0));
    return;
  }
  // A hanging or directed start below the bottom would start with the
  // contact springs compressed by metres: refused (initial: steady lays it down).
  if (m.initial.kind == Initial::Kind::Steady) return;
  const Where& w = s.initial.kind.given ? s.initial.kind.where : spec.depth_where;
  const std::string fix =
      ": start with initial: steady (the cable settles on the bottom), a direction that keeps it above, or a "
      "shorter cable";
  const PhysicalState st = initial_state(m);
  Workspace ws(m);
  compute_kinematics(m, st, ws);
  double arc = 0;  // arc length of joint k from the tow point [m]
  for (std::size_t k = 0; k < ws.P.size(); ++k) {
    if (k > 0) arc += m.cable.elements[k - 1].length;
    if (sb.gap(ws.P[k]) < 0) {
      d.error(w.loc, w.path,
              "cable joint " + std::to_string(k) + " (" + fmt_num(arc) +
                  " m from the tow point) starts below the seabed " + below_text(sb, ws.P[k]) + fix);
      return;
    }
  }
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyWork& bw = ws.body[b];
    const Body& body = m.bodies[b];
    // Its lowest contact point, by the rule the contact uses (hull_points).
    double lowest = 0;
    Vec3 where = Vec3::Zero();
    hull_points(sb, body, bw, [&](const Vec3& p, double) {
      if (sb.gap(p) < lowest) lowest = sb.gap(p), where = p;
    });
    if (lowest < 0) {
      d.error(w.loc, w.path, "body " + body.name + " starts below the seabed " + below_text(sb, where) + fix);
      return;
    }
  }
}

}  // namespace towsim::scenario
