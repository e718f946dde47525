#include "parse_sections.hpp"

namespace towsim::scenario {
namespace {

void parse_sphere(MapReader& r, SphereSpec& s) {
  s.where = r.where();
  r.read("center", s.center, true);
  r.read("radius", s.radius, true);
  r.read("drag", s.drag);
  r.read("added_mass", s.added_mass);
}

void parse_cylinder(MapReader& r, CylinderSpec& c) {
  c.where = r.where();
  r.read("center", c.center, true);
  r.read("axis", c.axis, true);
  r.read("length", c.length, true);
  r.read("diameter", c.diameter, true);
  r.read("normal_drag", c.normal_drag);
  r.read("axial_drag", c.axial_drag);
  r.read("added_mass", c.added_mass);
}

/// deflection_deg: a number (constant) or a table [[t, deg], ...].
void parse_deflection(MapReader& r, SurfaceSpec& s, Diagnostics& d) {
  const YNode* n = r.get("deflection_deg");
  if (n == nullptr) return;
  s.deflection_where = r.where(*n, "deflection_deg");
  if (n->is_scalar()) {
    double deg = 0;
    if (convert(*n, s.deflection_where.path, d, deg)) s.deflection.push_back(RowSpec{{0.0, deg}, s.deflection_where});
    return;
  }
  if (!read_table(*n, s.deflection_where.path, 2, d, s.deflection)) s.deflection.clear();
}

/// depth_control: {target_depth, kp, ki, kd, max_deflection_deg, max_rate_deg_s, ...}.
void parse_depth_control(MapReader& r, DepthControlSpec& c) {
  c.where = r.where();
  r.read("target_depth", c.target_depth, true);
  r.read("kp", c.kp);
  r.read("ki", c.ki);
  r.read("kd", c.kd);
  r.read("max_deflection_deg", c.max_deflection_deg, true);
  r.read("max_rate_deg_s", c.max_rate_deg_s, true);
  r.read("servo_time_constant", c.servo_time_constant);
  r.read("tracking_time", c.tracking_time);
  r.read("initial_deflection_deg", c.initial_deflection_deg);
  r.read("settling_band", c.settling_band);
}

void parse_surface(MapReader& r, SurfaceSpec& s, Diagnostics& d) {
  s.where = r.where();
  r.read("center", s.center, true);
  r.read("chord", s.chord, true);
  r.read("normal", s.normal, true);
  r.read("area", s.area, true);
  r.read("lift_slope", s.lift_slope);
  r.read("stall_angle_deg", s.stall_angle_deg);
  r.read("drag0", s.drag0);
  r.read("induced_drag", s.induced_drag);
  parse_deflection(r, s, d);
  MapReader dc(r.get("depth_control"), r.sub("depth_control"), d);
  s.depth_control.present = dc.present();
  if (dc.present()) parse_depth_control(dc, s.depth_control);
  dc.finish();
}

/// thrusters item: point, direction, force (a number or a table [[t, N], ...]).
void parse_thruster(MapReader& r, ThrusterSpec& th, Diagnostics& d) {
  th.where = r.where();
  r.read("point", th.point);
  r.read("direction", th.direction);
  const YNode* n = r.get("force", true);
  if (n == nullptr) return;
  th.force_where = r.where(*n, "force");
  if (n->is_scalar()) {
    double f = 0;
    if (convert(*n, th.force_where.path, d, f)) th.force.push_back(RowSpec{{0.0, f}, th.force_where});
    return;
  }
  if (!read_table(*n, th.force_where.path, 2, d, th.force)) th.force.clear();
}

}  // namespace

void parse_body(MapReader& r, BodySpec& b, Diagnostics& d, bool link_required) {
  b.where = r.where();
  r.read("name", b.name);
  r.read("mass", b.mass, true);
  r.read("inertia", b.inertia, true);
  r.read("center_of_gravity", b.center_of_gravity);
  r.read("link_point", b.link_point, link_required);
  r.read("lower_link_point", b.lower_link_point);
  r.read("volume", b.volume);
  r.read("center_of_buoyancy", b.center_of_buoyancy);
  r.read("added_mass", b.added_mass);
  r.read("linear_damping", b.linear_damping);
  r.read("quadratic_damping", b.quadratic_damping);
  r.read("initial_attitude_deg", b.initial_attitude_deg);
  r.list("spheres", [&](MapReader& item, std::size_t) {
    b.spheres.emplace_back();
    parse_sphere(item, b.spheres.back());
  });
  r.list("cylinders", [&](MapReader& item, std::size_t) {
    b.cylinders.emplace_back();
    parse_cylinder(item, b.cylinders.back());
  });
  r.list("surfaces", [&](MapReader& item, std::size_t) {
    b.surfaces.emplace_back();
    parse_surface(item, b.surfaces.back(), d);
  });
  r.list("thrusters", [&](MapReader& item, std::size_t) {
    b.thrusters.emplace_back();
    parse_thruster(item, b.thrusters.back(), d);
  });
}

}  // namespace towsim::scenario
