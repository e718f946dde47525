// W's time column f_t without the articulated inertias: the evaluation at
// the same state and a later time (forward_dynamics_time_shift,
// System::derivative_time_shift) against the full evaluation there, on every
// kind of part: cable and sphere in a turn, elastic cable, in-line body with
// attachments, imposed winch, waves over a sheared current.
//
// Exact equality (EXPECT_EQ) is the right assertion: the rigid elements'
// inertias (K, T, G T, Phi, H) are functions of the directions and lengths
// alone, so those taken over are bit for bit what the full evaluation
// computes, and everything else runs the same operations on the same
// values. Any difference, however small, is a time-dependent input taken as
// constant (a bug), not round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/tow/kinematics.hpp"
#include "towsim/waves/waves.hpp"

namespace towsim {
namespace {

struct Case {
  std::string name;
  Model m;
};

/// A sheared current (time enters the loads through waves only, but the
/// current makes the relative velocities, hence the loads, depend on r0, v0).
void add_current(Model& m) {
  m.fluid.current_depth = {0.0, 10.0, 50.0};
  m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.5, 0.1, 0), Vec3(0.1, -0.2, 0)};
}

std::vector<Case> cases() {
  std::vector<Case> out;
  testing::CableSpec spec;
  spec.n = 10;
  spec.length = 300;
  spec.mass_per_length = 0.14;
  spec.diameter = 0.010;
  spec.cd = 1.9;
  {  // paper-3d-turn: ramp then turn, the 3 kg sphere
    Model m = testing::cable_model(spec);
    testing::add_sphere_body(m);
    m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.57, 15));
    m.tow.pieces.push_back(testing::turn_piece(7.5, 15));
    out.push_back({"cable and sphere in a turn", m});
  }
  {  // elastic cable, sphere, on the ramp in a current
    Model m = testing::cable_model(spec);
    for (Element& el : m.cable.elements) el.axial_stiffness = 2e5, el.axial_damping = 1e3;
    testing::add_sphere_body(m);
    add_current(m);
    m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.push_back({"elastic cable", m});
  }
  {  // in-line body (every body load, a fin), end sphere, attachments
    Model m = testing::two_part_model();
    add_current(m);
    m.bodies.front().thrusters.push_back({Vec3(-0.8, 0.05, 0.02), Vec3::UnitX(), {0.0, 40.0}, {0.0, 50.0}});
    m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.push_back({"in-line body", m});
  }
  {  // imposed winch paying out: l_1 moves with time
    Model m = testing::cable_model(spec);
    testing::add_sphere_body(m);
    testing::impose_winch(m, spec.n, spec.length, {0.0}, {0.5});
    m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.push_back({"winch", m});
  }
  {  // irregular sea over a sheared current, the rich body at the end
    Model m = testing::cable_model(spec);
    add_current(m);
    m.fluid.waves = std::make_shared<const WaveField>(
        make_irregular_sea(3.0, 9.0, 3.3, 50, 5, Vec3(0.6, 0.8, 0), std::numeric_limits<double>::infinity(), 9.81));
    testing::add_rich_body(m);
    m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.push_back({"waves", m});
  }
  return out;
}

constexpr double kT = 20;     // the Jacobian point's time (on the turn) [s]
constexpr double kDt = 1e-4;  // the time shift: 1e-3 h at h = 0.1 s [s]
constexpr int kStates = 5;    // random states per case

/// Every result of an evaluation equal bit for bit (-0 == 0 aside).
void expect_same(const Accelerations& a, const Accelerations& b, const std::string& what) {
  SCOPED_TRACE(what);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.a0[i], b.a0[i]);
    EXPECT_EQ(a.tow_force[i], b.tow_force[i]);
    for (std::size_t k = 0; k < a.alpha.size(); ++k) EXPECT_EQ(a.alpha[k][i], b.alpha[k][i]) << "element " << k;
    for (std::size_t k = 0; k < a.joint_force.size(); ++k)
      EXPECT_EQ(a.joint_force[k][i], b.joint_force[k][i]) << "joint " << k;
    for (std::size_t q = 0; q < a.alpha_b.size(); ++q) {
      EXPECT_EQ(a.alpha_b[q][i], b.alpha_b[q][i]);
      EXPECT_EQ(a.link_force[q][i], b.link_force[q][i]);
      EXPECT_EQ(a.lower_link_force[q][i], b.lower_link_force[q][i]);
    }
  }
  for (std::size_t k = 0; k < a.length_acc.size(); ++k) EXPECT_EQ(a.length_acc[k], b.length_acc[k]);
  EXPECT_EQ(a.top_length_acc, b.top_length_acc);
}

