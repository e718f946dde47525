// The seabed (MODEL.md 9 "Seabed", docs/theory.md §3.2, docs/validation.md):
// the contact law against its closed forms, a cable lying on the bottom from
// a stationary tow point (top tension = apparent weight per metre x depth),
// a sled dragged along the bottom (towing force = mu x normal load + drag),
// with the joint law (contact: joints).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "../../src/sim/statics_internal.hpp"
#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

constexpr double kRho = 1025, kG = 9.81;  // the test models' water [kg/m^3] and gravity [m/s^2]

/// Apparent weight per metre of a test cable, from its own data [N/m].
double apparent_weight(const testing::CableSpec& c) {
  return (c.mass_per_length - kRho * std::numbers::pi / 4 * c.diameter * c.diameter) * kG;
}

/// The bottom with the joint law (contact: joints), which these tests check:
/// the law along elements has its own, tests/validation/test_seabed_along.cpp.
Seabed joint_law(Seabed sb) {
  sb.along_elements = false;
  return sb;
}

/// How far 10 s of the dynamics (rosenbrock, tolerance 1e-8) started from
/// the steady configuration `r` (tow velocity U) move from it: joints and
/// bodies relative to the tow point [m], joint speeds against U [m/s], tow
/// force change relative to its size [-].
struct Drift {
  double x = 0, v = 0, force = 0;
};
Drift drift_from_steady(Model m, const StaticsResult& r, const Vec3& U) {
  m.initial.kind = Initial::Kind::Steady;
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-8;
  m.sim.duration = 10;
  m.sim.time_step = 0.01;
  m.sim.output_interval = 1;
  const auto samples = testing::run(m);
  EXPECT_FALSE(samples.empty());
  Drift d;
  auto moved = [&](const Vec3& p, const Vec3& tow, const Vec3& p0) {
    d.x = std::max(d.x, ((p - tow) - (p0 - r.sample.tow_pos)).norm());
  };
  for (const Sample& smp : samples) {
    for (std::size_t j = 0; j < smp.node_pos.size(); ++j) {
      moved(smp.node_pos[j], smp.tow_pos, r.sample.node_pos[j]);
      d.v = std::max(d.v, (smp.node_vel[j] - U).norm());
    }
    for (std::size_t b = 0; b < smp.bodies.size(); ++b) moved(smp.bodies[b].pos, smp.tow_pos, r.sample.bodies[b].pos);
    d.force = std::max(d.force, (smp.tow_force - r.tow_force).norm() / r.tow_force.norm());
  }
  return d;
}

// ---------------------------------------------------------------------------
// The law at one point: geometry of a sloped table, and the friction's
// smoothing converging to Coulomb at second order in v_s.
// ---------------------------------------------------------------------------
TEST(SeabedLaw, SlopedTableGeometry) {
  Seabed sb;
  sb.x = {0, 100};
  sb.depth = {100, 50};                          // z_b = -100 + 0.5 x between the rows
  const Vec3 n = Vec3(-0.5, 0, 1).normalized();  // gradient of z - 0.5 x, normalised
  EXPECT_LT((sb.normal(40) - n).norm(), 1e-15);
  EXPECT_EQ(sb.normal(-10), Vec3::UnitZ());  // held flat beyond the table
  EXPECT_EQ(sb.normal(150), Vec3::UnitZ());
  // A NaN abscissa (a rejected trial state) reads inside the table (ASan
  // found a read past it): the first row, and a flat normal.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(sb.depth_at(nan), 100.0);
  EXPECT_EQ(sb.normal(nan), Vec3::UnitZ());
  // A point at distance d along the normal from the bottom point (40, -80).
  for (double d : {-0.3, 0.0, 2.0}) EXPECT_NEAR(sb.gap(Vec3(40, 0, -80) + d * n), d, 1e-13);
  // In contact: the normal force is along n, of size k l delta at rest.
  const SeabedForce f = sb.contact(Vec3(40, 3, -80) - 0.01 * n, Vec3::Zero(), 2.0);
  // Round-off: the 0.01 m penetration of a point at 80 m carries 80 * 2.2e-16
  // m of error, times k l = 2e5 N/m: 4e-9 N of the 2000 N force; 1e-11 relative.
  EXPECT_NEAR((f.normal - sb.stiffness * 2.0 * 0.01 * n).norm(), 0, 1e-11 * f.normal.norm());
  EXPECT_EQ(f.friction, Vec3::Zero());
  EXPECT_EQ(f.length, 2.0);
}

TEST(SeabedLaw, FrictionSmoothingConvergesToCoulomb) {
  // Slip at U along the bottom: |F_t| = mu |F_n| U / sqrt(U^2 + v_s^2), so the
  // error to Coulomb is mu |F_n| (v_s/U)^2 / 2 to leading order (the next
  // term, 3/8 (v_s/U)^4, is below 0.12 % of it for v_s/U <= 0.04): halving
  // v_s divides it by 4 (order 2 within 0.01).
  Seabed sb = joint_law(Seabed::flat(10, 1e5, 0, 0.6));
  const double U = 1.0;
  double previous = 0;
  for (double vs : {0.04, 0.02, 0.01, 0.005}) {
    sb.slip_speed = vs;
    const SeabedForce f = sb.contact(Vec3(0, 0, -10.01), Vec3(U, 0, 0), 1.0);
    const double coulomb = sb.friction * f.normal.norm();
    const double err = coulomb - f.friction.norm();
    EXPECT_NEAR(err / coulomb, 0.5 * vs * vs / (U * U), 0.01 * vs * vs / (U * U)) << vs;
    EXPECT_LT(f.friction.x(), 0);  // against the slip
    if (previous > 0) {
      EXPECT_NEAR(std::log2(previous / err), 2.0, 0.01) << vs;
    }
    previous = err;
  }
}

