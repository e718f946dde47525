// The depth-keeping controller: its law (depth_control_rates) by hand, its
// state in the default formulation's flat state, and the parsing of
// `depth_control` with exact error texts.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/scenario_files.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/model/depth_control.hpp"
#include "towsim/output/output.hpp"
#include "towsim/sim/simulate.hpp"

using towsim::ControlRates;
using towsim::ControlState;
using towsim::DepthControl;

namespace {
constexpr double kDeg = std::numbers::pi / 180;

DepthControl controller() {
  DepthControl c;
  c.target_depth = 120;
  c.kp = 0.02;   // rad/m
  c.ki = 0.001;  // rad/(m s)
  c.kd = 0.05;   // rad s/m
  c.max_deflection = 0.25;
  c.max_rate = 0.1;
  c.servo_time_constant = 0.5;
  c.tracking_time = 20;
  return c;
}
}  // namespace

// Inside every limit: u = kp e + ki I + kd de/dt, dI/dt = e, d delta/dt = (u - delta)/tau.
TEST(DepthControlLaw, LinearRegionByHand) {
  const DepthControl c = controller();
  const ControlRates r = depth_control_rates(c, ControlState{3.0, 0.01}, 121.0, -0.2);
  const double u = 0.02 * 1.0 + 0.001 * 3.0 + 0.05 * -0.2;  // = 0.013 rad
  EXPECT_DOUBLE_EQ(r.error, 1.0);
  EXPECT_DOUBLE_EQ(r.command, u);
  EXPECT_DOUBLE_EQ(r.dintegral, 1.0);
  EXPECT_DOUBLE_EQ(r.ddeflection, (u - 0.01) / 0.5);
}

// Saturated command: u_s at the limit, the integral pulled back by
// (u_s - u)/(ki T_t); the servo rate at its limit.
TEST(DepthControlLaw, SaturationAntiWindupAndRateLimit) {
  const DepthControl c = controller();
  const ControlRates r = depth_control_rates(c, ControlState{0.0, -0.2}, 100.0, 0.0);  // e = -20 m
  const double u = 0.02 * -20;                                                         // -0.4 rad, beyond -0.25
  EXPECT_DOUBLE_EQ(r.command, -0.25);
  EXPECT_DOUBLE_EQ(r.dintegral, -20 + (-0.25 - u) / (0.001 * 20));
  EXPECT_GT(r.dintegral, -20);            // anti-windup slows the integral's growth
  EXPECT_DOUBLE_EQ(r.ddeflection, -0.1);  // (-0.25 + 0.2)/0.5 = -0.1: at the limit exactly
  const ControlRates far = depth_control_rates(c, ControlState{0.0, 0.2}, 100.0, 0.0);
  EXPECT_DOUBLE_EQ(far.ddeflection, -0.1);  // (-0.45)/0.5 = -0.9, limited
  // The applied deflection never leaves the limits.
  EXPECT_DOUBLE_EQ(applied_deflection(c, ControlState{0, 0.3}), 0.25);
  EXPECT_DOUBLE_EQ(applied_deflection(c, ControlState{0, -0.3}), -0.25);
  EXPECT_DOUBLE_EQ(applied_deflection(c, ControlState{0, 0.1}), 0.1);
}

// Without an integral gain the integral is a plain integral of the error (no division by ki).
TEST(DepthControlLaw, NoIntegralGain) {
  DepthControl c = controller();
  c.ki = 0;
  const ControlRates r = depth_control_rates(c, ControlState{5.0, 0.0}, 100.0, 0.0);
  EXPECT_DOUBLE_EQ(r.dintegral, -20);
  EXPECT_DOUBLE_EQ(r.command, -0.25);
}

// ------------------------------------------------------------ parsing

namespace {
using ScenarioFile = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;

const std::string kBody = "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n  surfaces:\n";
}  // namespace

