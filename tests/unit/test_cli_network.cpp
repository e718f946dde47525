// `towsim run` on networks: the files' columns, and the bridle's leg
// tensions against statics by hand (shared/MODEL.md §10).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "../support/cli.hpp"

namespace {

using towsim::testing::quoted;
using towsim::testing::read_csv;
using towsim::testing::run_towsim;
using towsim::testing::slurp;
using Cli = towsim::testing::TempDirTest;

// The bridle at rest (tests/support/bridle-at-rest.yaml): a 100 kg sphere
// of radius 0.2 m hung from a junction by two light legs (a = 2 m, hull
// points 2b = 2 m apart): each leg carries W / (2 cos(asin(b/a))), W the
// sphere's apparent weight. The legs weigh 2 g each: the tolerance 0.02 N
// is their weight in water.
const std::string kBridleAtRest = slurp(TOWSIM_SOURCE_DIR "/tests/support/bridle-at-rest.yaml");

/// Each leg's tension of the bridle at rest, W / (2 cos(asin(b/a))) [N],
/// and its tolerance, the legs' weight in water [N].
constexpr double kLegWeight = 0.02;
double bridle_leg_tension() {
  const double W = (100 - 1025 * 4.0 / 3 * std::numbers::pi * 0.008) * 9.81;  // the box's apparent weight [N]
  return W / (2 * std::cos(std::asin(0.5)));
}

TEST_F(Cli, BridleAtRestCarriesTheLegTensionsOfStatics) {
  const auto file = dir_ / "bridle.yaml";
  std::ofstream(file) << kBridleAtRest;
  const auto r = run_towsim("run " + quoted(file) + " -o " + quoted(dir_ / "out") + " -q");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto ts = read_csv(dir_ / "out" / "timeseries.csv");
  const double expected = bridle_leg_tension();
  for (const char* leg : {"leg_a_top_tension", "leg_b_top_tension"}) {
    const int c = ts.column(leg);
    ASSERT_GE(c, 0) << leg;
    EXPECT_NEAR(ts.rows.back()[static_cast<std::size_t>(c)], expected, kLegWeight) << leg;
  }
  // Every line, body and junction by name; nodes.csv with the line first.
  for (const char* col : {"main_top_force_z", "main_end_depth", "box_depth", "box_link_tension", "j_x", "j_depth"})
    EXPECT_GE(ts.column(col), 0) << col;
  EXPECT_EQ(slurp(dir_ / "out" / "nodes.csv").rfind("line,time,node,x,y,z", 0), 0u);
  const std::string summary = slurp(dir_ / "out" / "summary.json");
  EXPECT_NE(summary.find("\"max_leg_a_top_tension\""), std::string::npos);
  EXPECT_NE(summary.find("\"max_box_depth\""), std::string::npos);
}

// The same bridle's steady start (initial: steady, the tow at rest): the
// legs carry the statics' tensions from the first row on (the relaxation
// settles to 1e-6 m/s; the tolerance is the legs' weight, as above), and
// the run stays there.
TEST_F(Cli, BridleSteadyStartCarriesTheLegTensionsOfStatics) {
  const auto file = dir_ / "bridle.yaml";
  std::string text = kBridleAtRest;
  text.replace(text.find("initial: hanging"), 16, "initial: steady");
  text.replace(text.find("duration: 60"), 12, "duration: 5");
  std::ofstream(file) << text;
  const auto r = run_towsim("run " + quoted(file) + " -o " + quoted(dir_ / "out") + " -q");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto ts = read_csv(dir_ / "out" / "timeseries.csv");
  const double expected = bridle_leg_tension();
  for (const char* leg : {"leg_a_top_tension", "leg_b_top_tension"}) {
    const auto c = static_cast<std::size_t>(ts.column(leg));
    EXPECT_NEAR(ts.rows.front()[c], expected, kLegWeight) << leg;
    EXPECT_NEAR(ts.rows.back()[c], expected, kLegWeight) << leg;
  }
}

// `towsim statics` on the bridle at rest: the same leg tensions, printed
// and written (--out: a one-sample network run).
TEST_F(Cli, BridleStaticsCarriesTheLegTensionsOfStatics) {
  const auto file = dir_ / "bridle.yaml";
  std::ofstream(file) << kBridleAtRest;
  const auto r = run_towsim("statics " + quoted(file) + " --out " + quoted(dir_ / "out"));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.rfind("steady tow of bridle at V = (0 0 0) m/s, |V| = 0 m/s\n", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("    leg_a: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  junction j: depth "), std::string::npos) << r.out;
  const auto ts = read_csv(dir_ / "out" / "timeseries.csv");
  ASSERT_EQ(ts.rows.size(), 1u);
  const double expected = bridle_leg_tension();
  for (const char* leg : {"leg_a_top_tension", "leg_b_top_tension"})
    EXPECT_NEAR(ts.rows.front()[static_cast<std::size_t>(ts.column(leg))], expected, kLegWeight) << leg;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out" / "summary.json"));
  // What it does not take yet: refused, nothing written.
  const auto t = run_towsim("statics " + quoted(file) + " --trim box --out " + quoted(dir_ / "out2"));
  EXPECT_EQ(t.status, 2) << t.out;
  EXPECT_EQ(t.out, "towsim: statics: --trim takes a single line (cable:), not a network yet\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out2"));
}