TEST(SeabedLaw, DampingNeverPulls) {
  // Leaving the bottom fast: k delta - c v_n < 0 gives no force at all.
  const Seabed sb = joint_law(Seabed::flat(10, 1e4, 1e3, 0.5));
  const SeabedForce f = sb.contact(Vec3(0, 0, -10.001), Vec3(0.3, 0, 1.0), 1.0);
  EXPECT_EQ(f.normal, Vec3::Zero());
  EXPECT_EQ(f.friction, Vec3::Zero());
}

// ---------------------------------------------------------------------------
// A cable lying flat on the bottom, free at both ends (tow force zero):
// every joint carries exactly the weight of the length it represents, so
// each sinks by delta = w / k (closed form).
// ---------------------------------------------------------------------------
TEST(SeabedCable, RestingJointsSinkByWeightOverStiffness) {
  testing::CableSpec cs;
  cs.n = 10;
  cs.length = 20;
  Model m = testing::cable_model(cs);
  const double depth = 50, k = 1e4;
  m.seabed = joint_law(Seabed::flat(depth, k, 300, 0.5));  // overdamped: zeta = 300 / (2 sqrt(k (m + ma))) ~ 1.1
  m.tow.mode = Tow::Mode::Force;
  m.tow.start = Vec3(0, 0, -depth);
  m.tow.force_time = {0};
  m.tow.force_value = {Vec3::Zero()};
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3::UnitX();
  m.sim.duration = 3;
  m.sim.time_step = 1e-3;
  m.sim.output_interval = 0.5;
  const auto samples = testing::run(m);
  const double delta = apparent_weight(cs) / k;  // [m]
  const Sample& last = samples.back();
  // Slowest vertical mode decays at >= 40 /s: after 3 s only round-off is
  // left; 1e-6 of delta (1 nm) is far above it.
  double worst = 0;
  for (const Vec3& p : last.node_pos) worst = std::max(worst, std::abs(-depth - p.z() - delta) / delta);
  std::printf("resting joints: max |penetration - w/k| / (w/k) = %.2e\n", worst);
  for (std::size_t j = 0; j < last.node_pos.size(); ++j)
    EXPECT_NEAR(-depth - last.node_pos[j].z(), delta, 1e-6 * delta) << "node " << j;
  EXPECT_NEAR(last.contact_length, cs.length, 1e-12);
  EXPECT_NEAR(last.seabed_normal, apparent_weight(cs) * cs.length, 1e-6 * apparent_weight(cs) * cs.length);
  EXPECT_LT(last.seabed_friction, 1e-6);
}

// ---------------------------------------------------------------------------
// A cable from a stationary tow point, its lower part on a flat bottom: the
// suspended part hangs straight down and the part on the bottom carries no
// tension, so the top tension is the apparent weight per metre times the
// depth (MODEL.md 9). Statics, then a dynamic run from it that stays there.
// Bound: the element crossing the bottom hangs at an angle and its top
// carries between 0 and all of its weight, so |T - w h| <= w (L/2 + delta),
// plus w delta for the penetration delta = w / k of the joints on the bottom.
// ---------------------------------------------------------------------------
struct LyingCase {
  int n;         // elements of the 150 m cable
  double depth;  // [m]
};

class SeabedLying : public ::testing::TestWithParam<LyingCase> {};

Model lying_model(const LyingCase& c, testing::CableSpec& cs) {
  cs.n = c.n;
  cs.length = 150;
  Model m = testing::cable_model(cs);
  m.seabed = joint_law(Seabed::flat(c.depth, 1e5, 1e3, 0.5));
  m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point stays at the origin
  return m;
}

TEST_P(SeabedLying, TopTensionIsWeightTimesDepth) {
  testing::CableSpec cs;
  const Model m = lying_model(GetParam(), cs);
  const double w = apparent_weight(cs), L = cs.length / cs.n, h = GetParam().depth, delta = w / 1e5;
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  const double T = r.tow_force.norm();
  std::printf("lying n = %d: (T - w h) / (w L / 2) = %.4f, contact %.3f m, %d iterations\n", cs.n,
              (T - w * h) / (0.5 * w * L), r.sample.contact_length, r.iterations);
  EXPECT_LE(std::abs(T - w * h), w * (0.5 * L + 2 * delta)) << "T = " << T << ", w h = " << w * h;
  // Sharper, the discrete equilibrium itself: m = floor(h / L) elements hang
  // vertically, the crossing one adds half its weight whatever its tilt, so
  // T = w (m L + L / 2) (1e-9 relative: the statics' residual floor).
  const double m_vertical = std::floor(h / L);
  EXPECT_NEAR(T, w * (m_vertical * L + 0.5 * L), 1e-9 * T);
  EXPECT_NEAR(r.tow_force.z(), T, 1e-9 * T);  // straight up: the suspended part hangs vertically
  // On the bottom: the length beyond the depth, to within the crossing element.
  EXPECT_NEAR(r.sample.contact_length, cs.length - h, L);
  EXPECT_NEAR(r.sample.seabed_normal, w * (cs.length - h), w * L);
  // No joint below the bottom by more than the resting penetration (+ 1 %).
  for (const Vec3& p : r.sample.node_pos) EXPECT_GE(p.z(), -h - 1.01 * delta);
}

TEST_P(SeabedLying, DynamicRunStaysOnTheBottom) {
  testing::CableSpec cs;
  Model m = lying_model(GetParam(), cs);
  const double w = apparent_weight(cs), L = cs.length / cs.n, h = GetParam().depth;
  m.initial.kind = Initial::Kind::Steady;
  m.sim.duration = 3;
  // RK4 stable: the free end joint's effective mass is a quarter of its
  // element's (a free rod pushed at its end) for half an element of contact,
  // so its damping rate is 2 c / (m + ma) = 1100 /s: 1100 dt = 1.1 < 2.78.
  m.sim.time_step = 1e-3;
  m.sim.output_interval = 1;
  const auto samples = testing::run(m);
  for (const Sample& s : samples) {
    EXPECT_LE(std::abs(s.tow_force.norm() - w * h), w * (0.5 * L + 2 * w / 1e5)) << "t = " << s.t;
    double vmax = 0;
    std::size_t jmax = 0;
    for (std::size_t j = 0; j < s.node_vel.size(); ++j)
      if (s.node_vel[j].norm() > vmax) vmax = s.node_vel[j].norm(), jmax = j;
    EXPECT_LT(vmax, 1e-4) << "t = " << s.t << " node " << jmax << " v " << s.node_vel[jmax].transpose() << " p "
                          << s.node_pos[jmax].transpose();  // at rest: the statics is the dynamics' equilibrium
  }
}

