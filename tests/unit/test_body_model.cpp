// The towed body's model (finalize_body, body_loads, body_inertia,
// lift_coefficient, surface_deflection) against hand calculations, energy
// identities and finite differences of Kirchhoff's momenta (docs/theory.md §4,
// theory.md 4).
//
// Tolerances: hand values to 1e-12 relative (a few roundings of O(1-1000)
// numbers); finite differences within 2 (h^2/6 |f'''|) + 8 eps |f| / h (the
// central-difference truncation with |f'''| estimated on a wider stencil,
// plus round-off), see fd_with_bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "../support/fd.hpp"
#include "towsim/dynamics/state.hpp"
#include "towsim/hydro/loads.hpp"

namespace {

using towsim::Body;
using towsim::CylinderLoad;
using towsim::LiftingSurface;
using towsim::Mat3;
using towsim::Mat6;
using towsim::Model;
using towsim::PhysicalState;
using towsim::Quat;
using towsim::SphereLoad;
using towsim::Vec3;
using towsim::Vec6;
using towsim::Workspace;
using towsim::testing::fd_richardson;
using towsim::testing::fd_with_bound;

constexpr double pi = std::numbers::pi;

void report(const char* what, double err, double tol) {
  std::printf("[measured] %-58s max err %.3e  (tol %.3e)\n", what, err, tol);
}

/// A body model with no cable, no loads, nothing but what the test sets.
Model body_model(double rho = 1025, double g = 9.81) {
  Model m;
  m.fluid.rho = rho;
  m.fluid.g = g;
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 0;
  b.inertia_cg.setZero();
  b.cg.setZero();
  b.link_point.setZero();
  return m;
}

/// Body kinematics for body_loads / body_inertia (what compute_kinematics sets).
struct BodyState {
  PhysicalState s;
  Workspace ws;
  BodyState(const Model& m, const Mat3& R, const Vec3& O, const Vec3& vO, const Vec3& w)
      : s(PhysicalState::hanging(m)), ws(m) {
    s.bodies[0].q = Quat(R);
    s.bodies[0].w = w;
    ws.body[0].R = R;
    ws.body[0].O = O;
    ws.body[0].vO = vO;
    ws.body[0].w = w;
  }
};

struct Loads6 {
  Vec3 F, M;
};
Loads6 body_loads(const Model& m, const Mat3& R, const Vec3& O, const Vec3& vO, const Vec3& w, double t = 0) {
  BodyState st(m, R, O, vO, w);
  towsim::body_loads(m.fluid, m.bodies[0], t, st.ws.body[0]);
  return {st.ws.body[0].Fb, st.ws.body[0].Mb};
}

Mat3 rotation(double roll, double pitch, double yaw) {
  return towsim::quat_from_rpy(roll, pitch, yaw).toRotationMatrix();
}

}  // namespace

// ------------------------------------------------------------ finalize_body

// m = 10, r_G = (0.1, -0.2, 0.3), I_G non-diagonal. By hand:
//   p = m (v + w x c) = m v - m [c]x w   -> top right  -m [c]x
//   l_O = I_G w + c x p                    -> bottom left m [c]x,
//   bottom right I_G + m (|c|^2 I - c c^T)  (parallel axes), with
//   m [c]x = [[0,-3,-2],[3,0,-1],[2,1,0]], m (|c|^2 I - cc^T) =
//   [[1.3,0.2,-0.3],[0.2,1.0,0.6],[-0.3,0.6,0.5]].
TEST(BodyModel, RigidMassAboutOriginWithOffsetCg) {
  Model m = body_model();
  Body& b = m.bodies[0];
  b.mass = 10;
  b.cg = Vec3(0.1, -0.2, 0.3);
  b.inertia_cg << 2, 0.1, -0.05, 0.1, 3, 0.2, -0.05, 0.2, 4;
  towsim::finalize_body(b, m.fluid);
  Mat6 expect;
  expect << 10, 0, 0, 0, 3, 2,     //
      0, 10, 0, -3, 0, 1,          //
      0, 0, 10, -2, -1, 0,         //
      0, -3, -2, 3.3, 0.3, -0.35,  //
      3, 0, -1, 0.3, 4.0, 0.8,     //
      2, 1, 0, -0.35, 0.8, 4.5;
  const double err = (b.rigid_mass - expect).cwiseAbs().maxCoeff();
  report("RigidMassAboutOrigin entries vs hand", err, 1e-13);
  EXPECT_LE(err, 1e-13);
  EXPECT_EQ(b.fluid_mass, Mat6::Zero());
  EXPECT_EQ(b.displaced_volume, 0.0);
  EXPECT_EQ(b.buoyancy_center, b.cg);  // no volume: buoyancy (zero) put at the CG
  // Kinetic energy: 1/2 nu^T M nu = 1/2 m |v + w x c|^2 + 1/2 w^T I_G w.
  std::mt19937 rng(3);
  std::normal_distribution<double> N(0, 1);
  for (int i = 0; i < 10; ++i) {
    Vec6 nu;
    for (int k = 0; k < 6; ++k) nu(k) = N(rng);
    const Vec3 v = nu.head<3>(), w = nu.tail<3>();
    const double T = 0.5 * 10 * (v + w.cross(b.cg)).squaredNorm() + 0.5 * w.dot(b.inertia_cg * w);
    EXPECT_NEAR(0.5 * nu.dot(b.rigid_mass * nu), T, 1e-13 * (1 + T));
  }
}

