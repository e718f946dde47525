// Cable element loads (element_loads, element_mass, make_element) and the
// current profile (Fluid::current, current_gradient) against hand
// calculations, symmetry checks and finite differences (docs/theory.md §3,
// theory.md 3).
//
// Tolerances: hand-calculated values are compared to 1e-12 relative (a few
// operations in double precision, values of order 1-100). Finite differences
// use the central-difference bound h^2/6 |f'''| (truncation) with |f'''|
// estimated by a wider stencil, times 2, plus 8 eps |f| / h (round-off);
// see fd_with_bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "../support/fd.hpp"
#include "towsim/hydro/loads.hpp"

namespace {

using towsim::AddedMassModel;
using towsim::Element;
using towsim::Fluid;
using towsim::Mat3;
using towsim::Model;
using towsim::TangentialLaw;
using towsim::Vec3;
using towsim::testing::fd_richardson;
using towsim::testing::fd_with_bound;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kRel = 1e-12;  // hand calculations: a few roundings of O(1-100) values
constexpr double pi = std::numbers::pi;

void report(const char* what, double err, double tol) {
  std::printf("[measured] %-58s max err %.3e  (tol %.3e)\n", what, err, tol);
}

/// An element with every coefficient zero: tests switch on one load at a time.
Element bare_element() {
  Element el{};
  el.length = 2;
  el.mass = 3;
  el.diameter = 0.02;
  return el;
}

Model fluid_model(double rho = 1025, double g = 9.81, TangentialLaw law = TangentialLaw::Pode,
                  AddedMassModel am = AddedMassModel::IdealFluid) {
  Model m;
  m.fluid.rho = rho;
  m.fluid.g = g;
  m.cable.tangential_law = law;
  m.cable.added_mass_model = am;
  return m;
}

struct Loads {
  Vec3 F, M;
};
Loads loads(const Model& m, const Element& el, const Vec3& e, const Vec3& edot, const Vec3& vG, double zG = -10) {
  Loads l;
  towsim::element_loads(m, el, e, edot, vG, Vec3(0, 0, zG), 0.0, l.F, l.M);
  return l;
}

}  // namespace

// ------------------------------------------------------------ derived data

// L = 2 m, 1.5 kg/m, D = 0.02 m, Cd = 1.8, f = 0.02, Ca = 1, rho = 1025, g = 9.81:
// A = pi 1e-4 m^2, m = 3 kg, rho A L = 0.205 pi kg, I = m L^2/12 = 1,
// 1/2 rho Cd D L = 36.9, Pode 1/2 rho Cd f D L = 0.738, Skin (Ct = 0.005)
// 1/2 rho pi D L Ct = 0.1025 pi.
TEST(Loads, MakeElementDerivedFields) {
  Fluid fl;
  fl.rho = 1025;
  fl.g = 9.81;
  const Element p = towsim::make_element(2, 1.5, 0.02, 1.8, 0.02, TangentialLaw::Pode, 1.0, fl);
  EXPECT_DOUBLE_EQ(p.length, 2);
  EXPECT_DOUBLE_EQ(p.mass, 3);
  EXPECT_DOUBLE_EQ(p.inertia, 1);
  EXPECT_NEAR(p.added_mass, 0.205 * pi, kRel);
  EXPECT_NEAR(p.added_inertia, 0.205 * pi / 3, kRel);
  EXPECT_NEAR(p.weight, (3 - 0.205 * pi) * 9.81, 1e-12 * 30);
  EXPECT_NEAR(p.drag_factor, 36.9, 1e-12 * 37);
  EXPECT_NEAR(p.friction_factor, 0.738, kRel);
  const Element s = towsim::make_element(2, 1.5, 0.02, 1.8, 0.005, TangentialLaw::Skin, 1.0, fl);
  EXPECT_NEAR(s.friction_factor, 0.1025 * pi, kRel);
  // Vacuum: no displaced weight, no fluid coefficients.
  fl.rho = 0;
  const Element v = towsim::make_element(2, 1.5, 0.02, 1.8, 0.02, TangentialLaw::Pode, 1.0, fl);
  EXPECT_DOUBLE_EQ(v.weight, 3 * 9.81);
  EXPECT_EQ(v.added_mass, 0.0);
  EXPECT_EQ(v.drag_factor, 0.0);
  EXPECT_EQ(v.friction_factor, 0.0);
}