// A body resting on the bottom at the cable's end adds nothing to the top
// tension (MODEL.md 9): the part on the bottom carries no tension at V = 0.
// The body is a clump (no load model: it touches at its CG, as 1 m of
// cable; link point at the CG, so its rotations are neutral).
TEST_P(SeabedLying, BodyOnTheBottomAddsNothing) {
  testing::CableSpec cs;
  Model m = lying_model(GetParam(), cs);
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 200;
  b.volume = 0.05;
  b.inertia_cg = 10 * Mat3::Identity();
  finalize_body(b, m.fluid);
  const double w = apparent_weight(cs), L = cs.length / cs.n, h = GetParam().depth, delta = w / 1e5;
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(std::abs(r.tow_force.norm() - w * h), w * (0.5 * L + 2 * delta)) << r.tow_force.transpose();
  // The clump rests on the bottom with its apparent weight and half the last
  // element's, on its own spring (1 m) and the cable's at Q = CG (L/2):
  // k (1 + L/2) delta_b = W_b + w L / 2 (1e-6: the residual's force noise).
  const double Wb = (200 - kRho * 0.05) * kG;
  const double zb = r.sample.bodies[0].pos.z();
  EXPECT_NEAR((-h - zb) * 1e5 * (1 + 0.5 * L), Wb + 0.5 * w * L, 1e-6 * Wb);
}

// An in-line body (a clump in the chain, no load model: it touches at its
// CG, as 1 m of cable; both links at the CG, so its rotations are neutral)
// resting on a flat bottom between two lying sections, stationary tow point.
// At rest the lying cable carries no tension and each lying element's
// weight goes half to each end joint, so the point O (the hull's 1 m, the
// half elements above and below, L/2 each) carries W_b + w L:
// k (1 + L) delta_b = W_b + w L, and the hull's own contact force is its
// apparent weight minus the cable's vertical pulls on it: k delta_b.
TEST(SeabedInline, RestingBodySinksByItsLoadOverItsStiffness) {
  testing::CableSpec cs;
  cs.n = 8;
  cs.length = 40;  // upper section: 20 m hanging, 20 m lying
  Model m = testing::cable_model(cs);
  const double depth = 20, k = 1e5, L = 5;
  m.seabed = joint_law(Seabed::flat(depth, k, 1e3, 0.5));
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 300;
  b.volume = 0.05;
  b.inertia_cg = 10 * Mat3::Identity();
  b.inline_body = true;
  b.joint = cs.n;
  b.name = "clump";
  finalize_body(b, m.fluid);
  for (int i = 0; i < 4; ++i)  // lower section: 20 m lying
    m.cable.elements.push_back(
        make_element(L, cs.mass_per_length, cs.diameter, cs.cd, cs.tangential, m.cable.tangential_law, cs.ca, m.fluid));
  const double w = apparent_weight(cs), Wb = (300 - kRho * 0.05) * kG;
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  const double delta_b = -depth - r.sample.bodies[0].pos.z();
  const double pull = k * L * delta_b -
                      w * L;  // the cable's net upward pull at O: its springs there less its shares [N]
  const double T = r.tow_force.norm(), T_discrete = w * (std::floor(depth / L) * L + 0.5 * L);
  std::printf(
      "in-line clump on the bottom: k (1 + L) delta_b = %.6f N, W_b + w L = %.6f N (relative %.2e); hull "
      "contact k delta_b = %.3f N = W_b - %.3f N (the cable's net pull); T = %.4f N, discrete %.4f N\n",
      k * (1 + L) * delta_b, Wb + w * L, (k * (1 + L) * delta_b - Wb - w * L) / Wb, k * delta_b, pull, T, T_discrete);
  // 1e-6 W_b: the residual's force noise (as the end clump above).
  EXPECT_NEAR(k * (1 + L) * delta_b, Wb + w * L, 1e-6 * Wb);
  EXPECT_NEAR(k * delta_b, Wb - pull, 1e-6 * Wb);
  // The body adds nothing to the top tension: the discrete value of
  // SeabedLying (floor(h/L) vertical elements + half the crossing one), 1e-6
  // (the crossing joint sits on the bottom within its sink w/k).
  EXPECT_NEAR(T, T_discrete, 1e-6 * T);
}

TEST(SeabedInline, DraggedBodyIsASteadyStateOfTheDynamics) {
  // The same chain dragged at 0.5 m/s: the statics converge (the sweeps
  // fail, relaxation and the dense solve finish), and 10 s of the dynamics
  // from the result keep every joint and the body within 1 mm of their
  // places relative to the tow point and the tow force within 1e-3 (as
  // SeabedDragged).
  testing::CableSpec cs;
  cs.n = 8;
  cs.length = 40;
  Model m = testing::cable_model(cs);
  m.seabed = joint_law(Seabed::flat(20, 1e5, 1e3, 0.5));
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 300;
  b.volume = 0.05;
  b.inertia_cg = 10 * Mat3::Identity();
  b.inline_body = true;
  b.joint = cs.n;
  b.name = "clump";
  finalize_body(b, m.fluid);
  for (int i = 0; i < 4; ++i)
    m.cable.elements.push_back(make_element(5.0, cs.mass_per_length, cs.diameter, cs.cd, cs.tangential,
                                            m.cable.tangential_law, cs.ca, m.fluid));
  const double U = 0.5;
  m.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), U, 0.0)};
  const StaticsResult r = solve_statics(m, Vec3(U, 0, 0));
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_TRUE(r.message.empty()) << r.message;
  const Drift d = drift_from_steady(m, r, Vec3(U, 0, 0));
  const double dx = d.x, dT = d.force;
  std::printf(
      "dragged in-line clump: %d iterations, residual %.2e; 10 s of dynamics: drift %.2e m, tow force "
      "change %.2e\n",
      r.iterations, r.residual, dx, dT);
  EXPECT_LT(dx, 1e-3);
  EXPECT_LT(dT, 1e-3);
}