// Sphere: added mass Ca rho V as a point mass at its centre c. rho = 1000,
// r = 0.1, Ca = 0.5: ma = 2 pi / 3. c = (0.5, 0, -0.2):
//   -[c]x = [[0,-0.2,0],[0.2,0,0.5],[0,-0.5,0]],
//   |c|^2 I - cc^T = [[0.04,0,0.1],[0,0.29,0],[0.1,0,0.25]].
// The user's 6x6 added mass adds to it.
TEST(BodyModel, SphereAddedMassIsPointMassAtCentre) {
  Model m = body_model(1000);
  Body& b = m.bodies[0];
  b.mass = 5;
  b.inertia_cg = Mat3::Identity();
  b.spheres.push_back(SphereLoad{Vec3(0.5, 0, -0.2), 0.1, 0.5, 0.5});
  b.added_mass.diagonal() << 1, 2, 3, 4, 5, 6;
  towsim::finalize_body(b, m.fluid);
  const double ma = 2 * pi / 3;
  Mat6 expect;
  expect << 1, 0, 0, 0, -0.2, 0,  //
      0, 1, 0, 0.2, 0, 0.5,       //
      0, 0, 1, 0, -0.5, 0,        //
      0, 0.2, 0, 0.04, 0, 0.1,    //
      -0.2, 0, -0.5, 0, 0.29, 0,  //
      0, 0.5, 0, 0.1, 0, 0.25;
  expect *= ma;
  expect.diagonal() += Vec6(1, 2, 3, 4, 5, 6);
  const double err = (b.fluid_mass - expect).cwiseAbs().maxCoeff();
  report("SphereAddedMass entries vs hand", err, 1e-13);
  EXPECT_LE(err, 1e-13);
}

// Cylinder: ma = Ca rho pi D^2/4 L normal to its axis, ma L^2/12 about the
// normal axes, at its centre: 1/2 nu^T M nu = 1/2 vc^T A vc + 1/2 w^T B w with
// vc = v + w x c, A = ma (I - aa^T), B = ma L^2/12 (I - aa^T).
TEST(BodyModel, CylinderAddedMassAtCentre) {
  Model m = body_model(1000);
  Body& b = m.bodies[0];
  const Vec3 a = Vec3(1, 2, -0.5).normalized(), c(-0.3, 0.1, 0.2);
  b.cylinders.push_back(CylinderLoad{c, a, 1.2, 0.15, 1.2, 0.01, 1.0});
  towsim::finalize_body(b, m.fluid);
  const double ma = 1000 * pi * 0.15 * 0.15 / 4 * 1.2;
  const Mat3 A = ma * (Mat3::Identity() - a * a.transpose()), B = A * 1.2 * 1.2 / 12;
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0, 1);
  double err = 0;
  for (int i = 0; i < 10; ++i) {
    Vec6 nu;
    for (int k = 0; k < 6; ++k) nu(k) = N(rng);
    const Vec3 v = nu.head<3>(), w = nu.tail<3>(), vc = v + w.cross(c);
    const double T = 0.5 * vc.dot(A * vc) + 0.5 * w.dot(B * w);
    err = std::max(err, std::abs(0.5 * nu.dot(b.fluid_mass * nu) - T) / (1 + T));
  }
  report("CylinderAddedMass kinetic energy (relative)", err, 1e-13);
  EXPECT_LE(err, 1e-13);
  EXPECT_LE((b.fluid_mass - b.fluid_mass.transpose()).norm(), 1e-12);
}

// Displaced volume: volume 0.02 at (-0.05, 0, 0.03), sphere r = 0.1 at
// (0.3, 0, 0): 4/3 pi 1e-3, cylinder D = 0.15, L = 1.2 at (-0.2, 0, 0.1):
// pi 0.0225/4 * 1.2 = 0.00675 pi. Centre = volume-weighted mean.
TEST(BodyModel, DisplacedVolumeAndBuoyancyCentre) {
  Model m = body_model();
  Body& b = m.bodies[0];
  b.mass = 40;
  b.cg = Vec3(0.1, 0, 0);
  b.volume = 0.02;
  b.cb = Vec3(-0.05, 0, 0.03);
  b.spheres.push_back(SphereLoad{Vec3(0.3, 0, 0), 0.1, 0.5, 0.5});
  b.cylinders.push_back(CylinderLoad{Vec3(-0.2, 0, 0.1), Vec3::UnitX(), 1.2, 0.15, 1.2, 0.01, 1.0});
  towsim::finalize_body(b, m.fluid);
  const double Vs = 4.0 / 3.0 * pi * 1e-3, Vc = 0.00675 * pi, V = 0.02 + Vs + Vc;
  const Vec3 cb = (0.02 * Vec3(-0.05, 0, 0.03) + Vs * Vec3(0.3, 0, 0) + Vc * Vec3(-0.2, 0, 0.1)) / V;
  EXPECT_NEAR(b.displaced_volume, V, 1e-16);
  EXPECT_LE((b.buoyancy_center - cb).norm(), 1e-15);
  EXPECT_NEAR(V, 0.0453945406, 1e-10);  // 0.02 + 0.0041887902 + 0.0212057504
}

// ------------------------------------------------------------ body_loads

// Gravity at the CG and buoyancy at the centre of buoyancy, moments about O_t.
// Identity attitude, m = 40, r_G = (0.1, 0, -0.05), V = 0.05 at
// r_B = (-0.1, 0.02, 0.1), rho = 1025, g = 9.81: W = 392.4, B = 502.7625.
// (x, y, z) x (0, 0, f) = (y f, -x f, 0):
// M = (0, 0.1 W, 0) + (0.02 B, 0.1 B, 0) = (10.05525, 89.51625, 0).
TEST(BodyModel, GravityAndBuoyancyMomentAboutOrigin) {
  Model m = body_model(1025, 9.81);
  Body& b = m.bodies[0];
  b.mass = 40;
  b.cg = Vec3(0.1, 0, -0.05);
  b.volume = 0.05;
  b.cb = Vec3(-0.1, 0.02, 0.1);
  towsim::finalize_body(b, m.fluid);
  const Vec3 O(5, -3, -40);
  Loads6 l = body_loads(m, Mat3::Identity(), O, Vec3::Zero(), Vec3::Zero());
  EXPECT_LE((l.F - Vec3(0, 0, 502.7625 - 392.4)).norm(), 1e-12);
  EXPECT_LE((l.M - Vec3(10.05525, 89.51625, 0)).norm(), 1e-12);
  // Any attitude: lever arms R r_G, R r_B; the moment has no z component.
  const Mat3 R = rotation(0.2, -0.4, 1.1);
  l = body_loads(m, R, O, Vec3::Zero(), Vec3::Zero());
  const Vec3 g = R * b.cg, c = R * b.cb;
  const Vec3 M = Vec3(g.y() * -392.4, -g.x() * -392.4, 0) + Vec3(c.y() * 502.7625, -c.x() * 502.7625, 0);
  EXPECT_LE((l.F - Vec3(0, 0, 502.7625 - 392.4)).norm(), 1e-12);
  EXPECT_LE((l.M - M).norm(), 1e-12);
}

