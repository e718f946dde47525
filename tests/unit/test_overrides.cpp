// `--set KEY=VALUE`: an override replaces a key and its `_kn` twin, and an
// error that only the overrides cause points at the override.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "../support/cli.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/statics.hpp"

namespace {

using namespace towsim;
using namespace towsim::scenario;
using towsim::testing::CliResult;
using towsim::testing::run_towsim;

constexpr double kKnot = 1852.0 / 3600.0;  // [m/s]

const char* kTow = R"(name: twin
simulation: {duration: 1}
cable: {length: 100, elements: 5, mass_per_length: 1.5, diameter: 0.019}
environment: {current_kn: [0, 1, 0]}
tow:
  motion:
    - {type: ramp, direction: [1, 0, 0], speed_kn: 4, ramp_time: 0}
)";

LoadedScenario load(const std::string& text, const std::vector<std::string>& sets) {
  return load_scenario_text(text, "twin.yaml", "twin", "", sets);
}

TEST(Overrides, SpeedReplacesItsKnotsTwin) {
  const LoadedScenario sc = load(kTow, {"tow.motion.0.speed=2.5"});
  ASSERT_TRUE(sc.ok()) << sc.diags.str();
  // 2.5 m/s exactly (not the file's 4 kn): the override wins.
  EXPECT_EQ(final_tow_velocity(sc.model->tow).x(), 2.5);
  // The scenario as run (summary.json "scenario") has the override only.
  const auto ramp = to_json(sc.tree)["tow"]["motion"][0];
  EXPECT_EQ(ramp["speed"], 2.5);
  EXPECT_FALSE(ramp.contains("speed_kn")) << ramp.dump();
}

TEST(Overrides, KnotsReplaceTheirMetricTwin) {
  const std::string metric = R"(simulation: {duration: 1}
cable: {length: 100, elements: 5, mass_per_length: 1.5, diameter: 0.019}
environment: {current: [0, 0.5, 0]}
tow:
  motion:
    - {type: ramp, direction: [1, 0, 0], speed: 2, ramp_time: 0}
)";
  const LoadedScenario sc = load(metric, {"tow.motion.0.speed_kn=5", "environment.current_kn=[0, 2, 0]"});
  ASSERT_TRUE(sc.ok()) << sc.diags.str();
  EXPECT_DOUBLE_EQ(final_tow_velocity(sc.model->tow).x(), 5 * kKnot);  // one conversion's round-off
  const auto tree = to_json(sc.tree);
  EXPECT_FALSE(tree["tow"]["motion"][0].contains("speed"));
  EXPECT_FALSE(tree["environment"].contains("current")) << tree["environment"].dump();
  EXPECT_EQ(tree["environment"]["current_kn"], nlohmann::ordered_json::parse("[0, 2, 0]"));
}

TEST(Overrides, BothTwinsInTheFileAreStillRefused) {
  const std::string both = R"(simulation: {duration: 1}
cable: {length: 100, elements: 5, mass_per_length: 1.5, diameter: 0.019}
tow:
  motion:
    - {type: ramp, direction: [1, 0, 0], speed: 2, speed_kn: 4, ramp_time: 0}
)";
  const LoadedScenario sc = load(both, {"cable.elements=6"});
  EXPECT_EQ(sc.diags.str(), "twin.yaml:5:52: tow.motion.0.speed_kn: give either 'speed' or 'speed_kn', not both\n");
}

TEST(Overrides, AnErrorTheOverrideCausesPointsAtIt) {
  // A turn in the file needs speed; --set tow.motion.0.speed=0 takes it away.
  const CliResult r = run_towsim("check --example paper-3d-turn --set cable.elements=4 --set tow.motion.0.speed=0");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out,
            "--set:2:20: tow.motion.1: a turn needs a non-zero horizontal tow speed at its start time (got 0 m/s at "
            "t = 15 s) [caused by --set tow.motion.0.speed=0; see paper-3d-turn.yaml:33:7]\n");
}

TEST(Overrides, AnErrorOfTheFileStaysAtTheFile) {
  std::string bad = kTow;
  bad.replace(bad.find("duration: 1"), 11, "duration: -1");
  const LoadedScenario sc = load(bad, {"tow.motion.0.speed=2.5"});
  EXPECT_EQ(sc.diags.str(), "twin.yaml:2:24: simulation.duration: must be > 0 (got -1)\n");
}

TEST(Overrides, TheStaticsOfTheIssue) {
  // fish-depth-change gives speed_kn: 4; the override's 2.5 m/s is solved for.
  const CliResult r = run_towsim("statics --example fish-depth-change --set tow.motion.0.speed=2.5");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.rfind("steady tow at V = (2.5   0   0) m/s, |V| = 2.5 m/s\n", 0), 0U) << r.out;
}

}  // namespace