// An in-line depressor with a hull (a sphere of radius 0.3 m at O, links
// 0.3 m above and below it, as docs/scenario.md) between 110 m of cable (11
// elements) and a 20 m pigtail (4 elements), stationary tow point. Before,
// the statics started it with its hull and lower link 0.6 m into the bottom
// (the elements were laid, not the body) and the sweeps, which leave the
// contact out, and the dense solve stalled (0.15 to 1.5 rad/s^2 left).
Model depressor_model(double depth, double mass, testing::CableSpec& cs) {
  cs.n = 11;
  cs.length = 110;
  Model m = testing::cable_model(cs);
  m.seabed = joint_law(Seabed::flat(depth, 1e5, 1e3, 0.5));
  m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point stays at the origin
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = mass;
  b.inertia_cg = 4 * Mat3::Identity();
  b.link_point = Vec3(0, 0, 0.3);
  b.lower_link_point = Vec3(0, 0, -0.3);
  b.spheres.push_back({Vec3::Zero(), 0.3, 0.5, 0.5});
  b.inline_body = true;
  b.joint = cs.n;
  b.name = "depressor";
  finalize_body(b, m.fluid);
  for (int i = 0; i < 4; ++i)
    m.cable.elements.push_back(make_element(5.0, cs.mass_per_length, cs.diameter, cs.cd, cs.tangential,
                                            m.cable.tangential_law, cs.ca, m.fluid));
  return m;
}

/// The body's apparent weight (its sphere's buoyancy included) [N].
double body_apparent_weight(const Model& m) {
  const Body& b = m.bodies.front();
  return (b.mass - kRho * b.displaced_volume) * kG;
}

// Heavy (200 kg, 825 N in water) on a 100 m bottom: the body rests on its
// sphere with the cable on both sides lying. The body adds nothing to the top
// tension (MODEL.md 9): |T - w h| <= w (L/2 + 2 delta) as SeabedLying; the
// bottom carries everything else: the contact forces' vertical sum plus the
// top tension's is the apparent weight of cable and body (1e-6: the
// residual's force noise); the sphere rests on the bottom, sunk by at most
// all that can lean on it (its own weight and half of each adjacent element)
// over its spring k 2r; 10 s of dynamics from the result stay within 1 mm.
TEST(SeabedInline, DepressorRestingOnTheBottom) {
  testing::CableSpec cs;
  const double depth = 100;
  const Model m = depressor_model(depth, 200, cs);
  const double w = apparent_weight(cs), L = 10, delta = w / 1e5, Wb = body_apparent_weight(m);
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  const double T = r.tow_force.norm();
  const double sink = 0.3 - (depth + r.sample.bodies[0].pos.z());  // the sphere's lowest point below the bottom [m]
  const double W = w * (110 + 20) + Wb;                            // apparent weight of it all [N]
  std::printf(
      "resting depressor: %d iterations, residual %.2e; (T - w h) / (w L / 2) = %.4f; contact + T_z - W = "
      "%.2e N; sphere sink %.3e m (bound %.3e)\n",
      r.iterations, r.residual, (T - w * depth) / (0.5 * w * L), r.sample.seabed_normal + r.tow_force.z() - W, sink,
      (Wb + 0.5 * w * (L + 5)) / (1e5 * 0.6));
  EXPECT_LE(std::abs(T - w * depth), w * (0.5 * L + 2 * delta));
  EXPECT_NEAR(r.sample.seabed_normal + r.tow_force.z(), W, 1e-6 * W);
  EXPECT_GT(sink, 0);
  EXPECT_LE(sink, (Wb + 0.5 * w * (L + 5)) / (1e5 * 0.6));
  const Drift d = drift_from_steady(m, r, Vec3::Zero());
  std::printf("  10 s of dynamics: drift %.2e m, speed %.2e m/s, tow force change %.2e\n", d.x, d.v, d.force);
  EXPECT_LT(d.x, 1e-3);
  EXPECT_LT(d.v, 1e-3);
  EXPECT_LT(d.force, 1e-3);
}

// The same depressor over 125 m: it hangs, only the pigtail's end lies. The
// suspended cable spans the depth less the body's 0.6 m between its links,
// so T = w (h - 0.6) + W_b within w (L_p / 2 + 2 delta) (the pigtail's
// crossing element, L_p = 5 m); straight up; 10 s of dynamics stay put.
TEST(SeabedInline, DepressorHangingPigtailLying) {
  testing::CableSpec cs;
  const double depth = 125;
  const Model m = depressor_model(depth, 200, cs);
  const double w = apparent_weight(cs), delta = w / 1e5, Wb = body_apparent_weight(m);
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  const double T = r.tow_force.norm(), T0 = w * (depth - 0.6) + Wb;
  std::printf("hanging depressor: (T - w (h - 0.6) - W_b) / (w L_p / 2) = %.4f, contact %.3f m\n",
              (T - T0) / (0.5 * w * 5), r.sample.contact_length);
  EXPECT_LE(std::abs(T - T0), w * (0.5 * 5 + 2 * delta));
  EXPECT_NEAR(r.tow_force.z(), T, 1e-9 * T);
  EXPECT_GT(r.sample.contact_length, 0);
  const Drift d = drift_from_steady(m, r, Vec3::Zero());
  std::printf("  10 s of dynamics: drift %.2e m, tow force change %.2e\n", d.x, d.force);
  EXPECT_LT(d.x, 1e-3);
  EXPECT_LT(d.force, 1e-3);
}

