// The Rosenbrock-W stage solve with a body's own seabed contact points
// (docs/theory.md §6.3, "A body's own contact"): the stage matrix against
// a finite-difference Jacobian of the dynamics, a heavy sled landing on a
// stiff bottom (steps bounded by accuracy, not by the contact; the sink is
// weight / stiffness), and the sled dragged along the bottom at fixed large
// steps against a fine RK4 reference.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <utility>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "../support/rosenbrock.hpp"

namespace towsim {
namespace {

using testing::fixed_rosenbrock;
using testing::stage_W;

constexpr double kRho = 1025, kG = 9.81;         // the test models' water [kg/m^3] and gravity [m/s^2]
constexpr double kMass = 1135, kRadius = 0.368;  // km-turn-100's sled: mass [kg], sphere radius [m]
constexpr double kCable = 20;                    // cable length [m] (4 elements of 5 m)

/// Apparent weight of the sled [N]: the sphere's displacement only.
double sled_weight() { return (kMass - kRho * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3)) * kG; }

/// Apparent weight per metre of the km cable [N/m].
double cable_weight() { return (1.12 - kRho * std::numbers::pi / 4 * 0.0173 * 0.0173) * kG; }

/// km-turn-100's sled (1135 kg sphere, r 0.368 m, link on top) on 20 m of
/// its cable in 4 elements, hanging from a free tow point (Force mode) that
/// carries the cable's apparent weight, so that the link force is zero and the
/// sled rests on the bottom with its whole apparent weight. The bottom is
/// `gap0` below the sphere's lowest point in the hanging start (< 0: the
/// sphere starts sunk by -gap0). Contact stiffness k [N/m per m], the
/// default damping 1e3 N s/m per m and friction 0.5.
Model sled_model(double k, double gap0, bool runner = false) {
  testing::CableSpec c;
  c.n = 4;
  c.length = kCable;
  c.mass_per_length = 1.12;
  c.diameter = 0.0173;
  c.cd = 1.5;
  c.tangential = 0.01;
  c.law = TangentialLaw::Skin;
  Model m = testing::cable_model(c);
  testing::add_sphere_body(m, kMass, kRadius, 0.77, 0.5);
  if (runner) {
    // A runner instead: a 2 m cylinder of the sphere's diameter along x_b,
    // resting on its two end discs (1 m either side of O: a lever arm).
    Body& b = m.bodies.back();
    b.spheres.clear();
    b.cylinders.push_back({Vec3::Zero(), Vec3::UnitX(), 2.0, 2 * kRadius, 1.2, 0.01, 1.0});
    b.inertia_cg = Vec3(80, 420, 420).asDiagonal();
    finalize_body(b, m.fluid);
  }
  m.seabed = Seabed::flat(kCable + 2 * kRadius + gap0, k, 1e3, 0.5);
  m.tow.mode = Tow::Mode::Force;
  m.tow.force_time = {0.0};
  m.tow.force_value = {Vec3(0, 0, cable_weight() * kCable)};
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.time_step = 0.01;
  m.sim.output_interval = 0.5;
  return m;
}

/// Sink of the sled's lowest point below the bottom [m] in a sample.
double sink(const Model& m, const Sample& s) { return kRadius - s.bodies[0].pos.z() - m.seabed->depth_at(0); }

/// RK4's stability bound on the sled's contact spring, 2 sqrt(2) / omega,
/// omega = sqrt(k 2r / M): M the sled with its added mass and the cable
/// (1135 + 107 + 22.4 kg; Force mode: the whole chain moves with it) [s].
double spring_bound(double k) { return 2 * std::sqrt(2.0) / std::sqrt(k * 2 * kRadius / 1264.0); }

/// Relative mismatch of the stage matrix's W and the dynamics' Jacobian J
/// (central differences, step 1e-7) at the initial state of m with the
/// velocities v (every part translating at v [m/s]): ||(W - J) X|| / ||J X||
/// over the velocity rows (tow point, element and body rates) and the tangent
/// directions X of the state (tow point position and velocity; per element
/// two rotations and two rates normal to e; the body's three rotations and
/// three rates); `velocity_only`: the rate directions only.
/// Elements from `lying_from` on lie along x_g (the others hang).
struct Mismatch {
  double abs = 0;  // ||(W - J) X|| [SI, mixed]
  double rel = 0;  // ||(W - J) X|| / ||J X|| [-]
};
Mismatch stage_matrix_mismatch(const Model& m, const Vec3& v, bool velocity_only, std::size_t lying_from = 1000) {
  auto sys = make_system(m);
  PhysicalState s0 = initial_state(m);
  s0.v0 = v;
  for (std::size_t k = lying_from; k < s0.e.size(); ++k) s0.e[k] = Vec3::UnitX();
  const StateVector y = sys->initial(s0, 0.0);
  const std::size_t N = y.size(), n = s0.e.size(), ob = 6 + 6 * n;
  StateVector f;
  sys->derivative(y, f, 0.0);
  sys->prepare_stage_solve(0.0, StepWindow{});
  const Eigen::MatrixXd W = stage_W(*sys, N, 0.01);
  const auto Ni = static_cast<Eigen::Index>(N);
  auto at = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  std::vector<Eigen::VectorXd> X;
  auto add = [&](std::size_t o, const Vec3& t) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(Ni);
    x.segment<3>(at(o)) = t;
    X.push_back(x);
  };
  for (int j = 0; j < 3; ++j) {
    if (!velocity_only) add(0, Vec3::Unit(j));
    add(3, Vec3::Unit(j));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& e = s0.e[k];
    Eigen::Index im;
    e.cwiseAbs().minCoeff(&im);
    const Vec3 t1 = e.cross(Vec3::Unit(im)).normalized(), t2 = e.cross(t1);
    for (const Vec3& t : {t1, t2}) {
      if (!velocity_only) add(6 + 3 * k, t);
      add(6 + 3 * n + 3 * k, t);
    }
  }
  for (int j = 0; j < 3; ++j) {
    add(ob + 4, Vec3::Unit(j));
    if (velocity_only) continue;
    // Rotation by a about the body: dq = 1/2 (0, a) q.
    const Quat dq = Quat(0, Vec3::Unit(j).x(), Vec3::Unit(j).y(), Vec3::Unit(j).z()) * s0.bodies[0].q;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(Ni);
    x.segment<4>(at(ob)) << 0.5 * dq.w(), 0.5 * dq.x(), 0.5 * dq.y(), 0.5 * dq.z();
    X.push_back(x);
  }
  std::vector<std::size_t> rows = {3, 4, 5, ob + 4, ob + 5, ob + 6};
  for (std::size_t i = 0; i < 3 * n; ++i) rows.push_back(6 + 3 * n + i);
  double num = 0, den = 0;
  const double eps = 1e-7;
  for (const Eigen::VectorXd& x : X) {
    StateVector yp = y, ym = y, fp, fm;
    for (std::size_t i = 0; i < N; ++i) yp[i] += eps * x[at(i)], ym[i] -= eps * x[at(i)];
    sys->derivative(yp, fp, 0.0);
    sys->derivative(ym, fm, 0.0);
    const Eigen::VectorXd Wx = W * x;
    for (const std::size_t r : rows) {
      const double jx = (fp[r] - fm[r]) / (2 * eps);
      num += (Wx[at(r)] - jx) * (Wx[at(r)] - jx);
      den += jx * jx;
    }
  }
  return {std::sqrt(num), std::sqrt(num / den)};
}

