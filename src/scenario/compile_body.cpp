#include <cmath>
#include <numbers>

#include "checks.hpp"

namespace towsim::scenario {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

void check_sphere(const SphereSpec& s, Diagnostics& d) {
  check_positive(s.radius, d);
  check_non_negative(s.drag, d);
  check_non_negative(s.added_mass, d);
}

void check_cylinder(const CylinderSpec& c, Diagnostics& d) {
  check_nonzero(c.axis, d);
  check_positive(c.length, d);
  check_positive(c.diameter, d);
  check_non_negative(c.normal_drag, d);
  check_non_negative(c.axial_drag, d);
  check_non_negative(c.added_mass, d);
}

/// A surface's depth controller: gains, limits, servo.
void check_depth_control(const SurfaceSpec& s, Diagnostics& d) {
  const DepthControlSpec& c = s.depth_control;
  if (!s.deflection.empty())
    d.error(c.where.loc, c.where.path, "give either deflection_deg or depth_control, not both");
  check_non_negative(c.target_depth, d);
  if (c.kp.value == 0 && c.ki.value == 0 && c.kd.value == 0)
    d.error(c.where.loc, c.where.path, "needs a gain (kp, ki and kd are all 0)");
  check_positive(c.max_deflection_deg, d);
  if (c.max_deflection_deg.given && c.max_deflection_deg.value > 90)
    d.error(c.max_deflection_deg.where.loc, c.max_deflection_deg.where.path,
            "must be <= 90 (got " + fmt_num(c.max_deflection_deg.value) + ")");
  check_positive(c.max_rate_deg_s, d);
  check_positive(c.servo_time_constant, d);
  check_positive(c.tracking_time, d);
  check_positive(c.settling_band, d);
  const Field<double>& d0 = c.initial_deflection_deg;
  if (c.max_deflection_deg.given && std::abs(d0.value) > c.max_deflection_deg.value)
    d.error(d0.where.loc, d0.where.path,
            "must be within +-max_deflection_deg (got " + fmt_num(d0.value) + ", limit " +
                fmt_num(c.max_deflection_deg.value) + ")");
}

void check_surface(const SurfaceSpec& s, Diagnostics& d) {
  check_nonzero(s.chord, d);
  check_nonzero(s.normal, d);
  const double cn = s.chord.value.norm() * s.normal.value.norm();
  if (s.chord.given && s.normal.given && cn > 0) {
    const double cosang = s.chord.value.dot(s.normal.value) / cn;
    if (std::abs(cosang) > 1e-6)
      d.error(s.normal.where.loc, s.normal.where.path,
              "must be orthogonal to chord (the angle between them is " +
                  fmt_num(std::acos(std::clamp(cosang, -1.0, 1.0)) / kDeg) + " deg)");
  }
  check_positive(s.area, d);
  check_non_negative(s.lift_slope, d);
  check_positive(s.stall_angle_deg, d);
  if (s.stall_angle_deg.given && s.stall_angle_deg.value > 90)
    d.error(s.stall_angle_deg.where.loc, s.stall_angle_deg.where.path,
            "must be <= 90 (got " + fmt_num(s.stall_angle_deg.value) + ")");
  check_non_negative(s.drag0, d);
  check_non_negative(s.induced_drag, d);
  check_increasing(s.deflection, "times", d);
  if (s.depth_control.present) check_depth_control(s, d);
}

/// ZYX attitude: R = Rz(yaw) Ry(pitch) Rx(roll), angles in degrees.
Quat attitude(const Vec3& rpy_deg) {
  return Quat(Eigen::AngleAxisd(rpy_deg[2] * kDeg, Vec3::UnitZ()) *
              Eigen::AngleAxisd(rpy_deg[1] * kDeg, Vec3::UnitY()) *
              Eigen::AngleAxisd(rpy_deg[0] * kDeg, Vec3::UnitX()));
}

LiftingSurface build_surface(const SurfaceSpec& s) {
  LiftingSurface f;
  f.center = s.center.value;
  f.chord = s.chord.value.normalized();
  f.normal = s.normal.value.normalized();
  f.area = s.area.value;
  f.lift_slope = s.lift_slope.value;
  f.stall_angle = s.stall_angle_deg.value * kDeg;
  f.drag0 = s.drag0.value;
  f.induced_drag = s.induced_drag.value;
  for (const auto& row : s.deflection) {
    f.deflection_time.push_back(row.values[0]);
    f.deflection_angle.push_back(row.values[1] * kDeg);
  }
  if (s.depth_control.present) {
    const DepthControlSpec& c = s.depth_control;
    DepthControl dc;
    dc.target_depth = c.target_depth.value;
    dc.kp = c.kp.value * kDeg;
    dc.ki = c.ki.value * kDeg;
    dc.kd = c.kd.value * kDeg;
    dc.max_deflection = c.max_deflection_deg.value * kDeg;
    dc.max_rate = c.max_rate_deg_s.value * kDeg;
    dc.servo_time_constant = c.servo_time_constant.value;
    // Anti-windup tracking time: the integral time |kp/ki| unless given (1 s without both gains).
    dc.tracking_time = c.tracking_time.given                  ? c.tracking_time.value
                       : (c.kp.value != 0 && c.ki.value != 0) ? std::abs(c.kp.value / c.ki.value)
                                                              : 1.0;
    dc.initial_deflection = c.initial_deflection_deg.value * kDeg;
    dc.settling_band = c.settling_band.given ? c.settling_band.value : 0.0;
    f.depth_control = dc;
  }
  return f;
}

}  // namespace