// The audit's case as given: 100 kg with a 0.3 m sphere displaces 115.9 kg,
// so the depressor floats (156 N up) above the bottom; the statics converge
// to an equilibrium of the dynamics (10 s stay within 1 mm) whose top tension
// is still w h within w (L/2 + 2 delta): the body's lift is carried by the
// cable's weight on the bottom.
TEST(SeabedInline, BuoyantDepressorOverTheBottom) {
  testing::CableSpec cs;
  const double depth = 100;
  const Model m = depressor_model(depth, 100, cs);
  const double w = apparent_weight(cs), L = 10, delta = w / 1e5;
  ASSERT_LT(body_apparent_weight(m), 0);
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  const double T = r.tow_force.norm();
  std::printf("buoyant depressor: body %.3f m above the bottom, (T - w h) / (w L / 2) = %.4f\n",
              depth + r.sample.bodies[0].pos.z(), (T - w * depth) / (0.5 * w * L));
  EXPECT_LE(std::abs(T - w * depth), w * (0.5 * L + 2 * delta));
  const Drift d = drift_from_steady(m, r, Vec3::Zero());
  std::printf("  10 s of dynamics: drift %.2e m, tow force change %.2e\n", d.x, d.force);
  EXPECT_LT(d.x, 1e-3);
  EXPECT_LT(d.force, 1e-3);
}

// The heavy depressor of DepressorRestingOnTheBottom dragged at 0.5 m/s: a
// two-part tow whose in-line body slides on its sphere with the cable lying
// on both sides of it (exit 3 before: 2.10 rad/s^2 left, the body turned
// over backwards). Checks: the body rests on its sphere, sunk within the
// bound at rest, and 10 s of the dynamics from the result stay put (1 mm,
// 1 mm/s, 1e-3 of the tow force: as DraggedBodyIsASteadyStateOfTheDynamics;
// measured 5.8e-9 m).
TEST(SeabedInline, DepressorDraggedOnTheBottom) {
  testing::CableSpec cs;
  Model m = depressor_model(100, 200, cs);
  const double U = 0.5;
  m.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), U, 0.0)};
  const StaticsResult r = solve_statics(m, Vec3(U, 0, 0));
  ASSERT_TRUE(r.converged) << r.message;
  // The body slides on its sphere: sunk into the bottom, by at most all
  // that can lean on it (its weight and half of each adjacent element) over
  // its spring k 2r, as at rest (the cable's pulls on it point up or along).
  const double w = apparent_weight(cs), Wb = body_apparent_weight(m);
  const double sink = 0.3 - (100 + r.sample.bodies[0].pos.z());  // [m]
  EXPECT_GT(sink, 0);
  EXPECT_LE(sink, (Wb + 0.5 * w * (10 + 5)) / (1e5 * 0.6));
  const Drift d = drift_from_steady(m, r, Vec3(U, 0, 0));
  std::printf(
      "dragged depressor on the bottom: %d iterations, residual %.2e; sphere sink %.3e m; contact %.2f m; "
      "T = %.3f N; 10 s of dynamics: drift %.2e m, |v - U| %.2e m/s, tow force change %.2e\n",
      r.iterations, r.residual, sink, r.sample.contact_length, r.tow_force.norm(), d.x, d.v, d.force);
  EXPECT_LT(d.x, 1e-3);
  EXPECT_LT(d.v, 1e-3);
  EXPECT_LT(d.force, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Seabed, SeabedLying,
                         ::testing::Values(LyingCase{75, 101.0}, LyingCase{100, 101.0}, LyingCase{150, 100.3}),
                         [](const auto& info) { return "n" + std::to_string(info.param.n); });

// ---------------------------------------------------------------------------
// The same check paid out (MODEL.md 9): from a stationary tow point a winch
// pays a vertically hanging cable out onto the bottom (40 m -> 70.25 m over
// a 50 m depth, 0.5 m/s, then holds). The upright column landing on the
// bottom must fall over and lie there, not be driven into the bottom (an
// exactly vertical column: the end 20 m below the bottom and 2e7 N at the
// top; the run's start leans it by 1e-4 rad, lean_upright). After
// it settles the top tension is w h within the crossing element's
// w (L/2 + 2 delta) (the bound above, 5 % of w h here; measured at 150 s:
// 1.1 % with rosenbrock, 1.4 % with rk4 at the joints, 1.2 % and 3.7 % along
// elements, where the lying part's smoothed friction still creeps), and no
// joint is ever deeper than 0.1 m (measured: 2e-4 m; the resting
// penetration w / k is 1.2e-4 m). Under either contact law.
// ---------------------------------------------------------------------------
TEST(SeabedPayOut, VerticalPayOutLandsAndLies) {
  testing::CableSpec cs;
  cs.n = 8;
  cs.length = 40;
  const double h = 50, Le = 5, w = apparent_weight(cs), delta = w / 1e5;
  for (const bool along : {false, true}) {
    for (const Integrator integ : {Integrator::Rosenbrock, Integrator::RK4}) {
      Model m = testing::cable_model(cs);
      m.seabed = Seabed::flat(h, 1e5, 1e3, 0.5);
      m.seabed->along_elements = along;
      m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point stays at the origin
      testing::impose_winch(m, cs.n, cs.length, {0.0, 60.0, 61.0}, {0.5, 0.5, 0.0});  // Le = cs.length / cs.n
      m.sim.integrator = integ;
      m.sim.time_step = 1e-3;  // rk4's step; rosenbrock's first
      m.sim.duration = 150;
      m.sim.output_interval = 1;
      const auto samples = testing::run(m);
      ASSERT_FALSE(samples.empty());
      const Sample& last = samples.back();
      ASSERT_NEAR(last.t, 150, 1e-9);
      ASSERT_NEAR(last.deployed_length, 70.25, 1e-9);
      const double T = last.tow_force.norm();
      std::printf("vertical pay-out onto the bottom (%s, %s): T / (w h) = %.4f, contact %.2f m\n",
                  along ? "along elements" : "at joints", integrator_key(integ), T / (w * h), last.contact_length);
      EXPECT_LE(std::abs(T - w * h), w * (0.5 * Le + 2 * delta)) << integrator_key(integ);
      EXPECT_NEAR(last.contact_length, 70.25 - h, 2 * Le) << integrator_key(integ);
      for (const Sample& smp : samples)
        for (const Vec3& p : smp.node_pos)
          EXPECT_GE(p.z(), -h - 0.1) << "t = " << smp.t << ", " << integrator_key(integ);
    }
  }
}