// m I + ma (I - ee^T): m along e, m + ma across; rotational I + Ia.
TEST(Loads, ElementMass) {
  Element el = bare_element();
  el.added_mass = 0.7;
  el.inertia = 1.0;
  el.added_inertia = 0.25;
  const Vec3 e(0.6, 0, -0.8);
  const Mat3 Mt = towsim::element_mass(el, e);
  Mat3 expect;  // 3 I + 0.7 [[0.64, 0, 0.48], [0, 1, 0], [0.48, 0, 0.36]]
  expect << 3 + 0.7 * 0.64, 0, 0.7 * 0.48, 0, 3.7, 0, 0.7 * 0.48, 0, 3 + 0.7 * 0.36;
  EXPECT_LE((Mt - expect).norm(), kRel);
  EXPECT_LE((Mt * e - 3 * e).norm(), kRel);
  EXPECT_LE((Mt * Vec3(0.8, 0, 0.6) - 3.7 * Vec3(0.8, 0, 0.6)).norm(), kRel);
  EXPECT_DOUBLE_EQ(towsim::element_rot_inertia(el), 1.25);
}

// ------------------------------------------------------------ weight, drag, friction

// At rest in still water only the apparent weight (m - rho A L) g acts, along -z.
TEST(Loads, ApparentWeightAtRest) {
  const Model m = fluid_model();
  const Element el = towsim::make_element(2, 1.5, 0.02, 1.8, 0.02, TangentialLaw::Pode, 1.0, m.fluid);
  const Loads l = loads(m, el, Vec3(0.6, 0, -0.8), Vec3(0, 0.3, 0), Vec3::Zero());
  // edot != 0 but u = 0: the added-mass velocity terms vanish with u.
  EXPECT_LE((l.F - Vec3(0, 0, -(3 - 0.205 * pi) * 9.81)).norm(), 1e-12 * 30);
  EXPECT_EQ(l.M, Vec3::Zero());
}

// e = (0.6, 0, -0.8), u = (2, 0, 0): u.e = 1.2, u_n = (1.28, 0, 0.96), |u_n| = 1.6,
// F = -36.9 * 1.6 * u_n = (-75.5712, 0, -56.6784), normal to e.
TEST(Loads, NormalDragHandCalculation) {
  const Model m = fluid_model();
  const Vec3 e(0.6, 0, -0.8);
  // Isolated: only the drag factor set.
  Element el = bare_element();
  el.drag_factor = 36.9;
  Loads l = loads(m, el, e, Vec3::Zero(), Vec3(2, 0, 0));
  EXPECT_LE((l.F - Vec3(-75.5712, 0, -56.6784)).norm(), 1e-12 * 100);
  EXPECT_NEAR(l.F.dot(e), 0.0, 1e-12 * 100);
  EXPECT_EQ(l.M, Vec3::Zero());
  // The same through make_element (f = 0, Ca = 0), weight removed.
  const Element mk = towsim::make_element(2, 1.5, 0.02, 1.8, 0.0, TangentialLaw::Pode, 0.0, m.fluid);
  l = loads(m, mk, e, Vec3::Zero(), Vec3(2, 0, 0));
  const double err = (l.F - Vec3(-75.5712, 0, -56.6784 - mk.weight)).norm();
  report("NormalDragHandCalculation (make_element)", err, 1e-12 * 100);
  EXPECT_LE(err, 1e-12 * 100);
  // Quadratic and odd in u.
  const Loads l2 = loads(m, el, e, Vec3::Zero(), Vec3(-4, 0, 0));
  EXPECT_LE((l2.F - Vec3(4 * 75.5712, 0, 4 * 56.6784)).norm(), 1e-12 * 400);
}

