// A body's equilibria and their static stability (BodyEquilibria): a
// pendulum, whose restoring stiffness is known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "../../src/sim/statics_internal.hpp"
#include "../support/models.hpp"
#include "towsim/sim/statics.hpp"

namespace {

using namespace towsim;
using namespace towsim::testing;

// A 3 kg sphere of radius r = 0.05 m hanging at rest from a link on its
// surface: its apparent weight W = (m - rho V) g acts at its centre, r from
// the link, so a rotation theta about a horizontal axis through the link
// turns it by W r sin(theta): stiffness W r about x and y hanging, -W r
// inverted (the link below the centre), and 0 about z (the link line).
class Pendulum : public ::testing::Test {
 protected:
  void SetUp() override {
    CableSpec c;
    c.n = 2;
    c.length = 10;
    model_ = cable_model(c);
    add_sphere_body(model_, kMass, kRadius);
    finalize_tow(model_.tow);
  }
  static constexpr double kMass = 3.0, kRadius = 0.05;
  double stiffness() const {
    const double volume = 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
    return (kMass - model_.fluid.rho * volume) * model_.fluid.g * kRadius;  // W r [N m/rad]
  }
  Model model_;
};

// Central differences of 1e-5 rad leave ~1e-10 of the moment scale
// (W r ~ 1.2 N m): 1e-7 N m/rad is well above that and far below W r.
constexpr double kStiffnessTol = 1e-7;

TEST_F(Pendulum, HangingIsStableInvertedIsNot) {
  const Vec3 Q(0, 0, -10), V = Vec3::Zero(), f2 = Vec3::Zero();
  const BodyEquilibrium hanging = classify_body_balance(model_, 0, Q, V, f2, Quat::Identity());
  EXPECT_TRUE(hanging.stable);
  EXPECT_NEAR(hanging.stiffness.x(), stiffness(), kStiffnessTol);
  EXPECT_NEAR(hanging.stiffness.y(), stiffness(), kStiffnessTol);
  EXPECT_NEAR(hanging.stiffness.z(), 0.0, kStiffnessTol);  // neutral: not unstable
  EXPECT_NEAR(hanging.min_stiffness, 0.0, kStiffnessTol);
  const Quat upside_down(Eigen::AngleAxisd(M_PI, Vec3::UnitY()));
  const BodyEquilibrium inverted = classify_body_balance(model_, 0, Q, V, f2, upside_down);
  EXPECT_FALSE(inverted.stable);
  EXPECT_NEAR(inverted.stiffness.x(), -stiffness(), kStiffnessTol);
  EXPECT_NEAR(inverted.stiffness.y(), -stiffness(), kStiffnessTol);
  EXPECT_NEAR(inverted.min_stiffness, -stiffness(), kStiffnessTol);
}

// Started upside down, the statics reports the stable (hanging) balance:
// Newton from the start reaches the inverted one, unstable, so the trims
// are tried and the stable balance among them is kept; it is the only one
// listed (the rotation about the link line is neutral: one balance).
TEST_F(Pendulum, StartedInvertedTheStaticsReportsTheHangingBalance) {
  model_.bodies[0].initial_attitude = Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitY()));
  const StaticsResult r = solve_statics(model_, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_EQ(r.equilibria.size(), 1u);
  const BodyEquilibria& eq = r.equilibria[0];
  ASSERT_TRUE(eq.analysed);
  ASSERT_EQ(eq.balances.size(), 1u);
  EXPECT_EQ(eq.chosen, 0);
  EXPECT_TRUE(eq.balances[0].stable);
  EXPECT_NEAR(eq.balances[0].stiffness.y(), stiffness(), kStiffnessTol);
  // Hanging: the link straight above the centre (1e-9: the solve's residual).
  const Vec3 up = r.state.bodies[0].q.toRotationMatrix() * Vec3::UnitZ();
  EXPECT_NEAR(up.z(), 1.0, 1e-9);
}

}  // namespace