/// s with the tow point (and an imposed winch's l_1, l_1') at time t.
PhysicalState at_time(const Model& m, PhysicalState s, double t) {
  const TowKinematics k = tow_kinematics(m.tow, t);
  s.r0 = k.pos, s.v0 = k.vel;
  if (m.winch.mode == Winch::Mode::Imposed) {
    const WinchKinematics w = winch_kinematics(m.winch, t);
    double fixed = m.winch.length_offset;  // deployed length but l_1 [m]
    for (std::size_t k = 1; k < m.cable.elements.size(); ++k) fixed += m.cable.elements[k].length;
    s.length[0] = w.length - fixed;
    s.length_rate[0] = w.rate;
  }
  return s;
}

TEST(TimeShift, DynamicsWithInertiasTakenOverEqualTheFullEvaluation) {
  std::mt19937 rng(11);
  for (const Case& c : cases()) {
    for (int r = 0; r < kStates; ++r) {
      const PhysicalState s = testing::random_state(c.m, rng);
      const PhysicalState s1 = at_time(c.m, s, kT), s2 = at_time(c.m, s, kT + kDt);
      Workspace w1(c.m), shifted(c.m), full(c.m);
      forward_dynamics(c.m, s1, kT, w1);
      const Accelerations before = w1.acc;
      forward_dynamics_time_shift(c.m, s2, kT + kDt, w1, shifted);
      forward_dynamics(c.m, s2, kT + kDt, full);
      expect_same(shifted.acc, full.acc, c.name);
      // In place (the inertias' workspace itself) the same.
      forward_dynamics_time_shift(c.m, s2, kT + kDt, w1, w1);
      expect_same(w1.acc, full.acc, c.name + ", in place");
      // Not vacuous: the tow force does move with time here.
      EXPECT_NE(before.tow_force, full.acc.tow_force) << c.name;
    }
  }
}

/// dy of two evaluations equal component by component.
void expect_same(const StateVector& a, const StateVector& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << what << ", component " << i;
}

TEST(TimeShift, SystemTimeShiftEqualsTheFullDerivative) {
  std::mt19937 rng(12);
  constexpr double kH = 0.1;  // the step [s]
  const StepWindow window{kT, kT + kH};
  for (const Case& c : cases()) {
    const auto sys = make_system(c.m), ref = make_system(c.m);
    const StateVector y = sys->initial(testing::random_state(c.m, rng), kT);
    const StateVector other = sys->initial(testing::random_state(c.m, rng), kT);
    StateVector f0, a, b;
    auto full = [&](const StateVector& x, double t) {
      ref->derivative(x, b, t, window);
      return b;
    };
    // A step's start: f0 and the Jacobian at y, then f_t's evaluation.
    sys->derivative(y, f0, kT, window);
    sys->prepare_stage_solve(kT, window);
    sys->derivative_time_shift(y, a, kT + kDt, window);
    expect_same(a, full(y, kT + kDt), c.name);
    // Stage and output evaluations in between leave the Jacobian's state.
    sys->derivative(other, f0, kT + 0.5 * kH, window);
    (void)sys->evaluate(other, kT);
    sys->derivative_time_shift(y, a, kT + kDt, window);
    expect_same(a, full(y, kT + kDt), c.name + ", after other evaluations");
    // Another state than the Jacobian's: recognised, evaluated in full.
    sys->derivative_time_shift(other, a, kT + kDt, window);
    expect_same(a, full(other, kT + kDt), c.name + ", another state");
    // Other directions only (the bodies' attitudes, rates, tow point kept).
    StateVector turned = y;
    std::copy(other.begin() + 6, other.begin() + 6 + 3 * c.m.cable.n(), turned.begin() + 6);
    sys->derivative_time_shift(turned, a, kT + kDt, window);
    expect_same(a, full(turned, kT + kDt), c.name + ", other directions");
    StateVector moved = y;
    moved[6] = std::nextafter(moved[6], 2.0);  // e_1 by one ulp
    sys->derivative_time_shift(moved, a, kT + kDt, window);
    expect_same(a, full(moved, kT + kDt), c.name + ", e_1 moved by one ulp");
  }
}

}  // namespace
}  // namespace towsim
