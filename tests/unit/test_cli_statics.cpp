// `towsim statics`: steady tow of the built-in examples from the command line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace towsim::testing;

/// Every row of a CSV file has the header's columns, each a finite number.
void expect_all_finite(const fs::path& file) {
  const Csv csv = read_csv(file);
  ASSERT_FALSE(csv.rows.empty()) << file;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    EXPECT_EQ(csv.rows[i].size(), csv.header.size()) << file << " row " << i + 1;
    for (std::size_t j = 0; j < csv.rows[i].size() && j < csv.header.size(); ++j)
      EXPECT_TRUE(std::isfinite(csv.rows[i][j])) << file << " row " << i + 1 << " column " << csv.header[j];
  }
}

class CliStatics : public ::testing::TestWithParam<std::string> {};

TEST_P(CliStatics, ConvergesAndWritesTheConfiguration) {
  const fs::path dir = fresh_dir("statics_" + GetParam()) / "out";
  const auto [status, out] = run_towsim("statics --example " + GetParam() + " --out " + quoted(dir));
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("converged: yes"), std::string::npos) << out;
  EXPECT_NE(out.find("tow force F_R = ("), std::string::npos) << out;
  // nodes.csv: header + one row per joint P_0..P_n.
  EXPECT_GE(lines_of(dir / "nodes.csv").size(), 1u + 2u);
  // The statics writer fills every column (axial_force was once NaN in every row).
  expect_all_finite(dir / "timeseries.csv");
  expect_all_finite(dir / "nodes.csv");
  fs::remove_all(dir.parent_path());
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, CliStatics,
                         ::testing::Values("paper-planar-a", "paper-planar-b", "paper-3d-turn", "cable-tow"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

TEST(CliStaticsErrors, ForceModeIsRefused) {
  const auto [status, out] = run_towsim("statics --example cable-tow --set tow.mode=force --set 'tow.force=[10,0,0]'");
  EXPECT_EQ(status, 2) << out;
  EXPECT_EQ(out,
            "--set:1:10: tow.mode: statics needs mode: motion (the steady speed comes from the tow law; got force)\n");
}

// A target depth out of reach says how far the search got (before: "no
// deployed length between 0.000000 and 0.000000 m reaches depth 0.010000 m"):
// paper-3d-turn's sphere hangs 0.05 m below its link point, so even with no
// cable it is deeper than 0.01 m. Exit 3, as any statics that finds nothing.
TEST(CliStaticsErrors, TargetDepthOutOfReachSaysWhy) {
  const auto [status, out] = run_towsim("statics --example paper-3d-turn --target-depth 0.01");
  EXPECT_EQ(status, 3) << out;
  EXPECT_NE(out.find("--target-depth 0.01: depth 0.01 m is shallower than this tow reaches: the body is at 0.04"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find(" m with 0 m deployed"), std::string::npos) << out;
}

// The statics output equals the first sample of a run started `initial:
// steady` from the same scenario: both come from one statics solve and one
// sample assembly. The tow is at its full speed from t = 0 (ramp_time 0), so
// the run's first state is the steady one with no tow acceleration.
using CliStaticsVsRun = TempDirTest;

TEST_F(CliStaticsVsRun, NodesEqualTheSteadyRunAtTimeZero) {
  const fs::path scen = dir_ / "steady.yaml";
  std::ofstream(scen) << "cable: {length: 100, elements: 8, mass_per_length: 1.5, diameter: 0.019}\n"
                         "body:\n  mass: 3\n  inertia: [0.003, 0.003, 0.003]\n  link_point: [0, 0, 0.05]\n"
                         "  spheres: [{center: [0, 0, 0], radius: 0.05}]\n"
                         "tow:\n  motion: [{type: ramp, direction: [1, 0, 0.2], speed: 2, ramp_time: 0}]\n"
                         "initial: steady\n"
                         "simulation: {duration: 0.1, output_interval: 0.1}\n";
  const auto st = run_towsim("statics " + quoted(scen) + " --out " + quoted(dir_ / "statics"));
  ASSERT_EQ(st.status, 0) << st.out;
  const auto rn = run_towsim("run " + quoted(scen) + " --out " + quoted(dir_ / "run") + " --quiet");
  ASSERT_EQ(rn.status, 0) << rn.out;
  expect_all_finite(dir_ / "statics" / "nodes.csv");
  expect_all_finite(dir_ / "statics" / "timeseries.csv");

  const Csv s = read_csv(dir_ / "statics" / "nodes.csv");
  const Csv r = read_csv(dir_ / "run" / "nodes.csv");
  ASSERT_EQ(s.header, r.header);
  ASSERT_EQ(s.rows.size(), 9u);  // joints P_0..P_8 at t = 0
  ASSERT_GE(r.rows.size(), s.rows.size());
  const int tension = s.column("tension"), axial = s.column("axial_force");
  ASSERT_GE(axial, 0);
  // The same solve and the same assembly, printed to 12 significant digits:
  // measured, the forces print identically and positions differ by 2e-12 m
  // (the run reads the tow law 1e-12 s inside its first step, at V = 2 m/s).
  // 1e-10 of each column's largest magnitude allows for that and for
  // printing round-off (5e-12 relative) alone.
  constexpr double kRelTol = 1e-10;
  for (std::size_t j = 0; j < s.header.size(); ++j) {
    double scale = 1;  // the column's largest magnitude (at least 1: time, node)
    for (const auto& row : s.rows) scale = std::max(scale, std::abs(row[j]));
    for (std::size_t i = 0; i < s.rows.size(); ++i)
      EXPECT_NEAR(s.rows[i][j], r.rows[i][j], kRelTol * scale) << "joint " << i << " column " << s.header[j];
  }
  // A taut cable at equilibrium: 0 < axial force <= tension (its projection).
  for (const auto& row : s.rows) {
    EXPECT_GT(row[axial], 0);
    EXPECT_LE(row[axial], row[tension] * (1 + kRelTol));
  }
}

}  // namespace

namespace {

// Issue 15: 100000 elements used to end in "internal error: std::bad_alloc"
// (a dense 200000 x 200000 Jacobian); the O(n) sweeps solve it (about 1 s).
TEST(CliStaticsLarge, HundredThousandElementsConverge) {
  const CliResult r = run_towsim("statics --example sea-state-tow --set cable.elements=100000");
  EXPECT_EQ(r.status, 0) << r.out.substr(0, 2000);
  EXPECT_NE(r.out.find("converged: yes"), std::string::npos) << r.out.substr(0, 2000);
  EXPECT_EQ(r.out.find("bad_alloc"), std::string::npos);
}

// A body at an extreme attitude is named with the time it happened.
TEST(CliRunWarnings, ExtremeAttitudeIsReported) {
  const fs::path dir = fresh_dir("attitude_warning") / "out";
  const CliResult r = run_towsim("run --example paper-3d-turn --out " + quoted(dir) +
                                 " --set simulation.duration=1 --set 'body.initial_attitude_deg=[0, 50, 0]'");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("towsim: warning: the body's pitch reached 50 deg at t = 0 s (beyond 30 deg"), std::string::npos)
      << r.out;
}

}  // namespace

// Angles balanced but tensions of infinity (once "converged: yes", status ok,
// exit 0 with inf in the CSVs): a numerical failure, exit 3.
TEST(CliStaticsErrors, InfiniteTensionIsAFailure) {
  const fs::path dir = fresh_dir("statics_infinite") / "out";
  const auto [status,
              out] = run_towsim("statics --example cable-tow --set cable.mass_per_length=1e200 --out " + quoted(dir));
  EXPECT_EQ(status, 3) << out;
  EXPECT_NE(out.find("converged: NO"), std::string::npos) << out;
  EXPECT_NE(out.find("towsim: statics: no finite equilibrium: the forces overflow double precision (check the "
                     "scenario's masses, sizes and speeds)\n"),
            std::string::npos)
      << out;
  std::ifstream in(dir / "summary.json");
  std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos) << summary;
  fs::remove_all(dir.parent_path());
}