// The stage matrix against the dynamics: W = (I - S^-1)/hg from the stage
// solve S, and J by central differences of the dynamics, with the sled in
// contact. At rest the contact dominates J: the spring k 2r on the sled's
// height, the friction's slope mu N / v_s on its lowest point (through the
// lever arm r: a rolling term), and a runner's two end discs 1 m either side
// of O turn the springs into a pitch stiffness. Every other term of J is in
// W here (the hanging chain's rocking is exact at rest), so W = J up to
// the differences' error. Sliding (0.3, 0.1, 0) m/s, the rate columns: the
// friction's slope across and along the slip, the contact damping, the
// drag (the friction's dependence on the penetration, a position column,
// is left out of W: Seabed::contact_slopes).
TEST(RosenbrockBodyContact, StageMatrixIsTheDynamicsJacobian) {
  const double k = 1e6, d = sled_weight() / (k * 2 * kRadius);
  const struct {
    const char* name;
    Model m;
    Vec3 v;
    bool velocity_only;
    double bound;
  } cases[] = {{"sphere sled at rest", sled_model(k, -d), Vec3::Zero(), false, 1e-6},
               {"runner sled at rest", sled_model(k, -0.01, true), Vec3::Zero(), false, 1e-2},
               {"runner sled sliding", sled_model(k, -0.01, true), Vec3(0.3, 0.1, 0), true, 1e-2}};
  for (const auto& c : cases) {
    const double e = stage_matrix_mismatch(c.m, c.v, c.velocity_only).rel;
    std::cout << "[measured] " << c.name << ", k " << k << ": ||(W - J) X|| / ||J X|| = " << e << "\n";
    // Without the body's contact terms all three were 1.00 (W had none of
    // the contact's part, which dominates J). With them: the sphere at rest
    // 1.3e-9, the differences' own error (eps_mach |f| / 1e-7 against
    // |J X| ~ 1e4): bound 1e-6. The runner: 7.0e-4 at rest, terms W leaves
    // out by design (the contact forces' lever-arm stiffness, -2 R F in
    // pitch: negative, and a W never takes negative stiffness), and 3.0e-3
    // sliding, outside the contact (the same absolute mismatch, 4.2 against
    // 3.9, with the seabed removed: the symmetrised drag, local chain
    // terms): bound 1e-2, a hundredth of the mismatch without the terms.
    EXPECT_LT(e, c.bound) << c.name;
  }
}

