// Inertia and external loads of the towed body (docs/theory.md §4; paper section 4).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "body_load_laws.hpp"
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

/// The sum of a body's load laws (body_laws::visit_body_loads): F_b and M_b
/// about O_t [N, N m, R_g].
struct LoadSum {
  BodyWork& ws;
  void world(const Vec3& c, const Vec3& F) const { add_force(ws, c, F); }
  void turning(const Vec3& c, const Vec3& F) const { add_force(ws, c, F); }
  void waves(const Vec3& c, const Vec3& F, double /*rV*/) const { add_force(ws, c, F); }
  void flow(const Vec3& c, const Vec3& /*u*/, const body_laws::PointLoad& p) const { add_force(ws, c, p.F); }
  void damping(const Vec3& /*xr*/, const Vec6& /*nur*/, const Vec6& tau, const Mat6& /*T*/) const {
    ws.Fb += ws.R * tau.head<3>();
    ws.Mb += ws.R * tau.tail<3>();
  }
};
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
  ws.Fb.setZero();
  ws.Mb.setZero();
  LoadSum sum{ws};
  body_laws::visit_body_loads<false>(fluid, b, t, ws, sum);
}

}  // namespace towsim