// ---------------------------------------------------------------------------
// A cable dragged along a flat bottom at a steady speed U (issue 13): the
// statics converge (dynamic relaxation, then the dense solve), the result
// is a steady state of the dynamics, and it has the closed forms of a
// dragged cable without tangential drag: along the lying part the
// horizontal tension grows by mu s w per metre (s = U / sqrt(U^2 + v_s^2),
// the law's smoothing), and the suspended part adds w per metre of rise, so
// the top tension is w (depth - delta) + mu s w (lying length).
// ---------------------------------------------------------------------------
Model dragged_model(testing::CableSpec& cs, double U) {
  cs.n = 30;
  cs.length = 300;
  cs.tangential = 0;  // no tangential drag: the closed forms hold exactly
  Model m = testing::cable_model(cs);
  m.seabed = joint_law(Seabed::flat(110, 1e5, 1e3, 0.5));
  m.tow.mode = Tow::Mode::Motion;
  m.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), U, 0.0)};
  return m;
}

TEST(SeabedDragged, SteadyTowHasTheClosedForms) {
  for (double U : {0.01, 0.1, 0.5, 1.0}) {
    testing::CableSpec cs;
    const Model m = dragged_model(cs, U);
    const double w = apparent_weight(cs), L = cs.length / cs.n, mu = 0.5, delta = w / 1e5;
    const double s = U / std::hypot(U, kSeabedSlipSpeed);
    const StaticsResult r = solve_statics(m, Vec3(U, 0, 0));
    ASSERT_TRUE(r.converged) << "U = " << U << ": " << r.message;
    // The lying joints (behind the touchdown, before the end): each carries
    // exactly the weight of the length it stands for, so the horizontal
    // force steps by mu s w L from joint to joint (1e-6: above the
    // touchdown's decaying disturbance, 6e-9 two joints down, and the
    // residual left, ~1e-10 rad/s^2 times the inertias).
    int lying = 0;
    double worst = 0;
    for (int j = 2; j + 1 < cs.n; ++j) {
      const auto u = static_cast<std::size_t>(j);
      // Two joints above on the bottom: the touchdown's disturbance of the
      // shares decays by ~1e4 per joint (measured: 4e-5 at the first lying
      // joint, 6e-9 at the second).
      if (r.sample.node_pos[u - 2].z() > -110 + 1e-3) continue;
      ++lying;
      const double step = r.joint_force[u].x() - r.joint_force[u + 1].x();
      worst = std::max(worst, std::abs(step - mu * s * w * L) / (mu * s * w * L));
    }
    const double T = r.tow_force.norm(), Tc = w * (110 - delta) + mu * s * w * r.sample.contact_length;
    std::printf(
        "dragged U = %.2f: %d iterations, %d lying steps within %.1e of mu s w L; T = %.3f N, closed form "
        "%.3f N (%+.2e w L)\n",
        U, r.iterations, lying, worst, T, Tc, (T - Tc) / (w * L));
    EXPECT_GE(lying, 5) << U;
    EXPECT_LT(worst, 1e-6) << U;
    // Top tension: the contact length counts the touchdown joint's whole
    // share, which carries only part of its weight on the bottom, and the
    // rigid elements' kinks shift the tension by O(w L): bound w L.
    EXPECT_NEAR(T, Tc, w * L) << U;
  }
}

TEST(SeabedDragged, SteadyStateStaysSteadyInTheDynamics) {
  // 10 s of the dynamics (rosenbrock, fixed error target) from the steady
  // start: every joint keeps its place relative to the tow point within
  // 1 mm and moves at U within 1 mm/s, and the tow force stays within 1e-3
  // of the statics' (the integration error of a 1e-8 tolerance on a state
  // at rest, with contact springs of 1e5 N/m per m, is far below these).
  // U = 0.01 m/s: the friction's smoothing speed, where its viscous slope
  // made the relaxation creep (the statics relax with a sharper law of the
  // same steady friction, then solve with the true one).
  for (double U : {0.01, 0.5}) {
    testing::CableSpec cs;
    Model m = dragged_model(cs, U);
    const StaticsResult r = solve_statics(m, Vec3(U, 0, 0));
    ASSERT_TRUE(r.converged) << "U = " << U << ": " << r.message;
    const Drift d = drift_from_steady(m, r, Vec3(U, 0, 0));
    const double dx = d.x, dv = d.v, dT = d.force;
    std::printf(
        "dragged at %.2f m/s, 10 s of dynamics from the statics: max joint drift %.2e m, max |v - U| %.2e "
        "m/s, max tow force change %.2e\n",
        U, dx, dv, dT);
    EXPECT_LT(dx, 1e-3) << U;
    EXPECT_LT(dv, 1e-3) << U;
    EXPECT_LT(dT, 1e-3) << U;
  }
}