// The same for an in-line body: a 300 kg clump (no load model: it touches
// at its CG = O, 0.5 m below its links: no lever arm) between 20 m of hanging cable and 10 m
// lying along x_g just above the bottom, its CG 1 cm deep, at rest. The
// clump's terms enter its 6x6 block before the cable below is taken in
// (body_factor).
TEST(RosenbrockBodyContact, StageMatrixOfAnInlineBodyOnTheBottom) {
  Model m = sled_model(1e6, 0.0);
  m.bodies.clear();
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 300;
  b.volume = 0.05;
  b.inertia_cg = 10 * Mat3::Identity();
  b.link_point = b.lower_link_point = Vec3(0, 0, 0.5);
  b.inline_body = true;
  b.joint = 4;
  b.name = "clump";
  finalize_body(b, m.fluid);
  const Element el = m.cable.elements.back();
  m.cable.elements.push_back(el);
  m.cable.elements.push_back(el);
  m.seabed = Seabed::flat(kCable + 0.49, 1e6, 1e3, 0.5);
  const Mismatch on = stage_matrix_mismatch(m, Vec3::Zero(), false, 4);
  Model off = m;
  off.seabed = Seabed::flat(kCable + 5, 1e6, 1e3, 0.5);  // the same state off the bottom
  const Mismatch free = stage_matrix_mismatch(off, Vec3::Zero(), false, 4);
  std::cout << "[measured] in-line clump on the bottom, k 1e6: ||(W - J) X|| = " << on.abs << " (relative " << on.rel
            << "); off the bottom " << free.abs << "\n";
  // Measured 117 (1.0e-2 of ||J X|| = 1.1e4) on the bottom, 138 off it:
  // what is left is the same non-local coupling of this state (a horizontal
  // cable released from rest), none of it from the contact. Without the
  // clump's terms 11247 (relative 1.00). Bounds: no more than off the
  // bottom (x 1.2: the states' forces differ), and 2e-2 relative.
  EXPECT_LT(on.abs, 1.2 * free.abs);
  EXPECT_LT(on.rel, 2e-2);
}

// The sled resting on the bottom (started at its sink W/(k 2r), the link
// force zero), 60 s, rosenbrock adaptive at tolerance 1e-6, k = 1e5, 1e6,
// 1e7 N/m per m: at rest the contact's stiff modes are the spring (omega =
// sqrt(k 2r / M), RK4 bound 2 sqrt(2)/omega = 0.37, 0.12, 0.037 s) and the
// friction's slope at rest, mu N / v_s on the lowest point, rate 1358 /s
// (M_eff = 1/(1/1242 + r^2/I) = 333 kg with the sphere's rolling; RK4 bound
// 2.785 / 1358 = 2.1 ms). Then fixed steps of 0.25 s (7x the stiffest
// spring's bound, 120x the friction's).
TEST(RosenbrockBodyContact, RestingSledStepsAreBoundedByAccuracy) {
  for (const double k : {1e5, 1e6, 1e7}) {
    const double d = sled_weight() / (k * 2 * kRadius);
    Model m = sled_model(k, -d);
    m.sim.duration = 60;
    m.sim.tolerance = 1e-6;
    RunStats st;
    const auto samples = testing::run(m, &st);
    double e = 0;
    for (const Sample& s : samples) e = std::max(e, std::abs(sink(m, s) - d) / d);
    const double mean = m.sim.duration / static_cast<double>(st.steps);
    std::cout << "[measured] resting sled, k " << k << ": " << st.steps << " steps, " << st.rejected_steps
              << " rejected, mean step " << mean << " s (spring's RK4 bound " << spring_bound(k)
              << " s); max |sink - W/(k 2r)| / (W/(k 2r)) = " << e << "\n";
    // Measured 63 steps, none rejected, at every k (mean 0.95 s: 2.6x to
    // 26x the spring's bound, 460x the friction's); sink within 5.6e-12
    // (round-off of the statics-free start). Without the body's contact
    // terms: 335, 1230, 5299 steps (148, 510, 1508 rejected, mean 11 ms at
    // k = 1e7) and the sink off by 4.6e-6 to 4.4e-4.
    EXPECT_LE(st.rejected_steps, 2);
    EXPECT_GT(mean, 0.5);  // accuracy-bound: the output interval's order, not the contact's
    EXPECT_LT(e, 1e-9);    // at rest: round-off only
    for (const double h : {0.25}) {
      RunStats sf;
      const auto fs = testing::run(fixed_rosenbrock(m, h), &sf);
      double ef = 0;
      for (const Sample& s : fs) ef = std::max(ef, std::abs(sink(m, s) - d) / d);
      std::cout << "[measured] resting sled, k " << k << ", fixed h " << h << " s: max sink error / sink " << ef
                << "\n";
      // Measured <= 5.6e-12; without the terms 3.1e3 (k 1e6), 4.9e10 (k 1e7).
      EXPECT_LT(ef, 1e-9);
    }
  }
}