void check_body(const BodySpec& b, Diagnostics& d) {
  check_positive(b.mass, d);
  check_inertia(b.inertia, d);
  check_non_negative(b.volume, d);
  check_psd6(b.added_mass, d);
  check_diagonal_non_negative(b.linear_damping, d);
  check_diagonal_non_negative(b.quadratic_damping, d);
  for (const auto& s : b.spheres) check_sphere(s, d);
  for (const auto& c : b.cylinders) check_cylinder(c, d);
  for (const auto& s : b.surfaces) check_surface(s, d);
  for (const auto& th : b.thrusters) {
    check_nonzero(th.direction, d);
    check_increasing(th.force, "times", d);
  }
}

Body build_body(const BodySpec& b, const Fluid& fluid) {
  Body body;
  if (b.name.given) body.name = b.name.value;
  body.lower_link_point = b.lower_link_point.value;
  body.mass = b.mass.value;
  body.inertia_cg = b.inertia.value;
  body.cg = b.center_of_gravity.value;
  body.link_point = b.link_point.value;
  body.volume = b.volume.value;
  body.cb = b.center_of_buoyancy.given ? b.center_of_buoyancy.value : body.cg;
  body.added_mass = b.added_mass.value;
  body.linear_damping = b.linear_damping.value;
  body.quadratic_damping = b.quadratic_damping.value;
  for (const auto& s : b.spheres)
    body.spheres.push_back(SphereLoad{s.center.value, s.radius.value, s.drag.value, s.added_mass.value});
  for (const auto& c : b.cylinders)
    body.cylinders.push_back(CylinderLoad{c.center.value, c.axis.value.normalized(), c.length.value, c.diameter.value,
                                          c.normal_drag.value, c.axial_drag.value, c.added_mass.value});
  for (const auto& s : b.surfaces) body.surfaces.push_back(build_surface(s));
  for (const auto& th : b.thrusters) {
    Thruster t{th.point.value, th.direction.value.normalized(), {}, {}};
    for (const auto& row : th.force) t.time.push_back(row.values[0]), t.force.push_back(row.values[1]);
    body.thrusters.push_back(t);
  }
  body.initial_attitude = attitude(b.initial_attitude_deg.value);
  finalize_body(body, fluid);
  return body;
}

}  // namespace towsim::scenario
