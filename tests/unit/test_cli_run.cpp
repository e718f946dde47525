// The built program (TOWSIM_BINARY): exit statuses, nothing written on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/cli.hpp"

namespace fs = std::filesystem;
using towsim::testing::CliResult;
using towsim::testing::quoted;
using towsim::testing::run_towsim;
using Cli = towsim::testing::TempDirTest;

TEST_F(Cli, BrokenFileExits2AndCreatesNothing) {
  const fs::path scen = dir_ / "bad.yaml";
  std::ofstream(scen) << "cable:\n  length: 100\n  elements: 0\n  mass_per_length: 1.5\n  diameter: -0.019\n"
                         "simulation:\n  duration: 1\n";
  const fs::path out = dir_ / "out";
  const CliResult r = run_towsim("run " + quoted(scen) + " --out " + quoted(out));
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(r.out, scen.string() + ":3:13: cable.elements: must be >= 1 (got 0)\n" + scen.string() +
                       ":5:13: cable.diameter: must be > 0 (got -0.019)\n");
}

TEST_F(Cli, BadSetExits2) {
  const fs::path out = dir_ / "out";
  const CliResult r = run_towsim("run --example cable-tow --set cable.elements=0 --out " + quoted(out));
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out, "--set:1:16: cable.elements: must be >= 1 (got 0)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, ExamplesListsTheBuiltInNames) {
  const CliResult r = run_towsim("examples");
  EXPECT_EQ(r.status, 0);
  for (const char* name : {"paper-planar-a", "paper-planar-b", "paper-3d-turn", "cable-tow"})
    EXPECT_NE(("\n" + r.out).find(std::string("\n") + name + " "), std::string::npos) << name << " in:\n" << r.out;
}

TEST_F(Cli, ExamplePrintsYamlAndUnknownNameFails) {
  const CliResult r = run_towsim("examples paper-3d-turn");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("name: paper-3d-turn"), std::string::npos);
  const CliResult bad = run_towsim("examples paper-3d");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("did you mean 'paper-3d-turn'?"), std::string::npos) << bad.out;
}

TEST_F(Cli, CheckPrintsDerivedQuantities) {
  const CliResult r = run_towsim("check --example paper-planar-a");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("element length              20 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("apparent weight in water"), std::string::npos);
}

TEST_F(Cli, CheckPrintsEachBreakingLoadInItsSectionsBlock) {
  const fs::path scen = dir_ / "sections.yaml";
  std::ofstream(scen) << "cable:\n  mass_per_length: 1.5\n  diameter: 0.019\n  normal_drag: 1.8\n  sections:\n"
                         "    - {length: 50, elements: 5, breaking_load: 1.0e5}\n"
                         "    - {length: 30, elements: 3, breaking_load: 2.0e4}\n"
                         "simulation:\n  duration: 1\n";
  const CliResult r = run_towsim("check " + quoted(scen));
  ASSERT_EQ(r.status, 0) << r.out;
  const std::size_t first = r.out.find("\nsection 0: 50 m in 5 elements");
  const std::size_t second = r.out.find("\nsection 1: 30 m in 3 elements");
  const std::size_t load0 = r.out.find("  breaking load               100000 N\n");
  const std::size_t load1 = r.out.find("  breaking load               20000 N\n");
  ASSERT_NE(first, std::string::npos) << r.out;
  ASSERT_NE(second, std::string::npos) << r.out;
  EXPECT_TRUE(first < load0 && load0 < second) << r.out;
  EXPECT_TRUE(second < load1 && load1 != std::string::npos) << r.out;
}

TEST_F(Cli, RunWritesTheThreeFiles) {
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim("run --example cable-tow --set simulation.duration=2 --out " + quoted(out) +
                                 " --quiet");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "");
  for (const char* f : {"timeseries.csv", "nodes.csv", "summary.json"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto lines = towsim::testing::lines_of(out / "timeseries.csv");
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0].rfind("time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z", 0), 0u);
}

