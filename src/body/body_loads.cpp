// Inertia and external loads of the towed body (docs/theory.md §4; paper section 4).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "towsim/hydro/loads.hpp"
#include "towsim/model/table.hpp"

namespace towsim {

namespace {
/// Block-diagonal rotation of a 6-vector: [R a; R b].
Vec6 rotate6(const Mat3& R, const Vec6& v) {
  Vec6 out;
  out << R * v.head<3>(), R * v.tail<3>();
  return out;
}

/// Add a force F applied at point c (relative to O_t, R_g) to the body loads.
void add_force(BodyWork& ws, const Vec3& c, const Vec3& F) {
  ws.Fb += F;
  ws.Mb += c.cross(F);
}

/// Drag of a sphere load.
void sphere_loads(const Fluid& fluid, const SphereLoad& sp, double t, BodyWork& ws) {
  const Vec3 c = ws.R * sp.center;
  const Vec3 ur = ws.vO + ws.w.cross(c) - fluid.velocity(ws.O + c, t);
  const double area = std::numbers::pi * sp.radius * sp.radius;
  add_force(ws, c, -0.5 * fluid.rho * sp.drag * area * ur.norm() * ur);
}

/// Normal drag and axial skin friction of a slender cylinder load.
void cylinder_loads(const Fluid& fluid, const CylinderLoad& cy, double t, BodyWork& ws) {
  const Vec3 c = ws.R * cy.center;
  const Vec3 a = ws.R * cy.axis;
  const Vec3 u = ws.vO + ws.w.cross(c) - fluid.velocity(ws.O + c, t);
  const double ua = u.dot(a);
  const Vec3 un = u - ua * a;
  const double rho = fluid.rho;
  Vec3 F = -0.5 * rho * cy.normal_drag * cy.diameter * cy.length * un.norm() * un;
  F -= 0.5 * rho * std::numbers::pi * cy.diameter * cy.length * cy.axial_drag * std::abs(ua) * ua * a;
  add_force(ws, c, F);
}

/// Lift and drag of a lifting surface from its local angle of attack.
/// d: the surface's deflection [rad].
void surface_loads(const Fluid& fluid, const LiftingSurface& ls, double d, double t, BodyWork& ws) {
  const SurfaceFlow f = surface_flow(fluid, ls, d, t, ws);
  if (f.speed < 1e-12) return;
  const double alpha = f.alpha;
  const double cl = lift_coefficient(ls, alpha);
  const double as = ls.stall_angle;
  double cd = ls.drag0 + ls.induced_drag * cl * cl;
  const double sa = std::abs(std::sin(alpha));
  if (std::abs(alpha) > as) cd += 2 * (sa * sa - std::sin(as) * std::sin(as));
  const double qA = 0.5 * fluid.rho * f.speed * f.speed * ls.area;
  const Vec3 lift_dir = f.span.cross(f.up) / f.speed;
  add_force(ws, ws.R * ls.center, qA * (cl * lift_dir - cd * f.up / f.speed));
}
}  // namespace

SurfaceFlow surface_flow(const Fluid& fluid, const LiftingSurface& ls, double d, double t, const BodyWork& ws) {
  SurfaceFlow f;
  const Vec3 c = ws.R * ls.center;
  f.span = ws.R * ls.chord.cross(ls.normal);
  // Deflection d: chord and normal turn by +d about the span axis
  // (chord x normal), the leading edge towards +normal, so that with the flow
  // along the undeflected chord alpha = +d and the lift points to +normal.
  const Vec3 chord = ws.R * (std::cos(d) * ls.chord + std::sin(d) * ls.normal);
  const Vec3 normal = ws.R * (-std::sin(d) * ls.chord + std::cos(d) * ls.normal);
  const Vec3 u = ws.vO + ws.w.cross(c) - fluid.velocity(ws.O + c, t);
  f.up = u - u.dot(f.span) * f.span;  // velocity in the surface's plane
  f.speed = f.up.norm();
  if (f.speed >= 1e-12) f.alpha = std::atan2(-f.up.dot(normal), f.up.dot(chord));
  return f;
}

double lift_coefficient(const LiftingSurface& ls, double alpha) {
  // Reverse flow (|alpha| > 90 deg) mirrors the forward curve.
  const double half = std::numbers::pi / 2;
  if (std::abs(alpha) > half) {
    const double mirrored = (alpha > 0 ? 1 : -1) * (std::numbers::pi - std::abs(alpha));
    return -lift_coefficient(ls, mirrored);
  }
  const double as = ls.stall_angle;
  if (std::abs(alpha) <= as) return ls.lift_slope * alpha;
  // Past stall: falls as a cosine from CL_max at stall to zero at 90 degrees.
  const double s = (std::abs(alpha) - as) / (half - as);
  return (alpha > 0 ? 1 : -1) * ls.lift_slope * as * std::cos(s * half);
}

double current_deflection(const Body& b, std::size_t j, const BodyWork& ws, double t) {
  const LiftingSurface& ls = b.surfaces[j];
  if (!ls.depth_control) return surface_deflection(ls, t);
  // The controller's index: controlled surfaces before j.
  std::size_t c = 0;
  for (std::size_t i = 0; i < j; ++i) c += b.surfaces[i].depth_control ? 1 : 0;
  return ws.deflection[c];
}

double surface_deflection(const LiftingSurface& ls, double t) {
  if (ls.deflection_angle.empty()) return 0;
  return interpolate(ls.deflection_time, ls.deflection_angle, t);
}

void body_inertia(const Fluid& fluid, const Body& b, BodyWork& ws, double t) {
  const Mat3& R = ws.R;
  // Body-frame velocities, absolute and relative to the water at O_t.
  const Vec3 vb = R.transpose() * ws.vO;
  const Vec3 wb = R.transpose() * ws.w;
  const Vec3 vr = R.transpose() * (ws.vO - fluid.velocity(ws.O, t));
  // Rate of change of the water velocity seen by O_t as it moves.
  const Vec3 dU = R.transpose() * fluid.rate_seen(ws.O, ws.vO, t);
  Vec6 nu, nur;
  nu << vb, wb;
  nur << vr, wb;
  // Kirchhoff: rigid part with nu, fluid part with nu_r (body-frame rates of
  // change of the velocities contribute -w x v).
  const Vec6 PR = b.rigid_mass * nu;
  const Vec6 PA = b.fluid_mass * nur;
  Vec6 dnu, dnur, h;
  dnu << -wb.cross(vb), Vec3::Zero();
  dnur << -dU - wb.cross(vr), Vec3::Zero();
  h = b.rigid_mass * dnu + b.fluid_mass * dnur;
  h.head<3>() += wb.cross(PR.head<3>()) + wb.cross(PA.head<3>());
  h.tail<3>() += wb.cross(PR.tail<3>()) + vb.cross(PR.head<3>()) + wb.cross(PA.tail<3>()) + vr.cross(PA.head<3>());
  // To R_g: B M B^T with B = diag(R, R), block by block (R M_ij R^T).
  const Mat6& M = b.total_mass;
  ws.Mw.topLeftCorner<3, 3>().noalias() = R * M.topLeftCorner<3, 3>() * R.transpose();
  ws.Mw.topRightCorner<3, 3>().noalias() = R * M.topRightCorner<3, 3>() * R.transpose();
  ws.Mw.bottomLeftCorner<3, 3>().noalias() = R * M.bottomLeftCorner<3, 3>() * R.transpose();
  ws.Mw.bottomRightCorner<3, 3>().noalias() = R * M.bottomRightCorner<3, 3>() * R.transpose();
  ws.hw = rotate6(R, h);
}

void body_loads(const Fluid& fluid, const Body& b, double t, BodyWork& ws) {
  const double rho = fluid.rho, g = fluid.g;
  ws.Fb.setZero();
  ws.Mb.setZero();
  // Gravity at the CG, buoyancy at the centre of the displaced volume.
  add_force(ws, ws.R * b.cg, Vec3(0, 0, -b.mass * g));
  add_force(ws, ws.R * b.buoyancy_center, Vec3(0, 0, rho * g * b.displaced_volume));
  // Thrusters (they push in vacuum too).
  for (const Thruster& th : b.thrusters)
    add_force(ws, ws.R * th.point, interpolate(th.time, th.force, t) * (ws.R * th.direction));
  if (rho == 0) return;
  // Waves: Froude-Krylov force rho V a_w at the centre of the displaced volume
  // (the added mass's part is in body_inertia through rate_seen).
  if (fluid.waves) {
    const Vec3 cb = ws.R * b.buoyancy_center;
    add_force(ws, cb, rho * b.displaced_volume * fluid.acceleration(ws.O + cb, t));
  }
  for (const auto& sp : b.spheres) sphere_loads(fluid, sp, t, ws);
  for (const auto& cy : b.cylinders) cylinder_loads(fluid, cy, t, ws);
  // Surfaces: deflection from the depth controller's state, else from the table.
  for (std::size_t j = 0; j < b.surfaces.size(); ++j)
    surface_loads(fluid, b.surfaces[j], current_deflection(b, j, ws, t), t, ws);
  // Generic damping on the body-frame velocity relative to the water.
  if (b.damped) {
    Vec6 nur;
    nur << ws.R.transpose() * (ws.vO - fluid.velocity(ws.O, t)), ws.R.transpose() * ws.w;
    const Vec6 tau = -b.linear_damping * nur - b.quadratic_damping * nur.cwiseAbs().cwiseProduct(nur);
    ws.Fb += ws.R * tau.head<3>();
    ws.Mb += ws.R * tau.tail<3>();
  }
}

}  // namespace towsim
