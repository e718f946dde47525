// Elastic cable keys (docs/scenario.md "Elastic cable"): axial_stiffness and
// axial_damping per section or at cable level, the refusals (paper
// formulation, an RK4 step the axial wave cannot take), and what a run of
// an elastic cable writes (strain column, summary.json `elastic`, warning).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/cli.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/dynamics/elastic.hpp"
#include "towsim/scenario/scenario.hpp"

namespace fs = std::filesystem;

namespace {

using ElasticKeys = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;

}  // namespace

// Axial damping that overdamps the highest axial mode shrinks the RK4 bound:
// 20 m elements, m' = 1.5 kg/m, EA = 1.27e7 N: c = 2909.75 m/s, omega =
// 2 sqrt(3) c / L = 503.98 rad/s; c_a = 1e5 N s: zeta = c_a/EA omega/2 = 1.984,
// fast root omega (zeta + sqrt(zeta^2 - 1)) = 1864 /s, h <= 2.7/1864 = 1.448 ms
// (the undamped 5.50 ms would let a 3 ms step through, with wrong forces).
TEST_F(ElasticKeys, OverdampedAxialModeShrinksTheRk4Bound) {
  const auto bad = load(kCable + "  axial_stiffness: 1.27e7\n  axial_damping: 1.0e5\n" + kSim +
                        "  time_step: 0.003\n  integrator: rk4\n");
  EXPECT_EQ(bad.diags.str(), at("6:20: cable.axial_stiffness: with integrator: rk4, the axial wave (speed 2910 "
                                "m/s over 20 m elements, axial damping 100000 N s) needs simulation.time_step <= "
                                "0.00144 s (it is 0.003 s); use integrator: rosenbrock (implicit in the axial "
                                "mode) or a smaller step"));
  EXPECT_TRUE(load(kCable + "  axial_stiffness: 1.27e7\n  axial_damping: 1.0e5\n" + kSim +
                   "  time_step: 0.0014\n  integrator: rk4\n")
                  .ok());
  // Light damping (zeta < 1) keeps the undamped bound.
  EXPECT_TRUE(load(kCable + "  axial_stiffness: 1.27e7\n  axial_damping: 2000\n" + kSim +
                   "  time_step: 0.005\n  integrator: rk4\n")
                  .ok());
  // The default integrator (rosenbrock) has no such bound.
  EXPECT_TRUE(
      load(kCable + "  axial_stiffness: 1.27e7\n  axial_damping: 1.0e5\n" + kSim + "  time_step: 0.003\n").ok());
}

TEST_F(ElasticKeys, CableLevelAndSectionValuesReachTheElements) {
  const auto s = load(kCable + "  axial_stiffness: 1.27e7\n  axial_damping: 2000\n" + kSim + "  integrator: dopri5\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  for (const auto& el : s.model->cable.elements) {
    EXPECT_EQ(el.axial_stiffness, 1.27e7);
    EXPECT_EQ(el.axial_damping, 2000);
  }
  const auto t = load(
      "cable:\n  mass_per_length: 1.5\n  diameter: 0.019\n  axial_stiffness: 1e7\n  sections:\n"
      "    - {length: 50, elements: 5}\n"
      "    - {length: 20, elements: 4, axial_stiffness: 2e6, axial_damping: 10}\n" +
      kSim + "  integrator: dopri5\n");
  ASSERT_TRUE(t.ok()) << t.diags.str();
  const auto& els = t.model->cable.elements;
  ASSERT_EQ(els.size(), 9u);
  EXPECT_EQ(els[0].axial_stiffness, 1e7);
  EXPECT_EQ(els[0].axial_damping, 0);
  EXPECT_EQ(els[8].axial_stiffness, 2e6);
  EXPECT_EQ(els[8].axial_damping, 10);
  // Absent: inextensible (the paper's model).
  const auto u = load(kCable + kSim);
  ASSERT_TRUE(u.ok());
  EXPECT_FALSE(towsim::is_elastic(u.model->cable.elements[0]));
}

TEST_F(ElasticKeys, RefusalsNameTheKeyAndTheFix) {
  const auto bad = load(kCable + "  axial_stiffness: -1\n  axial_damping: -2\n" + kSim);
  EXPECT_EQ(bad.diags.str(), at("6:20: cable.axial_stiffness: must be > 0 (got -1)") +
                                 at("7:18: cable.axial_damping: must be >= 0 (got -2)"));
  const auto paper = load(kCable + "  axial_stiffness: 1.27e7\n" + kSim + "  formulation: paper\n");
  EXPECT_EQ(paper.diags.str(), at("6:20: cable.axial_stiffness: the paper formulation has inextensible elements "
                                  "only: an elastic cable needs formulation: default"));
  // 20 m elements, c = sqrt(1.27e7 / 1.5) = 2909.75 m/s: h <= 0.8 L / c = 5.4987 ms,
  // written rounded down to 3 digits (a value that passes).
  const auto rk4 = load(kCable + "  axial_stiffness: 1.27e7\n" + kSim + "  integrator: rk4\n");
  EXPECT_EQ(rk4.diags.str(), at("6:20: cable.axial_stiffness: with integrator: rk4, the axial wave (speed 2910 "
                                "m/s over 20 m elements) needs simulation.time_step <= 0.00549 s (it is 0.01 s); "
                                "use integrator: rosenbrock (implicit in the axial mode) or a smaller step"));
  EXPECT_TRUE(load(kCable + "  axial_stiffness: 1.27e7\n" + kSim + "  time_step: 0.005\n  integrator: rk4\n").ok());
  EXPECT_TRUE(load(kCable + "  axial_stiffness: 1.27e7\n" + kSim).ok());  // the default, rosenbrock: no bound
}

TEST_F(ElasticKeys, RunReportsSlackStrainAndSnap) {
  const std::string scen = write(
      "cable:\n  length: 50\n  elements: 10\n  mass_per_length: 0.3\n  diameter: 0.012\n"
      "  axial_stiffness: 5e4\n  axial_damping: 50\n  attachments: [{at: 50, mass: 2}]\n"
      "simulation:\n  duration: 6\n  integrator: dopri5\n  tolerance: 1e-7\n  output_interval: 0.05\n"
      "tow:\n  motion:\n    - {type: heave, amplitude: 1.2, period: 3}\n");
  const fs::path out = dir_ / "out";
  const auto r = towsim::testing::run_towsim("run " + towsim::testing::quoted(scen) + " --out " +
                                             towsim::testing::quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("towsim: warning: the cable went slack "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("in compression"), std::string::npos) << r.out;  // that warning is for rigid elements
  const auto summary = nlohmann::json::parse(towsim::testing::slurp(out / "summary.json"));
  ASSERT_TRUE(summary.contains("elastic"));
  const auto& e = summary["elastic"];
  EXPECT_GT(e["slack_episodes"].get<long>(), 0);
  EXPECT_GT(e["slack_time"].get<double>(), 0.0);
  ASSERT_FALSE(e["slack"].empty());
  const auto& first = e["slack"][0];
  EXPECT_GT(first["duration"].get<double>(), 0.0);
  EXPECT_GE(first["elements"][0].get<int>(), 1);
  EXPECT_GT(e["max_element_tension"]["value"].get<double>(), 0.0);
  const auto lines = towsim::testing::lines_of(out / "nodes.csv");
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "time,node,x,y,z,vx,vy,vz,tension,axial_force,strain");
}
