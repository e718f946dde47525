// The Rosenbrock-W stage solve of an elastic cable with a heavy body
// (docs/theory.md §6.3, "Elastic elements and seabed springs"; issue 13):
// the stage solve is (I - hg W)^-1 for ONE W, whatever hg; a steady tow takes
// the steps of the output interval like the inextensible cable; fixed large
// steps agree with RK4 at a fraction of its axial bound.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iostream>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "../support/rosenbrock.hpp"
#include "towsim/dynamics/elastic.hpp"

namespace towsim {
namespace {

using testing::stage_W;

/// bench/scenarios/km-turn-100-elastic.yaml in code: 1 km of cable in n
/// elements (EA [N]; 0: inextensible), the 1135 kg sphere (r 0.368 m, Cd
/// 0.77, link on top), towed at 6 kn (3.084 m/s) from the steady state.
Model km_model(int n, double EA) {
  testing::CableSpec c;
  c.n = n;
  c.length = 1000;
  c.mass_per_length = 1.12;
  c.diameter = 0.0173;
  c.cd = 1.5;
  c.tangential = 0.01;
  c.law = TangentialLaw::Skin;
  Model m = testing::cable_model(c);
  for (Element& el : m.cable.elements) el.axial_stiffness = EA;
  testing::add_sphere_body(m, 1135.0, 0.368, 0.77, 0.5);
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 3.084, 0));
  m.initial.kind = Initial::Kind::Steady;
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.time_step = 0.01;
  m.sim.output_interval = 1;
  return m;
}

// A W-method keeps its order with any W, but its stability (L-stability on
// the stiff modes) needs the stage solve to be (I - hg W)^-1 for one fixed W:
// the modified inertias M + hg C + hg^2 K and the right-hand side's loads
// -(hg C + hg^2 K) r_v - hg K r_x must use the same C and K. The elastic
// element's drag damping once entered its d-d block as C/3 (the rod mass's
// distribution) but the right-hand side as C/4 (the drag at G, velocity
// v + d'/2): W then changed with hg by 48 % of its largest entry here.
TEST(RosenbrockElasticBody, StageSolveIsOneWForEveryStep) {
  for (const double EA : {0.0, 1.27e7}) {
    const Model m = km_model(10, EA);
    auto sys = make_system(m);
    const StateVector y = sys->initial(initial_state(m), 0.0);
    StateVector f;
    sys->derivative(y, f, 0.0);
    sys->prepare_stage_solve(0.0, StepWindow{});
    const std::size_t N = y.size();
    // hg of a 1 s step (the output interval) and of a 10 ms one.
    const Eigen::MatrixXd W1 = stage_W(*sys, N, 0.436), W2 = stage_W(*sys, N, 0.00436);
    const double d = (W1 - W2).cwiseAbs().maxCoeff() / W1.cwiseAbs().maxCoeff();
    std::cout << "[measured] EA " << EA
              << " N, 10 elements + 1135 kg sphere: max |W(0.436) - W(0.00436)| / max |W| = " << d << "\n";
    // Measured 1.7e-12 (elastic) and 1.4e-14 (rigid): round-off of S^-1
    // divided by hg = 0.00436; the C/3 vs C/4 mismatch gave 0.48. Bound
    // 1e-6: far above round-off, far below any inconsistent term.
    EXPECT_LT(d, 1e-6);
  }
}

// Steady straight tow of the issue-13 case (1 km, 100 elements, EA 1.27e7 N,
// 1135 kg sled) for 100 s from the steady state at tolerance 1e-5, max_step
// 1 s = the output interval. The solution is constant in the tow's frame:
// the error estimate sits at the statics' residual and round-off, so the
// step grows to 1 s and stays there. Steps: 100 (one per second) plus the
// growth from the first step 0.01 s (x5 per step at most: 0.05, 0.25, 1.25
// -> 3 steps) plus the settling of the statics' residual; bound 120 for both
// cables (measured 103 and 103, no rejection). Before the fix the elastic cable took 1235 steps, 363 rejected
// (a rocking of the bottom elements and the body at the tolerance level, the
// W-method not damping it).
TEST(RosenbrockElasticBody, SteadyTowStepsAreBoundedByTheOutputInterval) {
  long steps[2] = {0, 0};
  int i = 0;
  for (const double EA : {0.0, 1.27e7}) {
    Model m = km_model(100, EA);
    m.sim.duration = 100;
    m.sim.tolerance = 1e-5;
    m.sim.max_step = 1;  // given: the bound holds whether steps land on output times or not
    RunStats st;
    testing::run(m, &st);
    steps[i++] = st.steps;
    std::cout << "[measured] steady tow 100 s, 100 elements, EA " << EA << " N, rosenbrock tol 1e-5: " << st.steps
              << " steps, " << st.rejected_steps << " rejected, " << st.rhs_evaluations << " evaluations\n";
    EXPECT_LE(st.steps, 120);
    EXPECT_LE(st.rejected_steps, 5);
  }
  EXPECT_LE(steps[1], steps[0] + 10);  // the elastic cable as cheap as the rigid one
}