TEST_F(Cli, Rk4StepNearItsStabilityLimitIsWarnedAbout) {
  // cable-tow: estimated rk4 limit ~0.21-0.22 s (docs/theory.md 6.4); 0.2 s
  // is above 0.9 times it (but stable: the warning is conservative). rk4
  // named: the example runs the default rosenbrock.
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim(
      "run --example cable-tow --set simulation.duration=20 --set simulation.time_step=0.2 "
      "--set simulation.integrator=rk4 --set simulation.write_nodes=false --out " +
      quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("towsim: warning: rk4 time_step 0.2 s is above 0.9 times the estimated stability limit"),
            std::string::npos)
      << r.out;
  const std::string summary = towsim::testing::slurp(out / "summary.json");
  EXPECT_NE(summary.find("\"integrator\": \"rk4\""), std::string::npos);
  EXPECT_NE(summary.find("\"warnings\": [\n    \"rk4 time_step 0.2 s is above"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("\"rk4_stability_limit\": null"), std::string::npos);
  EXPECT_NE(summary.find("\"integration_error_estimate\": null"), std::string::npos);
}

TEST_F(Cli, RosenbrockRunReportsItsErrorEstimate) {
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim(
      "run --example cable-tow --set simulation.duration=5 --set simulation.integrator=rosenbrock "
      "--set simulation.tolerance=1e-5 --set simulation.write_nodes=false --quiet --out " +
      quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string summary = towsim::testing::slurp(out / "summary.json");
  EXPECT_NE(summary.find("\"integrator\": \"rosenbrock\""), std::string::npos) << summary;
  EXPECT_EQ(summary.find("\"integration_error_estimate\": null"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"rk4_stability_limit\": null"), std::string::npos);
  EXPECT_NE(summary.find("\"warnings\": []"), std::string::npos);
}

// Without simulation.integrator: rosenbrock (tolerance 1e-4) with the default
// formulation, rk4 with the paper's; summary.json and towsim check say which.
TEST_F(Cli, DefaultIntegratorIsReportedBySummaryAndCheck) {
  const std::string base = "--example cable-tow --set simulation.duration=2 --set simulation.write_nodes=false ";
  const fs::path def = dir_ / "default", paper = dir_ / "paper";
  ASSERT_EQ(run_towsim("run " + base + "--quiet --out " + quoted(def)).status, 0);
  EXPECT_NE(towsim::testing::slurp(def / "summary.json").find("\"integrator\": \"rosenbrock\""), std::string::npos);
  ASSERT_EQ(run_towsim("run " + base + "--set simulation.formulation=paper --quiet --out " + quoted(paper)).status, 0);
  EXPECT_NE(towsim::testing::slurp(paper / "summary.json").find("\"integrator\": \"rk4\""), std::string::npos);
  const CliResult check = run_towsim("check " + base);
  EXPECT_EQ(check.status, 0) << check.out;
  EXPECT_NE(check.out.find("integrator                  rosenbrock, tolerance 0.0001, no max step\n"),
            std::string::npos)
      << check.out;
  EXPECT_NE(check.out.find("first step                  0.01 s\n"), std::string::npos) << check.out;
  const CliResult check_paper = run_towsim("check " + base + "--set simulation.formulation=paper");
  EXPECT_NE(check_paper.out.find("integrator                  rk4\n"), std::string::npos) << check_paper.out;
  EXPECT_NE(check_paper.out.find("time step                   0.01 s\n"), std::string::npos) << check_paper.out;
}

TEST_F(Cli, UsageErrorsExit2) {
  EXPECT_EQ(run_towsim("run --example cable-tow").status, 2);  // no --out
  EXPECT_EQ(run_towsim("").status, 2);                         // no subcommand
  EXPECT_EQ(run_towsim("check").status, 2);                    // no input
  EXPECT_EQ(run_towsim("--help").status, 0);
}

// A lifting surface beyond its stall angle is named with the first output
// time it is seen there, once, on stderr and in summary.json "warnings".
// Here the fish starts hanging at rest under a tow already at 4 kn: at t = 1 s
// its tail fin meets the flow at ~33 deg, beyond its 15 deg stall angle.
TEST_F(Cli, StalledSurfaceIsWarnedAboutWithItsTime) {
  const fs::path out = dir_ / "out";
  const CliResult r = run_towsim(
      "run --example fish-depth-change --set initial=hanging --set simulation.duration=5 "
      "--out " +
      quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string prefix = "towsim: warning: the body's surface 0 stalled at t = 1 s: angle of attack ";
  const auto at = r.out.find(prefix);
  ASSERT_NE(at, std::string::npos) << r.out;
  const double alpha = std::stod(r.out.substr(at + prefix.size()));
  EXPECT_GT(std::abs(alpha), 15.0);  // beyond the stall angle the message names
  EXPECT_EQ(r.out.find(prefix, at + 1), std::string::npos) << "warned once per surface";
  // The steady tow of the same example flies unstalled: no such warning.
  const CliResult ok = run_towsim("run --example fish-depth-change --set simulation.duration=5 --out " +
                                  quoted(dir_ / "ok"));
  ASSERT_EQ(ok.status, 0) << ok.out;
  EXPECT_EQ(ok.out.find("stalled"), std::string::npos) << ok.out;
}

// Above the mean water surface the water's loads still act (results there are
// not physical): the first output time the cable (below the tow point) or a
// body is above z = 0 is warned about, once per part, on stderr and in
// summary.json "warnings" (once a silent status ok).
TEST_F(Cli, CableOrBodyAboveTheSurfaceIsWarned) {
  const std::string tail =
      " rose above the water surface at t = 0 s (joint 1 at z = 980 m): the water's loads (buoyancy, drag, added "
      "mass) still act there, so results above z = 0 are not physical";
  const fs::path high = dir_ / "high";
  const CliResult r = run_towsim(
      "run --example cable-tow --set 'tow.start=[0,0,1000]' --set simulation.duration=0.2 --out " + quoted(high));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("towsim: warning: the cable" + tail + "\n"), std::string::npos) << r.out;
  EXPECT_NE(towsim::testing::slurp(high / "summary.json").find("\"the cable" + tail + "\""), std::string::npos);
  // A buoyant body (34 kg of water displaced, 2 kg) on 4 m of cable from a tow point 1 m deep floats up.
  const fs::path scen = dir_ / "float.yaml";
  std::ofstream(scen) << "cable: {length: 4, elements: 4, mass_per_length: 0.1, diameter: 0.01}\n"
                         "body:\n  mass: 2\n  inertia: [0.1, 0.1, 0.1]\n  link_point: [0, 0, 0]\n"
                         "  spheres: [{center: [0, 0, 0], radius: 0.2}]\n"
                         "tow: {start: [0, 0, -1]}\ninitial: {direction: [1, 0, 0.2]}\n"
                         "simulation: {duration: 3, output_interval: 0.5}\n";
  const CliResult f = run_towsim("run " + quoted(scen) + " --out " + quoted(dir_ / "float"));
  ASSERT_EQ(f.status, 0) << f.out;
  const std::string prefix = "towsim: warning: the body rose above the water surface at t = ";
  const auto at = f.out.find(prefix);
  ASSERT_NE(at, std::string::npos) << f.out;
  EXPECT_EQ(f.out.find(prefix, at + 1), std::string::npos) << "warned once";
  EXPECT_NE(f.out.find("towsim: warning: the cable rose above the water surface at t = "), std::string::npos);
}

// A loose tolerance passes large errors as "ok": above 1e-2 it is warned about.
TEST_F(Cli, LooseToleranceIsWarned) {
  const std::string w =
      "simulation.tolerance 0.1 is loose (above 0.01): the results may be far from converged; check them at a "
      "tolerance 10 times smaller";
  for (const char* integrator : {"dopri5", "rosenbrock"}) {
    const fs::path out = dir_ / integrator;
    const CliResult r = run_towsim("run --example cable-tow --set simulation.duration=1 --set simulation.integrator=" +
                                   std::string(integrator) + " --set simulation.tolerance=0.1 --out " + quoted(out));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("towsim: warning: " + w + "\n"), std::string::npos) << r.out;
    EXPECT_NE(towsim::testing::slurp(out / "summary.json").find("\"" + w + "\""), std::string::npos);
  }
  const CliResult tight = run_towsim(
      "run --example cable-tow --set simulation.duration=1 --set simulation.tolerance=0.01 --out " +
      quoted(dir_ / "tight"));
  EXPECT_EQ(tight.out.find("is loose"), std::string::npos) << tight.out;
}

// Above 1e-4 (the default) the time step's share of the tow force's error
// may pass 0.1 % of its peak (measured with rosenbrock on the shipped
// examples: up to 8.4e-4 at 1e-4, 2.8e-3 at 3e-4): warned about; 1e-4 is not.
TEST_F(Cli, ToleranceAbove01PercentIsWarned) {
  const std::string w =
      "simulation.tolerance 0.001 is above 0.0001: the time step's error of the tow force may pass 0.1 % of its peak "
      "(up to 9 times the tolerance on the shipped examples at 3e-4); 0.0001 (the default) or less keeps it within "
      "0.1 %";
  const fs::path out = dir_ / "above";
  const CliResult r = run_towsim(
      "run --example cable-tow --set simulation.duration=1 --set simulation.integrator=rosenbrock "
      "--set simulation.tolerance=1e-3 --out " +
      quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("towsim: warning: " + w + "\n"), std::string::npos) << r.out;
  EXPECT_NE(towsim::testing::slurp(out / "summary.json").find("\"" + w + "\""), std::string::npos);
  const CliResult ok = run_towsim(
      "run --example cable-tow --set simulation.duration=1 --set simulation.integrator=rosenbrock "
      "--set simulation.tolerance=1e-4 --out " +
      quoted(dir_ / "at"));
  EXPECT_EQ(ok.out.find("simulation.tolerance"), std::string::npos) << ok.out;
}

// The compression warning of a rigid cable is in summary.json "warnings" too
// (once on stderr only, unseen from Python and sweeps).
TEST_F(Cli, CompressionWarningIsInTheSummary) {
  const fs::path out = dir_ / "out";
  const CliResult r = run_towsim(
      "run --example paper-planar-b --set simulation.duration=20 --set simulation.write_nodes=false --out " +
      quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string w = "the cable was in compression (axial force ";
  const auto on_stderr = r.out.find("towsim: warning: " + w);
  ASSERT_NE(on_stderr, std::string::npos) << r.out;
  const std::string text = r.out.substr(on_stderr + 17, r.out.find('\n', on_stderr) - on_stderr - 17);
  EXPECT_NE(towsim::testing::slurp(out / "summary.json").find("\"" + text + "\""), std::string::npos) << text;
}