// --target-depth on the bridle at rest: everything hangs straight down, so
// the box's origin is at L + sqrt(a^2 - b^2) + 0.2 m below the tow point (the
// main line's L, the legs' drop sqrt(3) m, the origin 0.2 m below the hull
// points): for 15 m, L = 15 - sqrt(3) - 0.2 = 13.0679 m. Checked to 2e-3 m:
// the search's 1 mm of depth plus the legs' sag under their own weight.
TEST_F(Cli, BridleTargetDepthIsTheHangingLength) {
  const auto file = dir_ / "bridle.yaml";
  std::ofstream(file) << kBridleAtRest;
  const auto r = run_towsim("statics " + quoted(file) + " --target-depth 15");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string head = "deployed length of line main for a depth of 15 m: ";
  ASSERT_EQ(r.out.rfind(head, 0), 0u) << r.out;
  const double L = std::stod(r.out.substr(head.size()));
  EXPECT_NEAR(L, 15 - std::sqrt(3.0) - 0.2, 2e-3) << r.out;
}

// Two spheres hung at rest from two tow points: --target-depth with --line
// varies that line only, for the deepest body below it. Each sphere's
// origin hangs 0.2 m below its line's end (its link point), so the length
// for 15 m is 14.8 m, checked to 2e-3 m (the search's 1 mm plus the cable's
// stretch-free sag: none at rest). Without --line, and with a wrong one,
// the exact refusals.
TEST_F(Cli, NetworkTargetDepthVariesTheChosenLine) {
  const std::filesystem::path file = TOWSIM_SOURCE_DIR "/tests/support/two-spheres-at-rest.yaml";
  const auto r = run_towsim("statics " + quoted(file) + " --target-depth 15 --line la");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string head = "deployed length of line la for a depth of 15 m: ";
  ASSERT_EQ(r.out.rfind(head, 0), 0u) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(head.size())), 14.8, 2e-3) << r.out;
  EXPECT_NE(r.out.find("(deepest body below it at 15 m;"), std::string::npos) << r.out;
  const auto none = run_towsim("statics " + quoted(file) + " --target-depth 15");
  EXPECT_EQ(none.status, 3);
  EXPECT_EQ(none.out,
            "towsim: statics: --target-depth 15: the network has more than one line from the vessel (choose the one "
            "whose length varies: --line NAME)\n");
  const auto wrong = run_towsim("statics " + quoted(file) + " --target-depth 15 --line lc");
  EXPECT_EQ(wrong.status, 2);
  EXPECT_EQ(wrong.out, "towsim: statics: --line lc: no such line (lines from the vessel: la, lb)\n");
}