// Sphere drag -1/2 rho Cd pi r^2 |u| u at the centre c, u = v_O + w x c - U(z_c).
// rho = 1000, r = 0.1, Cd = 0.5: k = 2.5 pi. Identity attitude, c = (0.5, 0, 0),
// v_O = (1, 0, 0), w = (0, 0, 2): w x c = (0, 1, 0), u = (1, 1, 0),
// F = -k sqrt2 (1, 1, 0), M = c x F = -k sqrt2 (0, 0, 0.5). g = 0 here.
TEST(BodyModel, SphereDragAtCentreOfRotatingBody) {
  Model m = body_model(1000, 0.0);
  m.bodies[0].mass = 3;
  m.bodies[0].spheres.push_back(SphereLoad{Vec3(0.5, 0, 0), 0.1, 0.5, 0.5});
  towsim::finalize_body(m.bodies[0], m.fluid);
  const double k = 2.5 * pi, s2 = std::sqrt(2.0);
  Loads6 l = body_loads(m, Mat3::Identity(), Vec3(0, 0, -10), Vec3(1, 0, 0), Vec3(0, 0, 2));
  EXPECT_LE((l.F - (-k * s2) * Vec3(1, 1, 0)).norm(), 1e-12 * 30);
  EXPECT_LE((l.M - (-k * s2) * Vec3(0, 0, 0.5)).norm(), 1e-12 * 30);
  // Rotated body in a depth-dependent current: the current at the centre's depth.
  m.fluid.current_depth = {0, 20};
  m.fluid.current_velocity = {Vec3(1, 0, 0), Vec3(0, 0.5, 0)};
  m.bodies[0].spheres[0].center = Vec3(0.5, 0.2, -1.0);
  const Mat3 R = rotation(0.3, 0.5, -0.7);
  const Vec3 O(2, 1, -10), vO(1.5, -0.3, 0.2), w(0.4, -0.9, 0.6);
  l = body_loads(m, R, O, vO, w);
  const Vec3 c = R * Vec3(0.5, 0.2, -1.0);
  const double depth = -(O.z() + c.z());
  const Vec3 U = (1 - depth / 20) * Vec3(1, 0, 0) + depth / 20 * Vec3(0, 0.5, 0);
  const Vec3 u = vO + w.cross(c) - U;
  const Vec3 F = -k * u.norm() * u;
  const double err = std::max((l.F - F).norm(), (l.M - c.cross(F)).norm());
  report("SphereDrag rotating body in a current", err, 1e-12 * 100);
  EXPECT_LE(err, 1e-12 * 100);
}

// Slender cylinder on the body: -1/2 rho Cd D L |u_n| u_n - 1/2 rho pi D L Ct
// |u.a| (u.a) a at its centre. a = x, c = (0, 0.2, 0), v_O = (2, 0, 1), w = 0:
// u.a = 2, u_n = (0, 0, 1): F = -(k_n, 0, 0)... by components below.
TEST(BodyModel, CylinderLoadsAtCentre) {
  Model m = body_model(1000, 0.0);
  m.bodies[0].cylinders.push_back(CylinderLoad{Vec3(0, 0.2, 0), Vec3::UnitX(), 1.2, 0.15, 1.2, 0.01, 1.0});
  towsim::finalize_body(m.bodies[0], m.fluid);
  const Loads6 l = body_loads(m, Mat3::Identity(), Vec3(0, 0, -5), Vec3(2, 0, 1), Vec3::Zero());
  const double kn = 0.5 * 1000 * 1.2 * 0.15 * 1.2;        // 108
  const double kt = 0.5 * 1000 * pi * 0.15 * 1.2 * 0.01;  // 0.9 pi
  const Vec3 F(-kt * 4, 0, -kn * 1);
  EXPECT_LE((l.F - F).norm(), 1e-12 * 100);
  EXPECT_LE((l.M - Vec3(0, 0.2, 0).cross(F)).norm(), 1e-12 * 100);
}

namespace {
LiftingSurface fin() {
  return LiftingSurface{Vec3(-0.7, 0, 0.1), Vec3::UnitX(), Vec3::UnitZ(), 0.1, 2 * pi, 0.26, 0.01, 0.05, {}, {}};
}
}  // namespace