// Long dragged cables, solved by Newton-Krylov (the stage solve as its
// preconditioner) after the relaxation: 300 m in 150 elements (300
// unknowns, where the dense solve took 2 s before) and 1400 m in 700 (1400
// unknowns, above the dense solve's limit of 1200; relaxation leaves ~5e-4
// rad/s^2) dragged at 0.5 m/s over a 110 m bottom. The same closed forms as
// the 30-element case (lying steps mu s w L within 1e-6, top tension within
// w L), and 10 s of the dynamics from the result keep every joint within
// 1 mm and the tow force within 1e-3 (as SteadyStateStaysSteadyInTheDynamics).
void check_long_dragged(int n) {
  testing::CableSpec cs;
  const double U = 0.5;
  Model m = dragged_model(cs, U);
  cs.n = n;
  cs.length = 2.0 * n;
  {
    const Model long_model = testing::cable_model(cs);
    m.cable = long_model.cable;
  }
  const double w = apparent_weight(cs), L = cs.length / cs.n, mu = 0.5, delta = w / 1e5;
  const double s = U / std::hypot(U, kSeabedSlipSpeed);
  const StaticsResult r = solve_statics(m, Vec3(U, 0, 0));
  ASSERT_TRUE(r.converged) << n << ": " << r.message;
  // The touchdown's disturbance of the shares decays more slowly per joint
  // on 2 m elements than on 10 m ones (measured: 7.9e-5 at the first lying
  // joint counted, 1.2e-6 at the second): the bound from the fourth on, the
  // worst of the first three printed.
  int lying = 0;
  double worst = 0, near = 0;
  for (int j = 2; j + 1 < cs.n; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (r.sample.node_pos[u - 2].z() > -110 + 1e-3) continue;  // two joints past the touchdown (as above)
    ++lying;
    const double step = r.joint_force[u].x() - r.joint_force[u + 1].x();
    const double err = std::abs(step - mu * s * w * L) / (mu * s * w * L);
    if (lying <= 3)
      near = std::max(near, err);
    else
      worst = std::max(worst, err);
  }
  const double T = r.tow_force.norm(), Tc = w * (110 - delta) + mu * s * w * r.sample.contact_length;
  const Drift d = drift_from_steady(m, r, Vec3(U, 0, 0));
  std::printf(
      "dragged, %d elements: %d iterations, residual %.2e; %d lying steps within %.1e of mu s w L (the first 3: "
      "%.1e); T = %.3f N, "
      "closed form %.3f N (%+.2e w L); 10 s of dynamics: drift %.2e m, |v - U| %.2e m/s, tow force change %.2e\n",
      n, r.iterations, r.residual, lying, worst, near, T, Tc, (T - Tc) / (w * L), d.x, d.v, d.force);
  EXPECT_GE(lying, 50) << n;
  EXPECT_LT(worst, 1e-6) << n;
  EXPECT_NEAR(T, Tc, w * L) << n;
  EXPECT_LT(d.x, 1e-3) << n;
  EXPECT_LT(d.v, 1e-3) << n;
  EXPECT_LT(d.force, 1e-3) << n;
}

TEST(SeabedDragged, LongCableBeyondTheDenseSolve) {
  for (int n : {150, 700}) check_long_dragged(n);
}

// 2000 m in 1000 elements: the full Newton step raised |r| 200-fold at the
// touchdown (the second-order drop of the lying part under the suspended
// elements' turn, met by the contact springs) and the solve stalled at
// 1.0e-3 rad/s^2 (exit 3); with the touchdown held at its linear move
// (SteadyProblem::on_bottom) it converges. The same checks as above.
TEST(SeabedDragged, ThousandElementsPastTheTouchdown) { check_long_dragged(1000); }

// ---------------------------------------------------------------------------
// Newton-Krylov's compression guard (docs/theory.md §7): Newton finds
// unstable equilibria too. A heavy chain of 10 elements standing straight
// up from a stationary tow point, 1000 m above the bottom, is one exactly
// (each element's weight along its axis: no moment), every element in
// compression. Started tilted 0.01 rad from it, Newton-Krylov (which
// solve_statics uses above 600 elements, or above 100 after relaxing)
// steps towards it and the guard drops the result, a chain in compression,
// for the start (before this test the guard was reached only by forcing
// Newton-Krylov on a small problem). Started tilted as much from hanging,
// the same solve converges to the hanging chain, whose top tension is the
// cable's apparent weight w L (closed form; 1e-9: the residual floor's
// moments, ~1e-8 rad/s^2 times the inertias, over lever arms of metres).
// ---------------------------------------------------------------------------
TEST(SeabedNewtonKrylov, CompressionGuardDropsTheInvertedColumn) {
  testing::CableSpec cs;
  cs.n = 10;
  cs.length = 100;
  Model m = testing::cable_model(cs);
  m.seabed = joint_law(Seabed::flat(1000, 1e5, 1e3, 0.5));
  m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point stays at the origin
  const double a = 0.01;           // tilt of the start [rad]
  auto start = [&](double up) {
    PhysicalState s = PhysicalState::hanging(m);
    for (auto& e : s.e) e = Vec3(std::sin(a), 0, up * std::cos(a));
    return s;
  };
  PhysicalState column = start(1.0);
  const StaticsResult inverted = newton_krylov_statics(m, Vec3::Zero(), column);
  std::printf("inverted start: %d Newton steps, guard: '%s', residual at the start kept %.2e rad/s^2\n",
              inverted.iterations, inverted.message.c_str(), inverted.residual);
  EXPECT_EQ(inverted.message, "compression");
  EXPECT_FALSE(inverted.converged);
  EXPECT_GT(inverted.iterations, 0);  // Newton steps were taken, then dropped
  for (std::size_t k = 0; k < column.e.size(); ++k) EXPECT_EQ(inverted.state.e[k], column.e[k]) << k;
  // The exact column is an equilibrium (zero residual, no step) and dropped as well.
  for (auto& e : column.e) e = Vec3::UnitZ();
  const StaticsResult exact = newton_krylov_statics(m, Vec3::Zero(), column);
  EXPECT_EQ(exact.iterations, 0);
  EXPECT_LT(exact.residual, 1e-12);
  EXPECT_EQ(exact.message, "compression");
  // The stable side: converged, no guard, the tension of a hanging chain.
  const StaticsResult hanging = newton_krylov_statics(m, Vec3::Zero(), start(-1.0));
  const double W = apparent_weight(cs) * cs.length;  // [N]
  std::printf("hanging start: %d Newton steps, residual %.2e, T / (w L) - 1 = %.2e\n", hanging.iterations,
              hanging.residual, hanging.tow_force.norm() / W - 1);
  EXPECT_TRUE(hanging.converged) << hanging.message;
  EXPECT_TRUE(hanging.message.empty());
  EXPECT_NEAR(hanging.tow_force.norm(), W, 1e-9 * W);
}