TEST_F(ScenarioFile, DepthControlParsesInDegrees) {
  const auto s = load(kCable + kSim + kBody +
                      "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 0, 1], area: 0.5,\n"
                      "       depth_control: {target_depth: 120, kp: 2, ki: 0.1, kd: -3, max_deflection_deg: 15,\n"
                      "                       max_rate_deg_s: 5, initial_deflection_deg: -2}}\n"
                      "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 1, 0], area: 0.5}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& b = s.model->bodies.at(0);
  ASSERT_TRUE(b.surfaces[0].depth_control.has_value());
  EXPECT_FALSE(b.surfaces[1].depth_control.has_value());
  EXPECT_EQ(towsim::control_count(b), 1);
  const DepthControl& c = *b.surfaces[0].depth_control;
  EXPECT_DOUBLE_EQ(c.target_depth, 120);
  EXPECT_NEAR(c.kp, 2 * kDeg, 1e-15);
  EXPECT_NEAR(c.ki, 0.1 * kDeg, 1e-15);
  EXPECT_NEAR(c.kd, -3 * kDeg, 1e-15);
  EXPECT_NEAR(c.max_deflection, 15 * kDeg, 1e-15);
  EXPECT_NEAR(c.max_rate, 5 * kDeg, 1e-15);
  EXPECT_NEAR(c.initial_deflection, -2 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(c.servo_time_constant, 0.1);
  EXPECT_DOUBLE_EQ(c.tracking_time, 20);  // |kp/ki|
  EXPECT_DOUBLE_EQ(c.settling_band, 0);
  // Its state: two components after the body's, starting at the initial deflection.
  auto sys = towsim::make_system(*s.model);
  const towsim::PhysicalState p = towsim::PhysicalState::hanging(*s.model);
  ASSERT_EQ(p.bodies[0].controls.size(), 1u);
  const towsim::StateVector y = sys->initial(p, 0);
  ASSERT_EQ(y.size(), 6u + 6 * 5 + 7 + 2);
  EXPECT_EQ(y[y.size() - 2], 0.0);
  EXPECT_NEAR(y.back(), -2 * kDeg, 1e-15);
  EXPECT_EQ(sys->describe(y.size() - 1), "depth controller 1");
  EXPECT_NEAR(sys->physical(y).bodies[0].controls[0].deflection, -2 * kDeg, 1e-15);
}

TEST_F(ScenarioFile, DepthControlErrors) {
  const auto s = load(kCable + kSim + kBody +
                      "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 0, 1], area: 0.5, deflection_deg: 3,\n"
                      "       depth_control: {target_depth: -1, max_deflection_deg: 95, max_rate_deg_s: 0,\n"
                      "                       servo_time_constant: 0, initial_deflection_deg: 100}}\n");
  EXPECT_EQ(s.diags.str(),
            at("14:23: body.surfaces.0.depth_control: give either deflection_deg or depth_control, not both") +
                at("14:23: body.surfaces.0.depth_control: needs a gain (kp, ki and kd are all 0)") +
                at("14:38: body.surfaces.0.depth_control.target_depth: must be >= 0 (got -1)") +
                at("14:62: body.surfaces.0.depth_control.max_deflection_deg: must be <= 90 (got 95)") +
                at("14:82: body.surfaces.0.depth_control.max_rate_deg_s: must be > 0 (got 0)") +
                at("15:45: body.surfaces.0.depth_control.servo_time_constant: must be > 0 (got 0)") +
                at("15:72: body.surfaces.0.depth_control.initial_deflection_deg: must be within "
                   "+-max_deflection_deg (got 100, limit 95)"));
}

TEST_F(ScenarioFile, DepthControlRequiredKeysAndUnknownKey) {
  const auto s = load(kCable + kSim + kBody +
                      "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 0, 1], area: 0.5,\n"
                      "       depth_control: {kp: 1, max_rate: 5}}\n");
  EXPECT_EQ(s.diags.str(),
            at("14:8: body.surfaces.0.depth_control.target_depth: missing required key") +
                at("14:8: body.surfaces.0.depth_control.max_deflection_deg: missing required key") +
                at("14:8: body.surfaces.0.depth_control.max_rate_deg_s: missing required key") +
                at("14:31: body.surfaces.0.depth_control.max_rate: unknown key (did you mean 'max_rate_deg_s'?)"));
}

TEST_F(ScenarioFile, DepthControlRefusedWithThePaperFormulationAndSlowRk4Servo) {
  const std::string surf =
      "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 0, 1], area: 0.5,\n"
      "       depth_control: {target_depth: 10, kp: 1, max_deflection_deg: 10, max_rate_deg_s: 5,"
      " servo_time_constant: 0.004}}\n";
  auto s = load(kCable + kSim + "  formulation: paper\n" + kBody + surf);
  EXPECT_EQ(
      s.diags.str(),
      at("8:16: simulation.formulation: the paper formulation has no depth controller (use formulation: default)"));
  s = load(kCable + kSim + "  integrator: rk4\n" + kBody + surf);
  EXPECT_EQ(s.diags.str(), at("15:113: body.surfaces.0.depth_control.servo_time_constant: must be >= "
                              "simulation.time_step / 2 with integrator rk4 (got 0.004 s, time step 0.01 s: the "
                              "servo would be unstable)"));
  s = load(kCable + kSim + "  integrator: dopri5\n" + kBody + surf);
  EXPECT_TRUE(s.ok()) << s.diags.str();  // an adaptive step resolves it
  s = load(kCable + kSim + kBody + surf);
  EXPECT_TRUE(s.ok()) << s.diags.str();  // so does the default integrator (rosenbrock)
}

// ------------------------------------------------------------ outputs

// Columns per controlled surface, named by body and surface index, after all
// others; summary.json's `depth_control` entry from the same samples.
TEST_F(ScenarioFile, DepthControlOutputs) {
  const auto s = load(kCable + kSim + kBody +
                          "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 1, 0], area: 0.5}\n"
                          "    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 0, 1], area: 0.5,\n"
                          "       depth_control: {target_depth: 101, kp: 2, max_deflection_deg: 10, max_rate_deg_s: 4,"
                          " settling_band: 0.5}}\n",
                      {"simulation.duration=0.5"});
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto cols = towsim::output::timeseries_columns(*s.model);
  ASSERT_GE(cols.size(), 3u);
  EXPECT_EQ(std::vector<std::string>(cols.end() - 3, cols.end()),
            (std::vector<std::string>{"body_surface1_deflection_deg", "body_surface1_deflection_rate_deg_s",
                                      "body_surface1_depth_error"}));
  towsim::output::RunRecord record(*s.model);
  const towsim::RunStats st = towsim::simulate(*s.model, record);
  ASSERT_EQ(st.status, "ok") << st.message;
  // Hanging at rest from z = 0 over 100 m: the body origin at 100 m, 1 m above the target.
  const auto& row = record.last_row();
  ASSERT_EQ(row.size(), cols.size());
  const double e = row[cols.size() - 1], defl = row[cols.size() - 3], rate = row[cols.size() - 2];
  EXPECT_LT(e, 0);
  EXPECT_GE(defl, -10);
  EXPECT_LE(std::abs(rate), 4);
  const auto j = towsim::output::make_summary(nlohmann::ordered_json::object(), "m", st, record, false);
  ASSERT_TRUE(j.contains("depth_control"));
  const auto& dc = j["depth_control"].at(0);
  EXPECT_EQ(dc["body"], "body");
  EXPECT_EQ(dc["surface"], 1);
  EXPECT_EQ(dc["target_depth"], 101.0);
  EXPECT_EQ(dc["settling_band"], 0.5);
  EXPECT_NEAR(dc["initial_error"].get<double>(), -1.0, 1e-9);
  EXPECT_TRUE(dc["settling_time"].is_null());  // 1 m off, band 0.5 m: not settled in 0.5 s
  EXPECT_NEAR(dc["max_abs_deflection_deg"]["value"].get<double>(), std::abs(defl), 1e-6);
  EXPECT_EQ(dc["max_abs_deflection_rate_deg_s"]["value"], 4.0);  // rate-limited from the start
}