// Lifting surface (chord x, normal z, span chord x normal = -y) at a small
// angle of attack alpha: moving with u = V (cos a, 0, -sin a) (the flow meets
// it from the -normal side), lift 1/2 rho V^2 A CL_a alpha normal to u towards
// +normal, i.e. along (sin a, 0, cos a), drag 1/2 rho V^2 A (CD0 + k CL^2)
// along -u. rho = 1025, V = 3, A = 0.1: q = 461.25; CL = 0.1 pi at 0.05 rad.
TEST(BodyModel, LiftingSurfaceSmallAngle) {
  Model m = body_model(1025, 0.0);
  m.bodies[0].surfaces.push_back(fin());
  towsim::finalize_body(m.bodies[0], m.fluid);
  const double V = 3, q = 461.25;
  const Vec3 c(-0.7, 0, 0.1);
  double err = 0;
  for (double a : {0.05, -0.05, 0.2}) {
    const Vec3 u = V * Vec3(std::cos(a), 0, -std::sin(a));
    const Loads6 l = body_loads(m, Mat3::Identity(), Vec3(0, 0, -10), u, Vec3::Zero());
    const double CL = 2 * pi * a, CD = 0.01 + 0.05 * CL * CL;
    const Vec3 F = q * CL * Vec3(std::sin(a), 0, std::cos(a)) - q * CD * u / V;
    err = std::max({err, (l.F - F).norm(), (l.M - c.cross(F)).norm()});
    // The same as statements: drag = -F.u/V, lift = the part normal to u, on the +normal side for a > 0.
    const Vec3 lift = l.F - l.F.dot(u / V) * u / V;
    EXPECT_NEAR(-l.F.dot(u / V), q * CD, 1e-10);
    EXPECT_NEAR(lift.norm(), q * std::abs(CL), 1e-10);
    EXPECT_EQ(lift.z() > 0, a > 0);
  }
  report("LiftingSurface small angle (identity attitude)", err, 1e-10);
  EXPECT_LE(err, 1e-10);

  // Any attitude, rotating, in a current: alpha from the body-frame velocity of
  // the centre relative to the water, projected on the chord-normal plane.
  m.fluid.current_depth = {5};
  m.fluid.current_velocity = {Vec3(0.3, -0.2, 0)};
  const Mat3 R = rotation(0.1, -0.2, 0.8);
  const Vec3 vO = R * Vec3(2.5, 0.3, 0.1) + Vec3(0.3, -0.2, 0), w = R * Vec3(0.02, 0.05, -0.03);
  const Loads6 l = body_loads(m, R, Vec3(0, 0, -10), vO, w);
  const Vec3 ub = R.transpose() * (vO + w.cross(R * c) - Vec3(0.3, -0.2, 0));
  const double a = std::atan2(-ub.z(), ub.x()), Vp = std::hypot(ub.x(), ub.z());
  ASSERT_LT(std::abs(a), 0.26);
  const double CL = 2 * pi * a, CD = 0.01 + 0.05 * CL * CL, qp = 0.5 * 1025 * Vp * Vp * 0.1;
  const Vec3 dir_u(ub.x() / Vp, 0, ub.z() / Vp);
  const Vec3 Fb = qp * CL * Vec3(-dir_u.z(), 0, dir_u.x()) - qp * CD * dir_u;  // lift: -y x dir_u
  const double err2 = std::max((l.F - R * Fb).norm(), (l.M - (R * c).cross(R * Fb)).norm());
  report("LiftingSurface rotated, rotating, current", err2, 1e-10);
  EXPECT_LE(err2, 1e-10);

  // Continuous across stall (lift and the extra post-stall drag both are).
  m.fluid.current_velocity.clear();
  m.fluid.current_depth.clear();
  auto F_at = [&](double a) {
    return body_loads(m, Mat3::Identity(), Vec3(0, 0, -10), V * Vec3(std::cos(a), 0, -std::sin(a)), Vec3::Zero()).F;
  };
  // Lipschitz: |dF/da| <= q (|CL'| + |CD'| + |CL| + |CD|) ~ q * 10: a step of 2e-9 moves F by < 1e-5.
  EXPECT_LE((F_at(0.26 + 1e-9) - F_at(0.26 - 1e-9)).norm(), 1e-5);
}

// Positive deflection about the span axis chord x normal (right-handed, as
// documented in model.hpp and scenario.md): the chord turns towards +normal,
// cos d chord + sin d normal, so flow along the undeflected chord meets the
// surface at alpha = +d and lifts it towards +normal with CL = CL_a d.
TEST(BodyModel, DeflectionRotatesAboutSpanAxis) {
  Model m = body_model(1025, 0.0);
  LiftingSurface ls = fin();
  ls.deflection_time = {0};
  ls.deflection_angle = {0.1};
  m.bodies[0].surfaces.push_back(ls);
  towsim::finalize_body(m.bodies[0], m.fluid);
  const double V = 3, q = 461.25, d = 0.1;
  const Loads6 l = body_loads(m, Mat3::Identity(), Vec3(0, 0, -10), Vec3(V, 0, 0), Vec3::Zero());
  const double CL = 2 * pi * d, CD = 0.01 + 0.05 * CL * CL;
  const Vec3 expect(-q * CD, 0, q * CL);
  report("Deflection: lift z (expected q CL_a d = +289.8)", std::abs(l.F.z() - expect.z()), 1e-9);
  EXPECT_NEAR(l.F.z(), expect.z(), 1e-9) << "lift of a surface deflected by +0.1 rad, flow along its chord";
  EXPECT_NEAR(l.F.x(), expect.x(), 1e-9);
  // Sign-independent part: the magnitudes are right either way.
  EXPECT_NEAR(std::abs(l.F.z()), q * CL, 1e-9);
}

// Linear interpolation in time, held at the ends; one row constant, none zero.
TEST(BodyModel, SurfaceDeflectionTable) {
  LiftingSurface ls = fin();
  EXPECT_EQ(towsim::surface_deflection(ls, 3), 0.0);
  ls.deflection_time = {0, 10, 20};
  ls.deflection_angle = {0, 0.1, -0.1};
  EXPECT_EQ(towsim::surface_deflection(ls, -1), 0.0);
  EXPECT_NEAR(towsim::surface_deflection(ls, 5), 0.05, 1e-16);
  EXPECT_NEAR(towsim::surface_deflection(ls, 10), 0.1, 1e-16);
  EXPECT_NEAR(towsim::surface_deflection(ls, 17.5), -0.05, 1e-16);
  EXPECT_EQ(towsim::surface_deflection(ls, 20), -0.1);
  EXPECT_EQ(towsim::surface_deflection(ls, 1e3), -0.1);
  ls.deflection_time = {4};
  ls.deflection_angle = {0.2};
  EXPECT_EQ(towsim::surface_deflection(ls, 0), 0.2);
  EXPECT_EQ(towsim::surface_deflection(ls, 9), 0.2);
}