// ---------------------------------------------------------------------------
// A cable at rest on a sloped bottom (a depth table, slope 0.1 deepening
// along +x), stationary tow point: at rest there is no friction, so the
// lying part hangs on its tension along the slope. Closed forms: between
// lying joints the force steps by the weight's component along the slope,
// (f_j - f_j+1) . d = w L sin(beta) exactly (the bottom pushes only along
// its normal); the top tension of a continuous frictionless cable at rest
// is w (z_0 - z_end). Then 10 s of dynamics from the result stay put.
// ---------------------------------------------------------------------------
TEST(SeabedSlope, RestingCableHangsOnItsTensionAlongTheSlope) {
  testing::CableSpec cs;
  cs.n = 30;
  cs.length = 300;
  Model m = testing::cable_model(cs);
  m.seabed = joint_law(Seabed::flat(100, 1e5, 1e3, 0.5));
  m.seabed->x = {0, 1000};
  m.seabed->depth = {100, 200};
  m.tow.mode = Tow::Mode::Motion;
  const double w = apparent_weight(cs), L = cs.length / cs.n, beta = std::atan(0.1);
  const Vec3 d = Vec3(std::cos(beta), 0, -std::sin(beta));  // downslope [-]
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  int lying = 0;
  double worst = 0;
  for (int j = 1; j + 1 < cs.n; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (m.seabed->gap(r.sample.node_pos[u - 1]) > 0 || m.seabed->gap(r.sample.node_pos[u]) > 0) continue;
    ++lying;
    const double step = (r.joint_force[u] - r.joint_force[u + 1]).dot(d);
    worst = std::max(worst, std::abs(std::abs(step) - w * L * std::sin(beta)) / (w * L * std::sin(beta)));
  }
  const double T = r.tow_force.norm(), Tc = w * (r.sample.tow_pos.z() - r.sample.node_pos.back().z());
  std::printf(
      "slope at rest: %d iterations, %d lying steps within %.1e of w L sin(beta); T = %.3f N, w (z_0 - "
      "z_end) = %.3f N (%+.2e w L)\n",
      r.iterations, lying, worst, T, Tc, (T - Tc) / (w * L));
  EXPECT_GE(lying, 5);
  EXPECT_LT(worst, 1e-6);     // residual floor's force noise, far below
  EXPECT_NEAR(T, Tc, w * L);  // the discrete chain's kinks at the touchdown: O(w L)
  // The dynamics from it (rosenbrock, tolerance 1e-8, 10 s): every joint
  // within 1 mm of its place, speeds below 1 mm/s.
  const Drift drift = drift_from_steady(m, r, Vec3::Zero());
  const double dx = drift.x, dv = drift.v;
  std::printf("slope at rest, 10 s of dynamics: drift %.2e m, speed %.2e m/s\n", dx, dv);
  EXPECT_LT(dx, 1e-3);
  EXPECT_LT(dv, 1e-3);
}

// ---------------------------------------------------------------------------
// A sled (a body resting on two runner ends) dragged along the bottom at a
// steady slow speed: along the tow, the cable's pull balances the friction
// mu N (N = apparent weight - the pull's vertical part) and the sled's
// hydrodynamic drag, computed here from the cylinder's skin-friction law.
// ---------------------------------------------------------------------------
TEST(SeabedSled, TowingForceIsFrictionPlusDrag) {
  testing::CableSpec cs;
  cs.n = 5;
  cs.length = 10;
  Model m = testing::cable_model(cs);
  const double depth = 50, mu = 0.4, U = 0.5, radius = 0.2, length = 2.0, ct = 0.01, mass = 500;
  m.seabed = joint_law(Seabed::flat(depth, 1e4, 1e3, mu));
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = mass;
  b.inertia_cg = Vec3(10, 170, 170).asDiagonal();
  b.link_point = Vec3(0.5 * length, 0, 0);  // the runner's nose, on its axis
  b.cylinders.push_back({Vec3::Zero(), Vec3::UnitX(), length, 2 * radius, 1.2, ct, 1.0});
  finalize_body(b, m.fluid);
  // Tow point 1 m above the runner's axis; cable streaming straight back.
  m.tow.start = Vec3(0, 0, -depth + radius + 1.0);
  m.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), U, 5.0)};
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3(-cs.length, 0, -1.0).normalized();
  m.sim.duration = 60;
  m.sim.time_step = 2e-3;
  m.sim.output_interval = 1;
  const auto samples = testing::run(m);
  const Sample& s = samples.back();
  const Vec3 FL = s.bodies[0].link_force;  // on the sled from the cable [N]
  const double volume = std::numbers::pi * radius * radius * length;
  const double W = (mass - kRho * volume) * kG;               // apparent weight [N]
  const double N = W - FL.z();                                // the bottom's normal load [N]
  const double smooth = U / std::hypot(U, kSeabedSlipSpeed);  // the law's smoothing at slip U
  const double drag = 0.5 * kRho * std::numbers::pi * 2 * radius * length * ct * U * U;  // axial skin friction [N]
  std::printf("sled: F_L,x = %.6f N, mu N s + drag = %.6f N (drag %.4f N), relative difference %.2e\n", FL.x(),
              mu * N * smooth + drag, drag, (FL.x() - mu * N * smooth - drag) / (mu * N));
  EXPECT_NEAR(s.bodies[0].vel.x(), U, 1e-3 * U);  // steady
  // Steady to 0.1 % of the friction (the body's residual acceleration times
  // its mass is below that after 55 s at speed).
  EXPECT_NEAR(FL.x(), mu * N * smooth + drag, 1e-3 * mu * N) << "N = " << N << ", drag = " << drag;
  EXPECT_NEAR(std::abs(FL.y()), 0, 1e-6 * mu * N);
  EXPECT_GT(s.seabed_friction, mu * N * smooth * (1 - 1e-3));  // the sled's friction is in the total
}

}  // namespace
}  // namespace towsim
