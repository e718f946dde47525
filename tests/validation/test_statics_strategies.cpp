// The statics strategies one at a time (docs/theory.md §7 "Strategies and
// the driver"), each against a closed form, and the driver's plan for a
// cable with and without a seabed, elastic elements, bending, a winch.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../../src/sim/statics/strategies.hpp"
#include "../../src/sim/statics_internal.hpp"
#include "../support/models.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

using Strategies = std::vector<std::string>;

constexpr double kRho = 1025, kG = 9.81;  // the test models' water [kg/m^3] and gravity [m/s^2]

/// Apparent weight per metre of a test cable, from its own data [N/m].
double apparent_weight(const testing::CableSpec& c) {
  return (c.mass_per_length - kRho * std::numbers::pi / 4 * c.diameter * c.diameter) * kG;
}

/// A cable with normal drag only (no tangential drag, no Munk moment: Morison added mass).
testing::CableSpec drag_only_cable(int n, double length) {
  testing::CableSpec cs;
  cs.n = n;
  cs.length = length;
  cs.tangential = 0;
  cs.am = AddedMassModel::Morison;
  return cs;
}

/// The steady problem of m towed at V with rigid elements, as the driver builds it.
statics::SteadyProblem rigid_problem(const Model& m, const Vec3& V) {
  statics::SteadyProblem p(m, V);
  p.model = statics::rigid_copy(p.model);
  return p;
}

// ---------------------------------------------------------------------------
// Sweeps alone. A cable with normal drag only and a free end, towed at U,
// hangs straight at the critical angle phi below the horizontal where the
// drag balances the weight's normal part, w cos phi = q sin^2 phi with
// q = rho Cd d U^2 / 2: cos phi = (sqrt(w^2 + 4 q^2) - w) / (2 q). Every
// element's load then lies along it, so the top tension is the weight's
// part along the cable, w L sin phi.
// ---------------------------------------------------------------------------
TEST(StaticsStrategies, SweepsAloneHoldTheCableAtTheCriticalAngle) {
  const testing::CableSpec cs = drag_only_cable(10, 100);
  const Model m = testing::cable_model(cs);
  const double U = 2.0, w = apparent_weight(cs), q = 0.5 * kRho * cs.cd * cs.diameter * U * U;
  const double phi = std::acos((std::sqrt(w * w + 4 * q * q) - w) / (2 * q));  // [rad]
  statics::SteadyProblem p = rigid_problem(m, Vec3(U, 0, 0));
  ASSERT_EQ(statics::lay_start(p), statics::Start::Aligned);
  std::string why;
  const int sweeps = statics::solve_by_sweeps(p, nullptr, why);
  EXPECT_TRUE(why.empty()) << why;
  EXPECT_LE(sweeps, 2);  // uniform flow: the first sweep is the answer, the second moves no joint
  for (const Vec3& e : p.base.e) {
    EXPECT_NEAR(std::asin(-e.z()), phi, 1e-10);
    EXPECT_LT(e.x(), 0);  // trailing behind the tow
  }
  EXPECT_LT(p.max_alpha(p.residual(Eigen::VectorXd::Zero(p.size()))), 1e-9);
  const Vec3 top = p.ws.acc.tow_force;  // of the residual's evaluation
  EXPECT_NEAR(top.norm(), w * cs.length * std::sin(phi), 1e-9 * w * cs.length);
}

/// The start the sweeps leave out: the chain hanging straight down, towed at V.
statics::SteadyProblem hanging_problem(const Model& m, const Vec3& V) {
  statics::SteadyProblem p = rigid_problem(m, V);
  PhysicalState s = PhysicalState::hanging(p.model);
  s.r0 = p.model.tow.start;
  s.v0 = V;
  p.accept_state(s);
  return p;
}

// Newton on all angles alone, dense (Levenberg-Marquardt) and Newton-Krylov,
// from the chain hanging straight down: the same critical angle.
TEST(StaticsStrategies, NewtonOnAllAnglesAloneReachesTheCriticalAngle) {
  const testing::CableSpec cs = drag_only_cable(10, 100);
  const Model m = testing::cable_model(cs);
  const double U = 2.0, w = apparent_weight(cs), q = 0.5 * kRho * cs.cd * cs.diameter * U * U;
  const double phi = std::acos((std::sqrt(w * w + 4 * q * q) - w) / (2 * q));  // [rad]
  for (const bool dense : {true, false}) {
    statics::SteadyProblem p = hanging_problem(m, Vec3(U, 0, 0));
    Eigen::VectorXd r = p.residual(Eigen::VectorXd::Zero(p.size()));
    StaticsResult out;
    if (dense) {
      statics::Attempt a;
      a.dense = true;
      a.dense_iterations = statics::kMaxIterations;
      statics::levenberg_marquardt(p, a, statics::kFloor, nullptr, r, out);
    } else {
      EXPECT_FALSE(statics::newton_krylov(p, statics::kFloor, nullptr, out.iterations));  // no compression
    }
    EXPECT_GT(out.iterations, 0);
    EXPECT_LT(p.max_alpha(p.residual(Eigen::VectorXd::Zero(p.size()))), statics::kFloor) << (dense ? "dense" : "NK");
    for (const Vec3& e : p.base.e) EXPECT_NEAR(std::asin(-e.z()), phi, 1e-8) << (dense ? "dense" : "NK");
  }
}