// CL: CL_a alpha up to stall, continuous at stall, zero at 90 deg, odd in
// alpha, and (reverse flow) continuous all round [-pi, pi].
TEST(BodyModel, LiftCoefficientShape) {
  const LiftingSurface ls = fin();
  const double as = 0.26, k = 2 * pi;
  for (double a : {0.0, 0.01, 0.1, 0.25, 0.26}) EXPECT_NEAR(towsim::lift_coefficient(ls, a), k * a, 1e-15);
  EXPECT_NEAR(towsim::lift_coefficient(ls, pi / 2), 0.0, 1e-15);
  EXPECT_NEAR(towsim::lift_coefficient(ls, -pi / 2), 0.0, 1e-15);
  // Slopes: k below stall, at most k as (pi/2) / (pi/2 - as) beyond it.
  const double slope = std::max(k, k * as * (pi / 2) / (pi / 2 - as));
  const double d = 1e-9;
  EXPECT_LE(std::abs(towsim::lift_coefficient(ls, as + d) - towsim::lift_coefficient(ls, as - d)),
            2 * d * slope + 1e-15);
  double worst_step = 0, worst_odd = 0;
  const int n = 200000;
  const double da = 2 * pi / n;
  for (int i = 0; i < n; ++i) {
    const double a = -pi + i * da;
    worst_step = std::max(worst_step, std::abs(towsim::lift_coefficient(ls, a + da) - towsim::lift_coefficient(ls, a)));
    worst_odd = std::max(worst_odd, std::abs(towsim::lift_coefficient(ls, -a) + towsim::lift_coefficient(ls, a)));
  }
  // Lipschitz bound slope * da (attained below stall, where CL is linear), with
  // 1e-9 relative slack for the rounding of CL(a + da) - CL(a).
  report("LiftCoefficient: largest step on a 3.1e-5 rad grid", worst_step, slope * da * (1 + 1e-9));
  report("LiftCoefficient: |CL(-a) + CL(a)|", worst_odd, 0.0);
  EXPECT_LE(worst_step, slope * da * (1 + 1e-9));
  EXPECT_EQ(worst_odd, 0.0);
  // Past stall it falls: CL(60 deg) between 0 and CL_max.
  const double c60 = towsim::lift_coefficient(ls, pi / 3);
  EXPECT_GT(c60, 0.0);
  EXPECT_LT(c60, k * as);
}

// tau = -D_l nu_r - D_q (|nu_r| o nu_r), nu_r in body axes, applied in R_g.
// Identity attitude, nu_r = (1, -2, 0.5, 0.1, 0, -0.3), D_l = diag(5, 10, 10,
// 1, 2, 2) + 0.7 at (2,6), (6,2); D_q = diag(10, 60, 60, 1, 5, 5):
//   D_l nu_r = (5, -20.21, 5, 0.1, 0, -2.0), |nu|nu = (1, -4, 0.25, 0.01, 0, -0.09),
//   D_q .. = (10, -240, 15, 0.01, 0, -0.45): tau = (-15, 260.21, -20, -0.11, 0, 2.45).
TEST(BodyModel, LinearAndQuadraticDamping) {
  Model m = body_model(1025, 0.0);
  Body& b = m.bodies[0];
  b.linear_damping.diagonal() << 5, 10, 10, 1, 2, 2;
  b.linear_damping(1, 5) = b.linear_damping(5, 1) = 0.7;
  b.quadratic_damping.diagonal() << 10, 60, 60, 1, 5, 5;
  towsim::finalize_body(b, m.fluid);
  Loads6 l = body_loads(m, Mat3::Identity(), Vec3(0, 0, -3), Vec3(1, -2, 0.5), Vec3(0.1, 0, -0.3));
  EXPECT_LE((l.F - Vec3(-15, 260.21, -20)).norm(), 1e-12);
  EXPECT_LE((l.M - Vec3(-0.11, 0, 2.45)).norm(), 1e-13);
  // Rotated, uniform current: the same law on R^T (v - U), R^T w, mapped back by R.
  m.fluid.current_depth = {10};
  m.fluid.current_velocity = {Vec3(0.5, 0.2, 0)};
  const Mat3 R = rotation(-0.3, 0.2, 2.0);
  const Vec3 vb(1, -2, 0.5), wb(0.1, 0, -0.3);
  l = body_loads(m, R, Vec3(0, 0, -3), R * vb + Vec3(0.5, 0.2, 0), R * wb);
  EXPECT_LE((l.F - R * Vec3(-15, 260.21, -20)).norm(), 1e-12);
  EXPECT_LE((l.M - R * Vec3(-0.11, 0, 2.45)).norm(), 1e-12);
}

// A thruster: its force is the table's value along R d at R p, in vacuum as
// in water; force and moment about O_t by hand: F = T(t) R d, M = (R p) x F.
// Tolerance 1e-12 N: a rotation and a cross product of O(100) values.
TEST(BodyModel, ThrusterForceAndMoment) {
  Model m = body_model(0.0, 0.0);  // no fluid, no gravity: the thrust alone
  Body& b = m.bodies[0];
  b.thrusters.push_back({Vec3(-1.2, 0.1, -0.3), Vec3(1, 0.2, 0).normalized(), {0.0, 10.0}, {0.0, 400.0}});
  const Mat3 R = rotation(0.2, -0.4, 0.9);
  const auto l = body_loads(m, R, Vec3(0, 0, -50), Vec3::Zero(), Vec3::Zero(), 2.5);
  const Vec3 F = 100.0 * (R * Vec3(1, 0.2, 0).normalized());  // 400 N * 2.5 / 10
  const Vec3 M = (R * Vec3(-1.2, 0.1, -0.3)).cross(F);
  EXPECT_LE((l.F - F).norm(), 1e-12);
  EXPECT_LE((l.M - M).norm(), 1e-12);
  // Held at the table's end.
  const auto late = body_loads(m, R, Vec3(0, 0, -50), Vec3::Zero(), Vec3::Zero(), 99.0);
  EXPECT_NEAR(late.F.norm(), 400.0, 1e-12);
}