// Accuracy at fixed large steps: 1 km in 20 elastic elements of 50 m (EA
// 1.27e7 N: RK4 bound 0.8 L / c = 11.9 ms) with the sled, in steady tow, a
// 294.5 m turn from t = 5 s (the bench's), 40 s. Rosenbrock at fixed 0.25 s
// and 0.5 s (21x and 42x the RK4 bound) against RK4 at half its bound, the
// tow force and the body's position every second. Before the fix the run at
// 0.5 s diverged.
TEST(RosenbrockElasticBody, FixedLargeStepsAgreeWithRk4InATurn) {
  Model m = km_model(20, 1.27e7);
  m.tow.pieces.push_back(testing::turn_piece(294.5, 5.0));
  m.sim.duration = 40;
  const double hmax = rk4_axial_step_limit(m.cable.elements[0]);
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 0.5 * hmax;
  RunStats sr;
  const auto r = testing::run(ref, &sr);
  double Tmax = 0;
  for (const Sample& s : r) Tmax = std::max(Tmax, s.tow_force.norm());
  // The reference's own error: RK4 at a quarter of the bound.
  Model ref2 = ref;
  ref2.sim.time_step = 0.25 * hmax;
  const auto r2 = testing::run(ref2);
  ASSERT_EQ(r2.size(), r.size());
  double eref = 0;
  for (std::size_t i = 0; i < r.size(); ++i) eref = std::max(eref, (r[i].tow_force - r2[i].tow_force).norm() / Tmax);
  std::cout << "[measured] rk4 at 0.5 and 0.25 x the bound: max tow force difference / max T = " << eref << "\n";
  // Measured 9.6e-11: far below the 6.8e-7 of rosenbrock at 0.25 s, so the
  // reference does not blur the order below.
  EXPECT_LT(eref, 1e-7);
  double err[2] = {0, 0};
  int i = 0;
  // Measured 6.8e-7 and 5.9e-6 of the peak tow force, 1.2e-4 m and 7.9e-4 m
  // in the body's position; bounds 5e-5 and 5e-3 m (about 8x the 0.5 s
  // values, 20x tighter than the 1e-3 tow force accuracy of
  // test_rosenbrock.cpp).
  for (const double h : {0.25, 0.5}) {
    Model fx = m;
    fx.sim.tolerance = 1e10;  // fixed steps: every step accepted
    fx.sim.time_step = h;
    fx.sim.max_step = h;
    RunStats st;
    const auto b = testing::run(fx, &st);
    ASSERT_EQ(b.size(), r.size());
    double e = 0, ep = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      e = std::max(e, (r[i].tow_force - b[i].tow_force).norm() / Tmax);
      ep = std::max(ep, (r[i].bodies[0].pos - b[i].bodies[0].pos).norm());
    }
    std::cout << "[measured] elastic 1 km + sled, turn, 40 s: rosenbrock h = " << h << " s (" << st.steps
              << " steps; rk4 " << sr.steps << " at " << ref.sim.time_step
              << " s): max tow force difference / max T = " << e << ", body position difference " << ep << " m\n";
    EXPECT_LT(e, 5e-5);
    EXPECT_LT(ep, 5e-3);
    err[i++] = e;
  }
  // Order 3 (ROS34PW2): the error grows 8x when h doubles (measured 8.6);
  // between 5 and 13 is order 2.3 to 3.7.
  EXPECT_GT(err[1], 5 * err[0]);
  EXPECT_LT(err[1], 13 * err[0]);
}

}  // namespace
}  // namespace towsim