// Pode: F = -c |u|^2 sgn_s(u.e) e, sgn_s(x) = x / sqrt(x^2 + v_s^2).
// e = (0.6, 0, -0.8), u = (2, 0, 0): |u|^2 = 4 (the whole speed, not u.e),
// u.e = 1.2, sgn_s = 1.2 / sqrt(1.44 + 1e-6).
TEST(Loads, PodeFrictionSmoothedSign) {
  Model m = fluid_model();
  const Vec3 e(0.6, 0, -0.8);
  Element el = bare_element();
  el.friction_factor = 0.738;
  const double vs = m.cable.sign_smoothing_speed;
  ASSERT_EQ(vs, 1e-3);
  const Loads l = loads(m, el, e, Vec3::Zero(), Vec3(2, 0, 0));
  const Vec3 expect = -0.738 * 4 * (1.2 / std::sqrt(1.44 + 1e-6)) * e;
  EXPECT_LE((l.F - expect).norm(), kRel * 3);
  EXPECT_EQ(l.M, Vec3::Zero());
  // Odd: u -> -u reverses it.
  EXPECT_LE((loads(m, el, e, Vec3::Zero(), Vec3(-2, 0, 0)).F + l.F).norm(), 1e-15);
  // |u.e| >> v_s: |sgn_s - 1| = 1 - 1/sqrt(1 + r^2) <= r^2 / 2, r = v_s / |u.e|.
  const double r = vs / 1.2;
  EXPECT_LE(std::abs(l.F.norm() / (0.738 * 4) - 1), r * r / 2 * (1 + 1e-6));
  EXPECT_GT(std::abs(l.F.norm() / (0.738 * 4) - 1), 0.0);  // smoothed, not the hard sign
  // Flow normal to the element: no friction (the smoothing makes it continuous).
  EXPECT_EQ(loads(m, el, e, Vec3::Zero(), Vec3(0, 3, 0)).F.norm(), 0.0);
  // At u.e = v_s the smoothed sign is 1/sqrt(2).
  const Vec3 u_vs = Vec3(0, 3, 0) + vs * e;
  EXPECT_LE((loads(m, el, e, Vec3::Zero(), u_vs).F + 0.738 * u_vs.squaredNorm() / std::sqrt(2.0) * e).norm(), 1e-12);
  // smooth_sign itself.
  EXPECT_EQ(towsim::smooth_sign(0, vs), 0.0);
  EXPECT_NEAR(towsim::smooth_sign(vs, vs), 1 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(towsim::smooth_sign(-3, vs), -1 / std::sqrt(1 + vs * vs / 9), 1e-15);
  for (double x : {1e-7, 1e-4, 1e-3, 0.5, 7.0}) EXPECT_EQ(towsim::smooth_sign(-x, vs), -towsim::smooth_sign(x, vs));
  // Continuity through zero: a change of u.e by dx changes sgn_s by <= dx / v_s.
  EXPECT_LE(std::abs(towsim::smooth_sign(1e-9, vs) - towsim::smooth_sign(-1e-9, vs)), 2e-9 / vs * (1 + 1e-12));
}

// Skin: F = -c |u.e| (u.e) e; with u.e = 1.2: -1.44 c e, odd in u.
TEST(Loads, SkinFrictionHandCalculation) {
  const Model m = fluid_model(1025, 9.81, TangentialLaw::Skin);
  const Vec3 e(0.6, 0, -0.8);
  Element el = bare_element();
  el.friction_factor = 0.1025 * pi;
  const Loads l = loads(m, el, e, Vec3::Zero(), Vec3(2, 0, 0));
  EXPECT_LE((l.F - (-0.1025 * pi * 1.44) * e).norm(), kRel);
  EXPECT_LE((loads(m, el, e, Vec3::Zero(), Vec3(-2, 0, 0)).F + l.F).norm(), 1e-15);
  // Depends on u.e only: adding a normal velocity changes nothing.
  EXPECT_LE((loads(m, el, e, Vec3::Zero(), Vec3(2, 5, 0)).F - l.F).norm(), 1e-15);
}

// ------------------------------------------------------------ added mass

// F = ma [edot (e.u) + e (edot.u)], M = ma (e.u) (u x e).
// (1) e = (1,0,0), edot = (0,2,0), u = (3,4,5), ma = 0.5: e.u = 3, edot.u = 8,
//     F = 0.5 (8, 6, 0) = (4, 3, 0); u x e = (0, 5, -4), M = 0.5*3*(0,5,-4) = (0, 7.5, -6).
// (2) e = (0,0,-1), edot = (0.3,0,0), u = (1,-2,0.5), ma = 2: e.u = -0.5,
//     edot.u = 0.3, F = 2 [(-0.15, 0, 0) + (0, 0, -0.3)] = (-0.3, 0, -0.6);
//     u x e = (2, 1, 0), M = 2 (-0.5) (2, 1, 0) = (-2, -1, 0).
TEST(Loads, IdealFluidVelocityTermsAndMunkMoment) {
  const Model ideal = fluid_model();
  const Model morison = fluid_model(1025, 9.81, TangentialLaw::Pode, AddedMassModel::Morison);
  Element el = bare_element();
  el.added_mass = 0.5;
  Loads l = loads(ideal, el, Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(3, 4, 5));
  EXPECT_LE((l.F - Vec3(4, 3, 0)).norm(), kRel * 10);
  EXPECT_LE((l.M - Vec3(0, 7.5, -6)).norm(), kRel * 10);
  el.added_mass = 2;
  l = loads(ideal, el, Vec3(0, 0, -1), Vec3(0.3, 0, 0), Vec3(1, -2, 0.5));
  EXPECT_LE((l.F - Vec3(-0.3, 0, -0.6)).norm(), kRel);
  EXPECT_LE((l.M - Vec3(-2, -1, 0)).norm(), kRel);
  // The Munk moment turns the element broadside to the flow: e = x, u in the
  // first quadrant of (x, y): the moment is about -z (rotating e away from u).
  EXPECT_LT(loads(ideal, el, Vec3(1, 0, 0), Vec3::Zero(), Vec3(1, 0.5, 0)).M.z(), 0.0);
  // Morison: none of these terms.
  l = loads(morison, el, Vec3(0, 0, -1), Vec3(0.3, 0, 0), Vec3(1, -2, 0.5));
  EXPECT_EQ(l.F, Vec3::Zero());
  EXPECT_EQ(l.M, Vec3::Zero());
}

// rho = 0 (vacuum): only the weight, whatever the coefficients and velocities.
TEST(Loads, VacuumGivesOnlyWeight) {
  Model m = fluid_model(0.0, 9.81);
  m.fluid.current_depth = {0, 100};
  m.fluid.current_velocity = {Vec3(1, 0, 0), Vec3(0, 1, 0)};
  Element el = bare_element();
  el.weight = 29.43;
  el.drag_factor = 10;
  el.friction_factor = 1;
  el.added_mass = 2;
  for (TangentialLaw law : {TangentialLaw::Pode, TangentialLaw::Skin}) {
    m.cable.tangential_law = law;
    const Loads l = loads(m, el, Vec3(0.6, 0, -0.8), Vec3(0.8, 0, 0.6), Vec3(3, -1, 2), -20);
    EXPECT_EQ(l.F, Vec3(0, 0, -29.43));
    EXPECT_EQ(l.M, Vec3::Zero());
  }
}

// Uniform current U: the loads depend on v - U only (Galilean invariance).
TEST(Loads, UniformCurrentGalilean) {
  std::mt19937 rng(7);
  std::normal_distribution<double> N(0, 1);
  auto rnd = [&] { return Vec3(N(rng), N(rng), N(rng)); };
  double err = 0;
  for (TangentialLaw law : {TangentialLaw::Pode, TangentialLaw::Skin}) {
    for (AddedMassModel am : {AddedMassModel::IdealFluid, AddedMassModel::Morison}) {
      Model still = fluid_model(1025, 9.81, law, am);
      Model moving = still;
      const Vec3 U(1.2, -0.4, 0.1);
      moving.fluid.current_depth = {30};
      moving.fluid.current_velocity = {U};
      const Element el = towsim::make_element(4, 1.5, 0.02, 1.8, law == TangentialLaw::Pode ? 0.02 : 0.005, law, 1.0,
                                              still.fluid);
      for (int i = 0; i < 20; ++i) {
        const Vec3 e = rnd().normalized();
        Vec3 w = rnd();
        const Vec3 edot = w.cross(e);
        const Vec3 v = 2 * rnd();
        const double z = -50 * std::abs(N(rng));
        const Loads a = loads(moving, el, e, edot, v, z), b = loads(still, el, e, edot, v - U, z);
        const double scale = 1 + a.F.norm() + a.M.norm();
        err = std::max({err, (a.F - b.F).norm() / scale, (a.M - b.M).norm() / scale});
      }
    }
  }
  report("UniformCurrentGalilean (relative)", err, 1e-14);
  EXPECT_LE(err, 1e-14);  // u = v - U computed the same way: identical up to one rounding
}

// ------------------------------------------------------------ current profile

// Table: depth 0 -> (1, 0, 0), 10 -> (0.5, 0.2, 0), 50 -> (0, 0, 0).
// z = -5 (depth 5): (0.75, 0.1, 0); z = -30 (s = 1/2): (0.25, 0.1, 0);
// above the first row and below the last: held. dU/dz = -dU/d(depth):
// (0.05, -0.02, 0) on [0, 10], (0.0125, 0.005, 0) on [10, 50], zero outside.
TEST(Loads, CurrentTableInterpolationAndGradient) {
  Fluid f;
  f.current_depth = {0, 10, 50};
  f.current_velocity = {Vec3(1, 0, 0), Vec3(0.5, 0.2, 0), Vec3(0, 0, 0)};
  EXPECT_LE((f.current(-5) - Vec3(0.75, 0.1, 0)).norm(), 1e-15);
  EXPECT_LE((f.current(-30) - Vec3(0.25, 0.1, 0)).norm(), 1e-15);
  EXPECT_EQ(f.current(2), Vec3(1, 0, 0));
  EXPECT_EQ(f.current(-80), Vec3(0, 0, 0));
  EXPECT_LE((f.current(-10) - Vec3(0.5, 0.2, 0)).norm(), 1e-15);
  EXPECT_LE((f.current_gradient(-5) - Vec3(0.05, -0.02, 0)).norm(), 1e-15);
  EXPECT_LE((f.current_gradient(-30) - Vec3(0.0125, 0.005, 0)).norm(), 1e-15);
  EXPECT_EQ(f.current_gradient(1), Vec3::Zero());
  EXPECT_EQ(f.current_gradient(-60), Vec3::Zero());
  // Against central differences: U is linear on each interval, so the FD is
  // exact up to round-off 8 eps |U| / h, h = 1e-4 m; away from the rows by 2h.
  const double h = 1e-4, tol = 8 * kEps * 2 / h;
  double err = 0;
  for (int i = 0; i <= 700; ++i) {
    const double z = 5 - 0.1 * i;
    if (std::abs(z) < 2 * h || std::abs(z + 10) < 2 * h || std::abs(z + 50) < 2 * h) continue;
    const Vec3 fd = (f.current(z + h) - f.current(z - h)) / (2 * h);
    err = std::max(err, (fd - f.current_gradient(z)).norm());
  }
  report("CurrentGradient vs FD", err, tol);
  EXPECT_LE(err, tol);
  // One row: uniform; none: still water.
  Fluid one;
  one.current_depth = {20};
  one.current_velocity = {Vec3(0.3, 0.4, 0)};
  EXPECT_EQ(one.current(-100), Vec3(0.3, 0.4, 0));
  EXPECT_EQ(one.current(0), Vec3(0.3, 0.4, 0));
  EXPECT_EQ(one.current_gradient(-20), Vec3::Zero());
  EXPECT_EQ(Fluid{}.current(-5), Vec3::Zero());
}

// In a sheared current du/dt = a_G - U'(z) zdot (theory 3): the U' part of
// -ma (I - ee^T) du/dt is a known load, ma (I - ee^T) U' zdot, in both
// added-mass forms. e = (0,0,-1) keeps x, y: U' = (0.05, -0.02, 0) at z = -5,
// zdot = -2: F = ma (-0.1, 0.04, 0). Drag and friction use U at z_G.
TEST(Loads, ShearedCurrentTerms) {
  for (AddedMassModel am : {AddedMassModel::IdealFluid, AddedMassModel::Morison}) {
    Model m = fluid_model(1025, 9.81, TangentialLaw::Pode, am);
    m.fluid.current_depth = {0, 10, 50};
    m.fluid.current_velocity = {Vec3(1, 0, 0), Vec3(0.5, 0.2, 0), Vec3(0, 0, 0)};
    Element el = bare_element();
    el.added_mass = 2;
    // v = U(z) + (0, 0, -2): u = (0,0,-2) along e; edot = 0: no ideal-fluid term.
    const Vec3 v = Vec3(0.75, 0.1, -2);
    Loads l = loads(m, el, Vec3(0, 0, -1), Vec3::Zero(), v, -5);
    EXPECT_LE((l.F - 2 * Vec3(-0.1, 0.04, 0)).norm(), 1e-14);
    // Drag uses the current at z_G: here u_n = 0, no drag.
    el.added_mass = 0;
    el.drag_factor = 3;
    l = loads(m, el, Vec3(0, 0, -1), Vec3::Zero(), v, -5);
    EXPECT_LE(l.F.norm(), 1e-14);
    l = loads(m, el, Vec3(0, 0, -1), Vec3::Zero(), Vec3(0.25, 0.1, 0), -30);
    EXPECT_LE(l.F.norm(), 1e-14);
  }
}

// ------------------------------------------------------------ F_A = -dP/dt

namespace {
/// A smooth trajectory of an element: axis e(t) from two angles, centre G(t).
struct Trajectory {
  static double a(double t) { return 0.3 + 0.7 * t + 0.2 * t * t; }
  static double da(double t) { return 0.7 + 0.4 * t; }
  static double b(double t) { return 0.2 * std::sin(1.3 * t); }
  static double db(double t) { return 0.26 * std::cos(1.3 * t); }
  static Vec3 e(double t) {
    return Vec3(std::cos(a(t)) * std::cos(b(t)), std::sin(a(t)) * std::cos(b(t)), std::sin(b(t)));
  }
  static Vec3 edot(double t) {
    const double A = a(t), B = b(t);
    return da(t) * Vec3(-std::sin(A) * std::cos(B), std::cos(A) * std::cos(B), 0) +
           db(t) * Vec3(-std::cos(A) * std::sin(B), -std::sin(A) * std::sin(B), std::cos(B));
  }
  static Vec3 G(double t) {
    return Vec3(2 * t + 0.5 * std::sin(t), 1 - std::cos(0.8 * t), -20 - 3 * std::sin(0.5 * t));
  }
  static Vec3 v(double t) { return Vec3(2 + 0.5 * std::cos(t), 0.8 * std::sin(0.8 * t), -1.5 * std::cos(0.5 * t)); }
  static Vec3 acc(double t) { return Vec3(-0.5 * std::sin(t), 0.64 * std::cos(0.8 * t), 0.75 * std::sin(0.5 * t)); }
};
}  // namespace

// The ideal-fluid force is F_A = -dP/dt with P = ma (I - ee^T) u, u = v - U(z).
// element_loads gives the velocity terms (and, in a sheared current, the U'
// term); adding the acceleration term -ma (I - ee^T) a_G must give -dP/dt,
// here from central differences of P(t) along an analytic trajectory
// (checked first: edot, v, a_G against FD of e, G, v).
TEST(Loads, IdealFluidForceIsMinusRateOfImpulse) {
  const double h = 1e-4;
  for (bool sheared : {false, true}) {
    Model m = fluid_model();
    if (sheared) {  // the trajectory stays at depths 17..23 m, inside one interval
      m.fluid.current_depth = {10, 30};
      m.fluid.current_velocity = {Vec3(1.0, 0.3, 0), Vec3(0.2, -0.4, 0.05)};
    }
    Element el = bare_element();
    el.added_mass = 0.644;  // the make_element value for D = 0.02, L = 2, rho = 1025
    double err = 0, worst_tol = 0, err_kin = 0, tol_kin = 0, err_r = 0, worst_tol_r = 0, ratio = 0, ratio_r = 0;
    for (int i = 0; i <= 40; ++i) {
      const double t = -3 + 0.17 * i;
      // The trajectory's own derivatives first.
      auto [de, tol_e] = fd_with_bound([](double s) -> Eigen::VectorXd { return Trajectory::e(s); }, t, h);
      auto [dG, tol_G] = fd_with_bound([](double s) -> Eigen::VectorXd { return Trajectory::G(s); }, t, h);
      auto [dv, tol_v] = fd_with_bound([](double s) -> Eigen::VectorXd { return Trajectory::v(s); }, t, h);
      EXPECT_LE((de - Trajectory::edot(t)).norm(), tol_e);
      EXPECT_LE((dG - Trajectory::v(t)).norm(), tol_G);
      EXPECT_LE((dv - Trajectory::acc(t)).norm(), tol_v);
      err_kin = std::max({err_kin, (de - Trajectory::edot(t)).norm(), (dG - Trajectory::v(t)).norm(),
                          (dv - Trajectory::acc(t)).norm()});
      tol_kin = std::max({tol_kin, tol_e, tol_G, tol_v});
      // Impulse and its rate.
      auto P = [&](double s) -> Eigen::VectorXd {
        const Vec3 e = Trajectory::e(s);
        const Vec3 u = Trajectory::v(s) - m.fluid.current(Trajectory::G(s).z());
        return Vec3(el.added_mass * (u - e.dot(u) * e));
      };
      auto [dP, tol] = fd_with_bound(P, t, h);
      const Vec3 e = Trajectory::e(t);
      const Loads l = loads(m, el, e, Trajectory::edot(t), Trajectory::v(t), Trajectory::G(t).z());
      const Vec3 a = Trajectory::acc(t);
      const Vec3 FA = -el.added_mass * (a - e.dot(a) * e) + l.F;
      err = std::max(err, (FA + Vec3(dP)).norm());
      worst_tol = std::max(worst_tol, tol);
      EXPECT_LE((FA + Vec3(dP)).norm(), tol) << "t = " << t << (sheared ? " (sheared current)" : "");
      // Sharper: Richardson-extrapolated rate (truncation O(h^4)).
      const double scale = el.added_mass * (Trajectory::v(t) - m.fluid.current(Trajectory::G(t).z())).norm();
      auto [dPr, tol_r] = fd_richardson(P, t, 1e-3, scale);
      err_r = std::max(err_r, (FA + Vec3(dPr)).norm());
      ratio_r = std::max(ratio_r, (FA + Vec3(dPr)).norm() / tol_r);
      ratio = std::max(ratio, (FA + Vec3(dP)).norm() / tol);
      worst_tol_r = std::max(worst_tol_r, tol_r);
      EXPECT_LE((FA + Vec3(dPr)).norm(), tol_r) << "t = " << t << (sheared ? " (sheared current)" : "");
    }
    report(sheared ? "F_A = -dP/dt, sheared current" : "F_A = -dP/dt, still water", err, worst_tol);
    report("  same, Richardson-extrapolated FD", err_r, worst_tol_r);
    std::printf("[measured]   worst err/tol: plain FD %.2f, Richardson %.2f\n", ratio, ratio_r);
    report("  (trajectory's own edot, v, a vs FD; each within its bound)", err_kin, tol_kin);
  }
}