// ---------------------------------------------------------------------------
// Relaxation alone. A chain at rest started 30 deg from the vertical swings
// down and, with kinetic damping, stops hanging straight down: every element
// vertical, the tow point carrying the chain's apparent weight w L.
// ---------------------------------------------------------------------------
TEST(StaticsStrategies, RelaxationAloneHangsAChainAtRest) {
  const testing::CableSpec cs = drag_only_cable(8, 40);
  const Model m = testing::cable_model(cs);
  statics::SteadyProblem p = rigid_problem(m, Vec3::Zero());
  PhysicalState s = PhysicalState::hanging(p.model);
  const double tilt = 30 * std::numbers::pi / 180;  // [rad]
  for (auto& e : s.e) e = Vec3(std::sin(tilt), 0, -std::cos(tilt));
  s.r0 = p.model.tow.start;
  s.v0 = Vec3::Zero();
  p.accept_state(s);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p.size());
  ASSERT_GT(p.max_alpha(p.residual(zero)), 1e-2);  // the start is far from balanced
  statics::relax(p, 1e-6, nullptr);
  EXPECT_LT(p.max_alpha(p.residual(zero)), 1e-6);
  const double W = apparent_weight(cs) * cs.length;  // [N]
  for (const Vec3& e : p.base.e) EXPECT_LT(std::hypot(e.x(), e.y()), 1e-5);
  EXPECT_NEAR(p.ws.acc.tow_force.z(), W, 1e-6 * W);
  EXPECT_NEAR(std::hypot(p.ws.acc.tow_force.x(), p.ws.acc.tow_force.y()), 0, 1e-5 * W);
}

// ---------------------------------------------------------------------------
// The dragged-cable start: a cable dragged along the bottom lies on it
// behind the tow, its suspended part descending to the touchdown.
// ---------------------------------------------------------------------------
TEST(StaticsStrategies, DraggedCableStartLiesOnTheBottomBehindTheTow) {
  const testing::CableSpec cs = drag_only_cable(30, 300);
  Model m = testing::cable_model(cs);
  const double depth = 110;  // [m]
  m.seabed = Seabed::flat(depth, 1e5, 1e3, 0.5);
  statics::SteadyProblem p = rigid_problem(m, Vec3(0.5, 0, 0));
  ASSERT_EQ(statics::lay_start(p), statics::Start::DraggedCable);
  compute_kinematics(p.model, p.base, p.ws);
  // The lying part: a tail of elements along the flat bottom, pointing away
  // from the tow; above it every element descends towards the touchdown.
  std::size_t lying = 0;
  while (lying < p.base.e.size() && p.base.e[p.base.e.size() - 1 - lying].z() == 0) ++lying;
  ASSERT_GE(lying, 1U);
  ASSERT_LT(lying, p.base.e.size());
  for (std::size_t k = p.base.e.size() - lying; k < p.base.e.size(); ++k) EXPECT_NEAR(p.base.e[k].x(), -1, 1e-12);
  for (std::size_t k = 0; k + lying < p.base.e.size(); ++k) EXPECT_LT(p.base.e[k].z(), 0);
  // The touchdown joint at or above the bottom (the bisection's bracket), nothing below it.
  const std::size_t touchdown = p.base.e.size() - lying;
  EXPECT_GE(p.ws.P[touchdown].z(), -depth);
  for (const Vec3& P : p.ws.P) EXPECT_GE(P.z(), -depth - 1e-9 * depth);
  EXPECT_LT(p.ws.P.back().x(), p.ws.P[touchdown].x());  // behind the touchdown
}

// ---------------------------------------------------------------------------
// The driver's plan (plan_statics), as docs/theory.md §7 lists it.
// ---------------------------------------------------------------------------
TEST(StaticsPlan, CableInOpenWaterIsSweptThenPolished) {
  const Model m = testing::cable_model(drag_only_cable(10, 100));
  const statics::StaticsPlan plan = statics::statics_plan(m, Vec3(2, 0, 0));
  ASSERT_EQ(plan.attempts.size(), 1U);
  EXPECT_EQ(plan.attempts[0].strategies(), (Strategies{"sweeps", "levenberg-marquardt"}));
  EXPECT_TRUE(plan.attempts[0].polish);
  EXPECT_EQ(plan.attempts[0].dense_iterations, statics::kMaxIterations);
  EXPECT_FALSE(plan.stretch);
}