// Every fluid load of a body in a uniform current depends on v - U only.
TEST(BodyModel, UniformCurrentGalilean) {
  Model still = body_model(1025, 9.81);
  Body& b = still.bodies[0];
  b.mass = 40;
  b.inertia_cg = Mat3::Identity();
  b.cg = Vec3(-0.1, 0.02, -0.05);
  b.volume = 0.02;
  b.linear_damping.diagonal() << 5, 10, 10, 1, 2, 2;
  b.quadratic_damping.diagonal() << 10, 60, 60, 1, 5, 5;
  b.spheres.push_back({Vec3(0.3, 0, 0), 0.1, 0.5, 0.5});
  b.cylinders.push_back({Vec3(-0.2, 0, 0), Vec3::UnitX(), 1.2, 0.15, 1.2, 0.01, 1.0});
  b.surfaces.push_back(fin());
  towsim::finalize_body(b, still.fluid);
  Model moving = still;
  const Vec3 U(0.8, -0.5, 0.05);
  moving.fluid.current_depth = {0};
  moving.fluid.current_velocity = {U};
  std::mt19937 rng(11);
  std::normal_distribution<double> N(0, 1);
  double err = 0;
  for (int i = 0; i < 20; ++i) {
    const Mat3 R = Quat(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix();
    const Vec3 v(2 * N(rng), N(rng), N(rng)), w(0.3 * N(rng), 0.3 * N(rng), 0.3 * N(rng));
    const Loads6 a = body_loads(moving, R, Vec3(0, 0, -10), v, w), c = body_loads(still, R, Vec3(0, 0, -10), v - U, w);
    err = std::max({err, (a.F - c.F).norm() / (1 + a.F.norm()), (a.M - c.M).norm() / (1 + a.M.norm())});
  }
  report("Body loads Galilean in a uniform current (relative)", err, 1e-13);
  EXPECT_LE(err, 1e-13);
}

// ------------------------------------------------------------ body_inertia

// No added mass, CG at O_t: momentum m v_O, moment of momentum about the CG
// I_w w with I_w = R I_G R^T: d/dt = [m a_O; I_w alpha + w x (I_w w)], so
// Mw = diag(m, m, m, I_w), hw = [0; w x (I_w w)].
TEST(BodyModel, InertiaNoAddedMassCgAtOrigin) {
  Model m = body_model(1025);
  Body& b = m.bodies[0];
  b.mass = 12;
  b.inertia_cg << 2, 0.1, -0.05, 0.1, 5, 0.2, -0.05, 0.2, 5.5;
  towsim::finalize_body(b, m.fluid);
  const Mat3 R = rotation(0.4, -0.3, 1.2);
  const Vec3 w(0.3, -0.7, 0.5), vO(1.5, 0.2, -0.4);
  BodyState st(m, R, Vec3(1, 2, -20), vO, w);
  towsim::body_inertia(m.fluid, m.bodies[0], st.ws.body[0]);
  const Mat3 Iw = R * b.inertia_cg * R.transpose();
  Mat6 Mw = Mat6::Zero();
  Mw.topLeftCorner<3, 3>() = 12 * Mat3::Identity();
  Mw.bottomRightCorner<3, 3>() = Iw;
  Vec6 hw;
  hw << Vec3::Zero(), w.cross(Iw * w);
  const double err = std::max((st.ws.body[0].Mw - Mw).norm(), (st.ws.body[0].hw - hw).norm());
  report("Inertia, no added mass, CG at O_t", err, 1e-13);
  EXPECT_LE(err, 1e-13);
}

// Added mass, no rotation (w = 0), uniform current U: nu_r = (R^T v_r, 0),
// v_r = v_O - U. Rigid part: p = m v, hw_rigid = [w x p; w x l + v x p] = 0.
// Fluid part: p_A = A11 v_r (body axes), hw_fluid = [0; v_r x p_A] -- the Munk
// moment, zero only when v_r is along an eigenvector of A11 (e.g. A11 = a I).
// So hw = [0; R (v_rb x A11 v_rb)], and Mw = B (M_RB + M_A) B^T.
TEST(BodyModel, InertiaAddedMassNoRotationUniformCurrent) {
  Model m = body_model(1025);
  Body& b = m.bodies[0];
  b.mass = 12;
  b.inertia_cg = Vec3(1, 2, 3).asDiagonal();
  b.cg = Vec3(0.1, 0.05, -0.1);  // irrelevant at w = 0 (checked)
  b.added_mass.diagonal() << 3, 20, 22, 0.5, 2, 2.1;
  b.added_mass(1, 5) = b.added_mass(5, 1) = 0.7;
  b.added_mass(0, 2) = b.added_mass(2, 0) = 1.1;
  towsim::finalize_body(b, m.fluid);
  m.fluid.current_depth = {0};
  m.fluid.current_velocity = {Vec3(0.4, -0.6, 0)};
  const Mat3 R = rotation(0.4, -0.3, 1.2);
  const Vec3 vO(1.5, 0.2, -0.4), vrb = R.transpose() * (vO - Vec3(0.4, -0.6, 0));
  BodyState st(m, R, Vec3(1, 2, -20), vO, Vec3::Zero());
  towsim::body_inertia(m.fluid, m.bodies[0], st.ws.body[0]);
  const Mat3 A11 = b.added_mass.topLeftCorner<3, 3>();
  Vec6 hw;
  hw << Vec3::Zero(), R * vrb.cross(A11 * vrb);
  Mat6 Bm = Mat6::Zero();
  Bm.topLeftCorner<3, 3>() = R;
  Bm.bottomRightCorner<3, 3>() = R;
  const double err = std::max((st.ws.body[0].hw - hw).norm(),
                              (st.ws.body[0].Mw - Bm * (b.rigid_mass + b.fluid_mass) * Bm.transpose()).norm());
  report("Inertia, added mass, w = 0, uniform current", err, 1e-12);
  EXPECT_LE(err, 1e-12);
  EXPECT_GT(hw.norm(), 1.0);  // the Munk moment is really there
  // Isotropic A11: no Munk moment, hw = 0.
  Model iso = m;
  iso.bodies[0].added_mass = Mat6::Zero();
  iso.bodies[0].added_mass.diagonal() << 7, 7, 7, 1, 1, 1;
  towsim::finalize_body(iso.bodies[0], iso.fluid);
  BodyState si(iso, R, Vec3(1, 2, -20), vO, Vec3::Zero());
  towsim::body_inertia(iso.fluid, iso.bodies[0], si.ws.body[0]);
  EXPECT_LE(si.ws.body[0].hw.norm(), 1e-12);
}

namespace {
/// A smooth body motion: R = Rz(psi) Ry(theta) Rx(phi) with analytic angles,
/// O_t(t) analytic; w and alpha derived analytically.
struct BodyTrajectory {
  static double psi(double t) { return 0.4 + 0.3 * t + 0.1 * std::sin(2 * t); }
  static double dpsi(double t) { return 0.3 + 0.2 * std::cos(2 * t); }
  static double ddpsi(double t) { return -0.4 * std::sin(2 * t); }
  static double th(double t) { return 0.2 * std::sin(0.9 * t); }
  static double dth(double t) { return 0.18 * std::cos(0.9 * t); }
  static double ddth(double t) { return -0.162 * std::sin(0.9 * t); }
  static double ph(double t) { return -0.3 + 0.5 * std::cos(1.3 * t); }
  static double dph(double t) { return -0.65 * std::sin(1.3 * t); }
  static double ddph(double t) { return -0.845 * std::cos(1.3 * t); }
  static Mat3 Rz(double t) { return Eigen::AngleAxisd(psi(t), Vec3::UnitZ()).toRotationMatrix(); }
  static Mat3 Ry(double t) { return Eigen::AngleAxisd(th(t), Vec3::UnitY()).toRotationMatrix(); }
  static Mat3 Rx(double t) { return Eigen::AngleAxisd(ph(t), Vec3::UnitX()).toRotationMatrix(); }
  static Mat3 R(double t) { return Rz(t) * Ry(t) * Rx(t); }
  // w = psi' z + theta' Rz y + phi' Rz Ry x.
  static Vec3 w(double t) {
    return dpsi(t) * Vec3::UnitZ() + dth(t) * Rz(t) * Vec3::UnitY() + dph(t) * Rz(t) * Ry(t) * Vec3::UnitX();
  }
  // d/dt (Rz y) = psi' z x Rz y; d/dt (Rz Ry x) = (psi' z + theta' Rz y) x Rz Ry x.
  static Vec3 alpha(double t) {
    const Vec3 y1 = Rz(t) * Vec3::UnitY(), x2 = Rz(t) * Ry(t) * Vec3::UnitX();
    const Vec3 w1 = dpsi(t) * Vec3::UnitZ(), w2 = w1 + dth(t) * y1;
    return ddpsi(t) * Vec3::UnitZ() + ddth(t) * y1 + dth(t) * w1.cross(y1) + ddph(t) * x2 + dph(t) * w2.cross(x2);
  }
  static Vec3 O(double t) {
    return Vec3(1.5 * t + 0.3 * std::sin(1.1 * t), 0.5 * std::cos(0.7 * t), -30 + 2 * std::sin(0.4 * t));
  }
  static Vec3 v(double t) {
    return Vec3(1.5 + 0.33 * std::cos(1.1 * t), -0.35 * std::sin(0.7 * t), 0.8 * std::cos(0.4 * t));
  }
  static Vec3 a(double t) {
    return Vec3(-0.363 * std::sin(1.1 * t), -0.245 * std::cos(0.7 * t), -0.32 * std::sin(0.4 * t));
  }
};

/// A body with a CG offset, a full inertia tensor and a full symmetric 6x6
/// added mass (positive definite).
Model kirchhoff_body() {
  Model m = body_model(1025);
  Body& b = m.bodies[0];
  b.mass = 40;
  b.inertia_cg << 2.0, 0.1, -0.05, 0.1, 5.0, 0.2, -0.05, 0.2, 5.5;
  b.cg = Vec3(-0.1, 0.02, -0.05);
  Eigen::Matrix<double, 6, 6> S;
  S << 1.0, 0.2, -0.1, 0.3, 0.0, 0.1,  //
      0.0, 3.0, 0.4, -0.2, 0.5, 0.7,   //
      0.1, -0.3, 3.2, 0.1, -0.6, 0.2,  //
      0.2, 0.0, 0.1, 0.6, 0.1, -0.1,   //
      -0.1, 0.4, 0.3, 0.0, 1.2, 0.2,   //
      0.3, 0.1, -0.2, 0.1, 0.0, 1.1;
  b.added_mass = S * S.transpose();
  towsim::finalize_body(b, m.fluid);
  return m;
}
}  // namespace

// Kirchhoff's equations in R_g, by finite differences along a prescribed smooth
// motion. With nu = (R^T v_O, R^T w), nu_r = (R^T (v_O - U(z_O)), R^T w),
// (p, l) = R (M_RB nu), (p_A, l_A) = R (M_A nu_r) (world frame):
//   d/dt (p + p_A)                               = rows 1-3 of Mw [a_O; alpha] + hw
//   d/dt (l + l_A) + v_O x p + (v_O - U) x p_A   = rows 4-6
// (moment about the moving point O_t: dL_O/dt + v_O x P; the fluid impulse sees
// O_t moving at v_O - U through the water). Still water, a uniform current,
// and a sheared current (U(z_O) through the table, as theory 4 defines nu_r).
TEST(BodyModel, KirchhoffMatchesFiniteDifferences) {
  using T = BodyTrajectory;
  const double h = 1e-4;
  // The trajectory's own w, alpha, v, a against FD of R, w, O, v first.
  double err_traj = 0;
  for (double t : {-1.0, 0.3, 2.2}) {
    const Mat3 W = (T::R(t + h) - T::R(t - h)) / (2 * h) * T::R(t).transpose();
    err_traj = std::max(err_traj, (Vec3(W(2, 1), W(0, 2), W(1, 0)) - T::w(t)).norm());
    err_traj = std::max(err_traj, ((T::w(t + h) - T::w(t - h)) / (2 * h) - T::alpha(t)).norm());
    err_traj = std::max(err_traj, ((T::O(t + h) - T::O(t - h)) / (2 * h) - T::v(t)).norm());
    err_traj = std::max(err_traj, ((T::v(t + h) - T::v(t - h)) / (2 * h) - T::a(t)).norm());
  }
  report("Kirchhoff: trajectory's own w, alpha, v, a vs FD", err_traj, 1e-7);
  ASSERT_LE(err_traj, 1e-7);  // h^2/6 |f'''| ~ 2e-9 |f'''|, |f'''| < 10 here

  for (int current = 0; current < 3; ++current) {
    Model m = kirchhoff_body();
    if (current == 1) {
      m.fluid.current_depth = {0};
      m.fluid.current_velocity = {Vec3(0.6, -0.3, 0.05)};
    } else if (current == 2) {  // O_t stays at depths 28..32 m, inside [20, 40]
      m.fluid.current_depth = {20, 40};
      m.fluid.current_velocity = {Vec3(0.8, 0.1, 0), Vec3(0.1, -0.4, 0.02)};
    }
    const Body& b = m.bodies[0];
    auto momenta = [&](double t) {
      const Mat3 R = T::R(t);
      const Vec3 U = m.fluid.current(T::O(t).z());
      Vec6 nu, nur;
      nu << R.transpose() * T::v(t), R.transpose() * T::w(t);
      nur << R.transpose() * (T::v(t) - U), R.transpose() * T::w(t);
      const Vec6 pr = b.rigid_mass * nu, pa = b.fluid_mass * nur;
      Eigen::VectorXd out(12);  // p, l, p_A, l_A in R_g
      out << R * pr.head<3>(), R * pr.tail<3>(), R * pa.head<3>(), R * pa.tail<3>();
      return out;
    };
    double err = 0, worst_tol = 0, err_r = 0, worst_tol_r = 0, ratio = 0, ratio_r = 0;
    for (int i = 0; i <= 30; ++i) {
      const double t = -2 + 0.21 * i;
      const Eigen::VectorXd now = momenta(t);
      const Vec3 vO = T::v(t), vr = vO - m.fluid.current(T::O(t).z());
      auto lhs_of = [&](const Eigen::VectorXd& d) {
        Vec6 lhs;
        lhs << d.segment<3>(0) + d.segment<3>(6),
            d.segment<3>(3) + d.segment<3>(9) + vO.cross(Vec3(now.segment<3>(0))) + vr.cross(Vec3(now.segment<3>(6)));
        return lhs;
      };
      BodyState st(m, T::R(t), T::O(t), vO, T::w(t));
      towsim::body_inertia(m.fluid, m.bodies[0], st.ws.body[0]);
      Vec6 acc;
      acc << T::a(t), T::alpha(t);
      const Vec6 rhs = st.ws.body[0].Mw * acc + st.ws.body[0].hw;
      // The FD bounds are on the 12-vector of momenta; each row of lhs adds two
      // of its 3-blocks (factor 2); the cross products are exact values.
      auto [d, tol] = fd_with_bound(momenta, t, h);
      const double e = (lhs_of(d) - rhs).norm();
      EXPECT_LE(e, 2 * tol) << "t = " << t << ", current case " << current << "\nlhs " << lhs_of(d).transpose()
                            << "\nrhs " << rhs.transpose();
      err = std::max(err, e);
      worst_tol = std::max(worst_tol, 2 * tol);
      auto [dr, tol_r] = fd_richardson(momenta, t, 1e-3);
      const double er = (lhs_of(dr) - rhs).norm();
      EXPECT_LE(er, 2 * tol_r) << "Richardson, t = " << t << ", current case " << current;
      err_r = std::max(err_r, er);
      ratio = std::max(ratio, e / (2 * tol));
      ratio_r = std::max(ratio_r, er / (2 * tol_r));
      worst_tol_r = std::max(worst_tol_r, 2 * tol_r);
    }
    const char* names[] = {"Kirchhoff FD, still water", "Kirchhoff FD, uniform current",
                           "Kirchhoff FD, sheared current"};
    report(names[current], err, worst_tol);
    report("  same, Richardson-extrapolated FD", err_r, worst_tol_r);
    std::printf("[measured]   worst err/tol: plain FD %.2f, Richardson %.2f\n", ratio, ratio_r);
  }
}

// Roll and yaw are read in (-180, 180] degrees: an attitude on atan2's cut (a
// planar tow whose body pitched past -90 degrees: roll and yaw 180) reads the
// same whatever the sign of the round-off zero in R, so both formulations
// print the same angles. Exact: the cut's +pi is atan2's own value.
TEST(BodyModel, RollAndYawOnTheCutReadPlusPi) {
  const double s = std::sin(-50.0 * std::numbers::pi / 180), c = std::cos(-50.0 * std::numbers::pi / 180);
  for (const double zero : {0.0, -0.0}) {
    // A rotation of -100 degrees about y_g, with a signed zero in x.
    const towsim::Quat q(c, zero, s, 0.0);
    const towsim::Vec3 rpy = towsim::roll_pitch_yaw(q);
    EXPECT_EQ(rpy.x(), std::numbers::pi) << zero;
    EXPECT_EQ(rpy.z(), std::numbers::pi) << zero;
    EXPECT_NEAR(rpy.y(), -80.0 * std::numbers::pi / 180, 1e-14);  // pitch: |R(2,0)| = sin 80, round-off
  }
  // Off the cut the angles are atan2's (-179 degrees stays -179).
  const towsim::Vec3 rpy = towsim::roll_pitch_yaw(towsim::quat_from_rpy(-179.0 * std::numbers::pi / 180, 0.1, 0.2));
  EXPECT_NEAR(rpy.x(), -179.0 * std::numbers::pi / 180, 1e-14);
}
