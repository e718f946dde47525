// winch: keys: exact error texts ("FILE:LINE:COL: KEY.PATH: problem") and
// what a valid winch compiles to (docs/scenario.md "winch").
#include <gtest/gtest.h>

#include <cmath>

#include "../support/scenario_files.hpp"
#include "towsim/dynamics/state.hpp"
#include "towsim/scenario/scenario.hpp"

namespace {

using WinchKeys = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;  // lines 6-7

}  // namespace

TEST_F(WinchKeys, NoModeAndUnknownKey) {
  const auto s = load(kCable + kSim + "winch:\n  max_sped: 2\n");
  EXPECT_EQ(s.diags.str(), at("9:3: winch.max_sped: unknown key (did you mean 'max_speed'?)") +
                               at("9:3: winch: give one of rate, length or tension"));
}

TEST_F(WinchKeys, TwoModes) {
  const auto s = load(kCable + kSim + "winch:\n  rate: 1\n  tension: 5000\n");
  EXPECT_EQ(s.diags.str(), at("10:12: winch.tension: give only one of rate, length or tension"));
}

TEST_F(WinchKeys, SpeedsOverLimits) {
  const auto s = load(kCable + kSim +
                      "winch:\n  rate: [[0, 0], [10, 2.5], [11, 0]]\n  max_speed: 2\n  max_acceleration: 0.5\n");
  EXPECT_EQ(s.diags.str(),
            at("9:18: winch.rate.1: pay-out speed 2.5 m/s exceeds winch.max_speed (2 m/s)") +
                at("9:29: winch.rate.2: pay-out acceleration -2.5 m/s^2 exceeds winch.max_acceleration (0.5 m/s^2)"));
}

TEST_F(WinchKeys, NonNumericRateSaysATableIsAcceptedToo) {
  const auto s = load(kCable + kSim + "winch:\n  rate: fast\n");
  EXPECT_EQ(s.diags.str(), at("9:9: winch.rate: expected a number or a table [[t, value], ...] (got 'fast')"));
  const auto kn = load(kCable + kSim + "winch:\n  rate_kn: {a: 1}\n");
  EXPECT_EQ(kn.diags.str(), at("9:12: winch.rate_kn: expected a number or a table [[t, value], ...] (got a mapping)"));
}

TEST_F(WinchKeys, LengthTableMustStartAtTheCableLength) {
  const auto s = load(kCable + kSim + "winch:\n  length: [[0, 90], [10, 120]]\n");
  EXPECT_EQ(s.diags.str(),
            at("9:11: winch.length: the length at t = 0 (90 m) must be the cable's deployed length (100 m)"));
}

TEST_F(WinchKeys, RefusedCombinations) {
  const auto s = load(kCable + kSim + "  formulation: paper\n" +
                      "tow:\n  mode: force\n  force: [0, 0, 10]\nwinch:\n  tension: 5000\n  split_at: 1.05\n");
  EXPECT_EQ(s.diags.str(),
            at("8:16: simulation.formulation: the paper formulation has a fixed cable length: winch: needs "
               "formulation: default") +
                at("13:12: winch.tension: a tension-controlled winch needs tow.mode: motion (tow.mode is force)") +
                at("14:13: winch.split_at: split_at (1.05) must be above 1 + remove_at (0.1) so that a split element "
                   "is not removed at once"));
}

// An elastic cable compiles: the winch pays out into its elastic top
// element. A rigid top section over an elastic one is refused (its l_1
// would be both the winch's length and a stretch state).
TEST_F(WinchKeys, ElasticCableCompiles) {
  const auto s = load(kCable + "  axial_stiffness: 1.0e7\n" + kSim + "  integrator: rosenbrock\nwinch:\n  rate: 1\n");
  ASSERT_EQ(s.diags.str(), "");
  ASSERT_TRUE(s.model.has_value());
  EXPECT_TRUE(towsim::elastic_winch(*s.model));
  const auto t = load(
      "cable:\n  mass_per_length: 1.5\n  diameter: 0.019\n  sections:\n"
      "    - {length: 50, elements: 5}\n"
      "    - {length: 20, elements: 4, axial_stiffness: 2e6}\n" +
      kSim + "  integrator: rosenbrock\nwinch:\n  rate: 1\n");
  EXPECT_EQ(t.diags.str(), at("11:3: winch: the top section must be elastic when another section is "
                              "(axial_stiffness at cable.sections.1.axial_stiffness)"));
}

// rk4: the top element at its shortest bounds the step; 10 elements of
// 10 m, EA 1e7, m' 1.5: c = 2582 m/s; paying out only, 0.5 L_e = 5 m
// after a split: 0.8 * 5 / c = 1.549e-3 s.
TEST_F(WinchKeys, ElasticCableRk4StepBound) {
  const std::string cable =
      "cable:\n  length: 100\n  elements: 10\n  mass_per_length: 1.5\n  diameter: 0.019\n"
      "  axial_stiffness: 1.0e7\n";
  const auto s = load(cable + kSim + "  integrator: rk4\n  time_step: 0.002\nwinch:\n  rate: 1\n");
  EXPECT_EQ(s.diags.str(), at("10:14: simulation.time_step: with integrator: rk4 and a winch on an elastic cable, "
                              "the top element shortens to 5 m (split_at, remove_at): its axial wave needs "
                              "simulation.time_step <= 0.00154 s; use integrator: rosenbrock or a smaller step"));
  const auto ok = load(cable + kSim + "  integrator: rk4\n  time_step: 0.0015\nwinch:\n  rate: 1\n");
  EXPECT_EQ(ok.diags.str(), "");
}