// A network's steady tow over a bottom that is not flat is refused before
// anything is written: in the tow's frame a table of depths moves under it.
TEST_F(Cli, NetworkSteadyOverASlopedBottomIsRefused) {
  const auto file = dir_ / "sloped.yaml";
  std::ofstream(file) << R"(lines:
  - {name: main, from: vessel.top, to: free, length: 80, elements: 8, mass_per_length: 1.0, diameter: 0.02}
vessel:
  tow_points: {top: [0, 0, 0]}
environment:
  seabed: {depth: [[0, 50], [1000, 60]]}
tow: {motion: [{type: ramp, direction: [1, 0, 0], speed: 0.5, ramp_time: 0}]}
initial: steady
simulation: {duration: 10}
)";
  const auto r = run_towsim("run " + quoted(file) + " -o " + quoted(dir_ / "out"));
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out,
            "towsim: run: initial: steady: a network's steady tow over a seabed needs a flat bottom (depth: D; a "
            "table of depths moves under the tow; use hanging or {direction: [x, y, z]})\n");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "timeseries.csv"));
}

// Each of a network's bodies is warned about by its name: the two fish of
// examples/two-fish-booms.yaml start hanging with the tow under way, and
// each fish's tail plane stalls at t = 1 s (with the same text for both, the
// second was taken for a repeat of the first and dropped).
TEST_F(Cli, EachNetworkBodyIsWarnedAboutByName) {
  const auto r = run_towsim("run " + quoted(std::filesystem::path(TOWSIM_SOURCE_DIR) / "examples/two-fish-booms.yaml") +
                            " --set simulation.duration=2 -o " + quoted(dir_ / "out"));
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* fish : {"port_fish", "starboard_fish"})
    EXPECT_NE(r.out.find(std::string("towsim: warning: body ") + fish + "'s surface 0 stalled at t = 1 s"),
              std::string::npos)
        << fish << "\n"
        << r.out;
}

// A winch on a network's line runs: the line's pay-out speed in
// timeseries.csv, the joints' identities in nodes.csv (the winch adds
// joints at the top), the events counted in summary.json.
TEST_F(Cli, NetworkWinchPaysOutTheLine) {
  const auto file = dir_ / "winch.yaml";
  std::ofstream(file) << R"(lines:
  - {name: main, from: vessel.top, to: free, length: 10, elements: 5, mass_per_length: 1.0, diameter: 0.02,
     winch: {rate: 0.5}}
vessel:
  tow_points: {top: [0, 0, 0]}
tow: {motion: []}
simulation: {duration: 10}
)";
  const auto r = run_towsim("run " + quoted(file) + " -o " + quoted(dir_ / "out") + " -q");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto ts = read_csv(dir_ / "out" / "timeseries.csv");
  const int length = ts.column("main_deployed_length"), speed = ts.column("main_payout_speed");
  ASSERT_GE(length, 0);
  ASSERT_EQ(speed, length + 1);
  // 5 m paid out at 0.5 m/s over 10 s (1e-9 m: the schedule's sums).
  EXPECT_NEAR(ts.rows.back()[static_cast<std::size_t>(length)], 15.0, 1e-9);
  EXPECT_EQ(ts.rows.back()[static_cast<std::size_t>(speed)], 0.5);
  EXPECT_EQ(slurp(dir_ / "out" / "nodes.csv").rfind("line,time,node,node_id,x,y,z", 0), 0u);
  // Elements of 2 m split above 3 m: at 3, 5 and 7 m paid out at least.
  const std::string summary = slurp(dir_ / "out" / "summary.json");
  const auto at = summary.find("\"splits\": ");
  ASSERT_NE(at, std::string::npos) << summary;
  EXPECT_GE(std::stoi(summary.substr(at + 10)), 2) << summary;
}

}  // namespace