// The sled landing: released 5 cm above the bottom (the chain falls with
// it), with the contact damping near critical for the sled (c = 2 sqrt(k 2r
// M) / 2r per metre, M = 1264 kg: a bottom tuned for a heavy body; the
// default 1e3 N s/m per m leaves it ringing at omega for seconds, which the
// steps then resolve for accuracy, with or without the terms). 30 s,
// tolerance 1e-5: it settles at W / (k 2r).
TEST(RosenbrockBodyContact, LandingSledSettlesAtWeightOverStiffness) {
  for (const double k : {1e5, 1e6, 1e7}) {
    Model m = sled_model(k, 0.05);
    m.seabed->damping = 2 * std::sqrt(k * 2 * kRadius * 1264.0) / (2 * kRadius);
    m.sim.duration = 30;
    m.sim.tolerance = 1e-5;
    RunStats st;
    const auto samples = testing::run(m, &st);
    const double d = sled_weight() / (k * 2 * kRadius), e = std::abs(sink(m, samples.back()) - d) / d;
    std::cout << "[measured] landing sled, k " << k << ": " << st.steps << " steps, " << st.rejected_steps
              << " rejected; final sink / (W/(k 2r)) - 1 = " << e << "\n";
    // Measured 93, 106, 115 steps (16, 15, 18 rejected: the impact) and the
    // final sink within 1e-11; without the terms 311, 806, 2334 steps (100,
    // 291, 895 rejected). Bound 200 steps: below the 311 of the softest
    // bottom without the terms; sink: settled at 30 s (decay time M / c l
    // below 0.1 s), bound 1e-6.
    EXPECT_LT(st.steps, 200);
    EXPECT_LT(e, 1e-6);
  }
}

// The sled dragged along the bottom (k = 1e6): the tow point (held, Motion
// mode) accelerates to 0.5 m/s along x over 10 s; the sled first sticks,
// then slides, lifting off and landing on its spring (stick-slip). 30 s,
// rosenbrock at fixed steps against RK4 at 1e-4 s (its own error: 1.4e-7 m
// against 2e-4 s), the sled's position and velocity every 0.5 s.
TEST(RosenbrockBodyContact, DraggedSledAgreesWithRk4) {
  const double k = 1e6;
  Model m = sled_model(k, -sled_weight() / (k * 2 * kRadius));
  m.tow.mode = Tow::Mode::Motion;
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 0.5, 10));
  m.sim.duration = 30;
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 1e-4;
  RunStats sr;
  const auto r = testing::run(ref, &sr);
  EXPECT_GT(r.back().bodies[0].pos.x(), 10.0);  // it slid
  double err[3] = {0, 0, 0};
  int i = 0;
  // Measured 5.6e-4, 4.2e-3, 1.7e-2 m (velocities 1.6e-3, 1.6e-2, 4.9e-2
  // m/s) over 11.8 m of travel; without the terms 0.05 s was off by 0.20 m
  // and 0.1, 0.2 s diverged within 1.2 s. Bounds: twice the measured.
  const double bound[3] = {1.2e-3, 8.4e-3, 3.4e-2};
  for (const double h : {0.05, 0.1, 0.2}) {
    RunStats st;
    const auto b = testing::run(fixed_rosenbrock(m, h), &st);
    ASSERT_EQ(b.size(), r.size());
    double e = 0, ev = 0;
    for (std::size_t j = 0; j < r.size(); ++j) {
      e = std::max(e, (r[j].bodies[0].pos - b[j].bodies[0].pos).norm());
      ev = std::max(ev, (r[j].bodies[0].vel - b[j].bodies[0].vel).norm());
    }
    std::cout << "[measured] dragged sled, 30 s: rosenbrock h = " << h << " s (" << st.steps << " steps; rk4 "
              << sr.steps << "): max body position difference " << e << " m, velocity " << ev << " m/s\n";
    EXPECT_LT(e, bound[i]);
    err[i++] = e;
  }
  // Converging: the error falls when h halves (measured 4.0x and 7.5x).
  EXPECT_GT(err[2], 2 * err[1]);
  EXPECT_GT(err[1], 2 * err[0]);
}

}  // namespace
}  // namespace towsim