TEST(StaticsPlan, ElasticCableIsStretchedAfterTheRigidSolve) {
  Model m = testing::cable_model(drag_only_cable(10, 100));
  for (Element& el : m.cable.elements) el.axial_stiffness = 1e7;
  const statics::StaticsPlan plan = statics::statics_plan(m, Vec3(2, 0, 0));
  ASSERT_EQ(plan.attempts.size(), 1U);
  EXPECT_EQ(plan.attempts[0].strategies(), (Strategies{"sweeps", "levenberg-marquardt"}));
  EXPECT_TRUE(plan.stretch);
  // The stretch's result: each element lengthened by its tension, l = L (1 + T / EA).
  const StaticsResult r = solve_statics(m, Vec3(2, 0, 0));
  ASSERT_TRUE(r.converged) << r.message;
  // T at mid-element: the mean of its joints' forces (to the variation of its own load along it).
  const double T = 0.5 * (r.joint_force[0].norm() + r.joint_force[1].norm()), L = m.cable.elements.front().length;
  EXPECT_GT(r.state.length.front(), L);
  EXPECT_NEAR(r.state.length.front(), L * (1 + T / 1e7), 1e-2 * L * T / 1e7);
}

TEST(StaticsPlan, LongCableBeyondTheDenseSolveIsSweptOnly) {
  Model m = testing::cable_model(drag_only_cable(700, 1400));
  EXPECT_EQ(statics::statics_plan(m, Vec3(2, 0, 0)).attempts[0].strategies(), (Strategies{"sweeps"}));
  // Bending springs couple the elements beyond what the sweeps balance: Newton-Krylov follows them.
  for (Element& el : m.cable.elements) el.bending_stiffness = 10;
  EXPECT_EQ(statics::statics_plan(m, Vec3(2, 0, 0)).attempts[0].strategies(), (Strategies{"sweeps", "newton-krylov"}));
}

TEST(StaticsPlan, CableAtRestOnTheBottomRelaxesWhenTheSweepsFail) {
  Model m = testing::cable_model(drag_only_cable(15, 150));
  m.seabed = Seabed::flat(100, 1e5, 1e3, 0.5);
  const statics::StaticsPlan plan = statics::statics_plan(m, Vec3::Zero());
  ASSERT_EQ(plan.attempts.size(), 2U);
  EXPECT_EQ(plan.attempts[0].strategies(), (Strategies{"sweeps", "levenberg-marquardt"}));
  EXPECT_EQ(plan.attempts[1].strategies(), (Strategies{"relaxation", "levenberg-marquardt"}));
  EXPECT_EQ(plan.attempts[1].relax_target, 1e-6);  // at rest: frictionless, to the floor
  EXPECT_TRUE(plan.attempts[1].dense_to_floor);
  EXPECT_EQ(plan.attempts[1].dense_iterations, statics::kMaxDenseOnlyIterations);
}

TEST(StaticsPlan, DraggedCableRelaxesFirst) {
  for (const int n : {30, 150}) {
    Model m = testing::cable_model(drag_only_cable(n, 300));
    m.seabed = Seabed::flat(110, 1e5, 1e3, 0.5);
    const statics::StaticsPlan plan = statics::statics_plan(m, Vec3(0.5, 0, 0));
    ASSERT_EQ(plan.attempts.size(), 1U);
    EXPECT_EQ(plan.attempts[0].relax_target, 1e-3);  // moving: the dense solve polishes
    // Above kPolishLimit unknowns Newton-Krylov goes before the dense solve.
    const Strategies expected = n == 30 ? Strategies{"relaxation", "levenberg-marquardt"}
                                        : Strategies{"relaxation", "newton-krylov", "levenberg-marquardt"};
    EXPECT_EQ(plan.attempts[0].strategies(), expected);
  }
}

TEST(StaticsPlan, WinchIsHeldAtTheCurrentLength) {
  Model m = testing::cable_model(drag_only_cable(10, 100));
  testing::impose_winch(m, 10, 100, {0.0, 10.0}, {1.0, 0.0});
  ASSERT_TRUE(m.winch.active());
  const Model held = statics::without_winch(m);
  EXPECT_FALSE(held.winch.active());
  EXPECT_EQ(statics::statics_plan(m, Vec3(2, 0, 0)).attempts[0].strategies(),
            statics::statics_plan(held, Vec3(2, 0, 0)).attempts[0].strategies());
  const StaticsResult with = solve_statics(m, Vec3(2, 0, 0)), without = solve_statics(held, Vec3(2, 0, 0));
  ASSERT_TRUE(with.converged) << with.message;
  EXPECT_EQ(with.tow_force, without.tow_force);  // the same solve
}

}  // namespace
}  // namespace towsim