TEST_F(WinchKeys, ValidRateCompiles) {
  const auto s = load(kCable + kSim + "winch:\n  rate: [[0, 0], [10, 1], [20, 1], [30, 0]]\n  max_length: 120\n" +
                      "  rating: 1.0e4\n");
  ASSERT_EQ(s.diags.str(), "");
  ASSERT_TRUE(s.model.has_value());
  const towsim::Winch& w = s.model->winch;
  EXPECT_EQ(w.mode, towsim::Winch::Mode::Imposed);
  EXPECT_DOUBLE_EQ(w.nominal_length, 20);
  EXPECT_DOUBLE_EQ(w.min_length, 20);  // the top section's last element stays out
  // 5 m in the ramp up, 10 m at 1 m/s, then stopped at the drum's capacity 120 m (t = 25 s... ).
  EXPECT_DOUBLE_EQ(towsim::winch_kinematics(w, 10).length, 105);
  EXPECT_DOUBLE_EQ(towsim::winch_kinematics(w, 20).length, 115);
  EXPECT_NEAR(towsim::winch_kinematics(w, 100).length, 120, 1e-12);
  EXPECT_DOUBLE_EQ(towsim::winch_kinematics(w, 100).rate, 0);
}

// Speeds in knots (INTERFACE.md: any speed key as `<key>_kn`): the pay-out
// rate (a number or a table: its speeds converted, its times not) and
// max_speed; 1 kn = 1852/3600 m/s exactly. Both forms of one key: an error.
TEST_F(WinchKeys, SpeedsInKnots) {
  const double kn = 1852.0 / 3600.0;  // [m/s]
  const auto s = load(kCable + kSim + "winch:\n  rate_kn: [[0, 0], [10, 2], [20, 2], [30, 0]]\n  max_speed_kn: 3\n");
  ASSERT_EQ(s.diags.str(), "");
  ASSERT_TRUE(s.model.has_value());
  const towsim::Winch& w = s.model->winch;
  EXPECT_EQ(w.mode, towsim::Winch::Mode::Imposed);
  EXPECT_DOUBLE_EQ(w.max_speed, 3 * kn);
  EXPECT_DOUBLE_EQ(towsim::winch_kinematics(w, 15).rate, 2 * kn);
  EXPECT_NEAR(towsim::winch_kinematics(w, 40).length, 100 + 20 * 2 * kn, 1e-12);  // 5 + 10 + 5 s at full speed
  const auto c = load(kCable + kSim + "winch:\n  rate_kn: 1\n");
  ASSERT_EQ(c.diags.str(), "");
  EXPECT_DOUBLE_EQ(towsim::winch_kinematics(c.model->winch, 10).rate, kn);
  const auto both = load(kCable + kSim + "winch:\n  rate: 1\n  rate_kn: 2\n  max_speed: 2\n  max_speed_kn: 4\n");
  EXPECT_EQ(both.diags.str(), at("10:12: winch.rate_kn: give either 'rate' or 'rate_kn', not both") +
                                  at("12:3: winch.max_speed_kn: give either 'max_speed' or 'max_speed_kn', not both"));
  const auto over = load(kCable + kSim + "winch:\n  rate_kn: [[0, 0], [10, 5], [20, 0]]\n  max_speed_kn: 4\n");
  EXPECT_EQ(over.diags.str(),
            at("9:21: winch.rate_kn.1: pay-out speed 2.572222222 m/s exceeds winch.max_speed (2.057777778 m/s)"));
}

// The rate schedule's stops: paying out into max_length stops there (the
// speed drops to 0) and resumes as soon as the table's speed turns back;
// hauling in along a ramp through zero stops at min_length and resumes
// where the ramp crosses zero. Exact quadratic pieces (1e-12).
TEST(WinchSchedule, StopsAndResumes) {
  using towsim::schedule_from_rate;
  using towsim::Winch;
  Winch w;
  w.mode = Winch::Mode::Imposed;
  // +1 m/s until 100 s, then -1 m/s: from 100 m with a 150 m drum.
  w.schedule = schedule_from_rate({100, 100.001}, {1, -1}, 100, 10, 150);
  EXPECT_NEAR(towsim::winch_kinematics(w, 25).length, 125, 1e-12);
  EXPECT_NEAR(towsim::winch_kinematics(w, 50).length, 150, 1e-12);
  EXPECT_NEAR(towsim::winch_kinematics(w, 80).length, 150, 1e-12);
  EXPECT_EQ(towsim::winch_kinematics(w, 80).rate, 0);
  EXPECT_NEAR(towsim::winch_kinematics(w, 120.001).length, 150 - 0.00025 - 20, 1e-9);  // the ramp, then 20 s back
  // A ramp from -1 to +1 m/s over 0..20 s from 60 m with min_length 57 m:
  // L = 60 - t + t^2/20 reaches 57 at t = 10 - sqrt(40) = 3.675 s, stops,
  // resumes at t = 10 s (speed 0), then L = 57 + (t-10)^2/20.
  w.schedule = schedule_from_rate({0, 20}, {-1, 1}, 60, 57, 1e9);
  const double hit = 10 - std::sqrt(40.0);
  EXPECT_NEAR(towsim::winch_kinematics(w, hit - 1e-6).length, 57, 1e-5);
  EXPECT_NEAR(towsim::winch_kinematics(w, 8).length, 57, 1e-12);
  EXPECT_EQ(towsim::winch_kinematics(w, 8).rate, 0);
  EXPECT_NEAR(towsim::winch_kinematics(w, 16).length, 57 + 36.0 / 20, 1e-12);
  EXPECT_NEAR(towsim::winch_kinematics(w, 16).rate, 0.6, 1e-12);
  EXPECT_NEAR(towsim::winch_breakpoints(w).front(), hit, 1e-12);
}
