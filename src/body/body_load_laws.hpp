// A body's load laws (docs/theory.md §4), each written once: the force it
// applies and, for the stage solve's local Jacobian, that force's slope.
// With the slope (kSlope) a law groups its factors as its derivative does,
// so the force agrees with the value path's to round-off, not bit for bit.
// body_loads (body_loads.cpp) sums the forces of one visit, and
// body_load_derivatives (src/dynamics/implicit.cpp) the derivatives of the
// same visit, so a law's value and its derivative cannot drift apart.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>

#include "towsim/hydro/loads.hpp"
#include "towsim/model/table.hpp"

namespace towsim::body_laws {

/// A force at a point c of the body that depends on the point's velocity
/// relative to the water u = v_O + w x c - U(O_t + c) [m/s, R_g] and on the
/// body's axes: the force F [N, R_g] and, when asked for, its slope
/// A = dF/du [N s/m] (zero otherwise).
struct PointLoad {
  Vec3 F = Vec3::Zero();
  Mat3 A = Mat3::Zero();
};

/// u at the body point c (from O_t, R_g) at time t [m/s, R_g].
inline Vec3 relative_velocity(const Fluid& fluid, const BodyWork& bw, const Vec3& c, double t) {
  return bw.vO + bw.w.cross(c) - fluid.velocity(bw.O + c, t);
}

/// A sphere's drag F = -k |u| u, k = rho Cd pi r^2 / 2; A = -k (|u| I + u u^T / |u|).
/// (With kSlope the factors are grouped as in the slope: F agrees to round-off.)
template <bool kSlope>
PointLoad sphere_drag(const Fluid& fluid, const SphereLoad& sp, const Vec3& u) {
  PointLoad p;
  const double un = u.norm();
  if constexpr (kSlope) {
    const double k = 0.5 * fluid.rho * sp.drag * std::numbers::pi * sp.radius * sp.radius;  // [kg/m]
    if (un == 0) return p;
    p.F = -k * un * u;
    p.A = -k * (un * Mat3::Identity() + u * u.transpose() / un);
  } else {
    const double area = std::numbers::pi * sp.radius * sp.radius;  // [m^2]
    p.F = -0.5 * fluid.rho * sp.drag * area * un * u;
  }
  return p;
}

/// A slender cylinder of axis a [R_g]: normal drag -k_n |u_n| u_n on
/// u_n = P_a u, P_a = I - a a^T, and axial friction -k_a |u_a| u_a a, u_a = u.a;
/// A = -2 k_a |u_a| a a^T - k_n (|u_n| P_a + u_n u_n^T / |u_n|).
template <bool kSlope>
PointLoad cylinder_drag(const Fluid& fluid, const CylinderLoad& cy, const Vec3& a, const Vec3& u) {
  PointLoad p;
  const double rho = fluid.rho;
  const double kn = 0.5 * rho * cy.normal_drag * cy.diameter * cy.length;                    // [kg/m]
  const double ka = 0.5 * rho * std::numbers::pi * cy.diameter * cy.length * cy.axial_drag;  // [kg/m]
  const double ua = u.dot(a);
  if constexpr (kSlope) {
    const Mat3 Pa = Mat3::Identity() - a * a.transpose();
    const Vec3 un = Pa * u;
    const double unn = un.norm();
    p.F = -kn * unn * un - ka * std::abs(ua) * ua * a;
    p.A = -2 * ka * std::abs(ua) * a * a.transpose();
    if (unn > 0) p.A -= kn * (unn * Pa + un * un.transpose() / unn);
  } else {
    const Vec3 un = u - ua * a;
    p.F = -kn * un.norm() * un;
    p.F -= ka * std::abs(ua) * ua * a;
  }
  return p;
}

/// dCL/dalpha of lift_coefficient [1/rad] (either side's slope at its kinks).
inline double lift_coefficient_slope(const LiftingSurface& ls, double alpha) {
  // Reverse flow: CL(alpha) = -CL(sgn(alpha) (pi - |alpha|)), whose slope in
  // alpha is +CL'(mirrored).
  const double half = std::numbers::pi / 2;
  if (std::abs(alpha) > half)
    return lift_coefficient_slope(ls, (alpha > 0 ? 1 : -1) * (std::numbers::pi - std::abs(alpha)));
  const double as = ls.stall_angle;
  if (std::abs(alpha) <= as) return ls.lift_slope;
  // Past stall: CL = sgn(alpha) a as cos(s pi/2), s = (|alpha| - as)/(pi/2 - as).
  const double s = (std::abs(alpha) - as) / (half - as);
  return -ls.lift_slope * as * std::sin(s * half) * half / (half - as);
}

/// A lifting surface at deflection d [rad], flow f (surface_flow, speed >= 1e-12):
/// lift and drag from its local angle of attack, F = q A (C_L l - C_D u_p / |u_p|),
/// l = s x u_p / |u_p| (u_p: the velocity in the surface's plane, s its span).
/// Slope: with k = rho A / 2, F = k |u_p| (C_L s x u_p - C_D u_p); alpha =
/// atan2(-u_p.n, u_p.c) has gradient P (-x n - y c) / (x^2 + y^2), x = u_p.c,
/// y = -u_p.n, P the projector onto the surface's plane.
template <bool kSlope>
PointLoad surface_force(const Fluid& fluid, const LiftingSurface& ls, double d, const SurfaceFlow& f,
                        const BodyWork& bw) {
  PointLoad p;
  const double alpha = f.alpha;
  const double cl = lift_coefficient(ls, alpha);
  const double as = ls.stall_angle;
  double cd = ls.drag0 + ls.induced_drag * cl * cl;
  const double sa = std::abs(std::sin(alpha));
  const bool stalled = std::abs(alpha) > as;
  if (stalled) cd += 2 * (sa * sa - std::sin(as) * std::sin(as));
  if constexpr (kSlope) {
    const Vec3 chord = bw.R * (std::cos(d) * ls.chord + std::sin(d) * ls.normal);
    const Vec3 normal = bw.R * (-std::sin(d) * ls.chord + std::cos(d) * ls.normal);
    const Mat3 P = Mat3::Identity() - f.span * f.span.transpose();
    const double x = f.up.dot(chord), y = -f.up.dot(normal);
    const Vec3 g = P * (-x * normal - y * chord) / (x * x + y * y);  // d alpha / du [s/m]
    const double dcl = lift_coefficient_slope(ls, alpha);
    double dcd = 2 * ls.induced_drag * cl * dcl;
    if (stalled) dcd += 2 * std::sin(2 * alpha);
    const Vec3 sxu = f.span.cross(f.up);
    const double k = 0.5 * fluid.rho * ls.area, v = f.speed;
    p.F = k * v * (cl * sxu - cd * f.up);
    p.A = k * ((cl * sxu - cd * f.up) * f.up.transpose() / v +
               v * ((dcl * sxu - dcd * f.up) * g.transpose() + cl * skew(f.span) * P - cd * P));
  } else {
    const double qA = 0.5 * fluid.rho * f.speed * f.speed * ls.area;  // [N]
    const Vec3 lift_dir = f.span.cross(f.up) / f.speed;
    p.F = qA * (cl * lift_dir - cd * f.up / f.speed);
  }
  return p;
}

/// Every load law of body b at time t, in a fixed order, each as the kind of
/// force it is (c: the point from O_t [m, R_g]; F [N, R_g]):
///   v.world(c, F)      a force fixed in R_g (gravity at the CG, buoyancy at
///                      the centre of the displaced volume);
///   v.turning(c, F)    a force turning with the body (thrusters);
///   v.waves(c, F, rV)  Froude-Krylov rho V a_w(O_t + c), rV = rho V [kg];
///   v.flow(c, u, p)    a velocity-dependent point load (spheres, cylinders,
///                      surfaces; u is given with kSlope only, else zero);
///   v.damping(xr, nur, tau, T)  generic damping tau(nu_r) [N; N m, body
///                      frame] on nu_r = (R^T xr; R^T w), xr = v_O - U(O_t),
///                      with kSlope its slope T = -dtau/dnu_r.
template <bool kSlope, class Visitor>
void visit_body_loads(const Fluid& fluid, const Body& b, double t, const BodyWork& bw, Visitor& v) {
  const double rho = fluid.rho, g = fluid.g;
  v.world(Vec3(bw.R * b.cg), Vec3(0, 0, -b.mass * g));
  v.world(Vec3(bw.R * b.buoyancy_center), Vec3(0, 0, rho * g * b.displaced_volume));
  // Thrusters (they push in vacuum too).
  for (const Thruster& th : b.thrusters)
    v.turning(Vec3(bw.R * th.point), Vec3(interpolate(th.time, th.force, t) * (bw.R * th.direction)));
  if (rho == 0) return;
  // Waves: Froude-Krylov force rho V a_w at the centre of the displaced volume
  // (the added mass's part is in body_inertia through rate_seen).
  if (fluid.waves) {
    const Vec3 cb = bw.R * b.buoyancy_center;
    const double rV = rho * b.displaced_volume;
    v.waves(cb, Vec3(rV * fluid.acceleration(bw.O + cb, t)), rV);
  }
  for (const SphereLoad& sp : b.spheres) {
    const Vec3 c = bw.R * sp.center, u = relative_velocity(fluid, bw, c, t);
    v.flow(c, u, sphere_drag<kSlope>(fluid, sp, u));
  }
  for (const CylinderLoad& cy : b.cylinders) {
    const Vec3 c = bw.R * cy.center, u = relative_velocity(fluid, bw, c, t);
    v.flow(c, u, cylinder_drag<kSlope>(fluid, cy, bw.R * cy.axis, u));
  }
  // Surfaces: deflection from the depth controller's state, else from the table.
  for (std::size_t j = 0; j < b.surfaces.size(); ++j) {
    const LiftingSurface& ls = b.surfaces[j];
    const double d = current_deflection(b, j, bw, t);
    const SurfaceFlow f = surface_flow(fluid, ls, d, t, bw);
    if (f.speed < 1e-12) continue;
    const Vec3 c = bw.R * ls.center;
    const Vec3 u = kSlope ? relative_velocity(fluid, bw, c, t) : Vec3::Zero();
    v.flow(c, u, surface_force<kSlope>(fluid, ls, d, f, bw));
  }
  // Generic damping on the body-frame velocity relative to the water:
  // tau = -D_l nu_r - D_q |nu_r| nu_r, T = D_l + D_q diag(2 |nu_r|).
  if (b.damped) {
    const Vec3 xr = bw.vO - fluid.velocity(bw.O, t);
    Vec6 nur;
    nur << bw.R.transpose() * xr, bw.R.transpose() * bw.w;
    const Vec6 tau = -b.linear_damping * nur - b.quadratic_damping * nur.cwiseAbs().cwiseProduct(nur);
    Mat6 T = Mat6::Zero();
    if constexpr (kSlope) T = b.linear_damping + b.quadratic_damping * (2 * nur.cwiseAbs()).asDiagonal();
    v.damping(xr, nur, tau, T);
  }
}

}  // namespace towsim::body_laws
