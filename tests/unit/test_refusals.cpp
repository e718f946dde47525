// Refusals: one test per class of bad input, each asserting the exact
// messages ("FILE:LINE:COL: KEY.PATH: problem"). Classes already covered by
// test_io_parse.cpp (unknown top-level and cable keys, inertia triangle /
// symmetry, inline track order, CSV bad number, --set unknown key and
// syntax, duplicate key, YAML syntax, missing scenario file, force without
// force, surfaces orthogonality) are not repeated here. docs/reliability.md
// lists every class with its message.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/cli.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/scenario/scenario.hpp"

namespace fs = std::filesystem;
using towsim::scenario::load_scenario_file;
using towsim::scenario::LoadedScenario;

namespace {

using Refusal = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;
using towsim::testing::run_towsim;

const std::string kBody =  // lines 8-11
    "body:\n"
    "  mass: 3\n"
    "  inertia: [1, 1, 1]\n"
    "  link_point: [0, 0, 0]\n";

}  // namespace

// --- unknown keys and values: a "did you mean" hint at every level ---------

TEST_F(Refusal, UnknownKeyInListItemAndChoiceHaveHints) {
  const auto s = load(kCable + "  tangential_drag: {law: skn}\n" + kSim + kBody +
                      "  spheres:\n    - {center: [0, 0, 0], raduis: 0.1}\n"
                      "tow:\n  motion:\n    - {type: heave, amplitude: 1, periode: 10}\n");
  EXPECT_EQ(s.diags.str(),
            at("6:26: cable.tangential_drag.law: expected one of pode, skin, table (got 'skn'; did you mean 'skin'?)") +
                at("14:7: body.spheres.0.radius: missing required key") +
                at("14:27: body.spheres.0.raduis: unknown key (did you mean 'radius'?)") +
                at("17:7: tow.motion.0.period: missing required key") +
                at("17:35: tow.motion.0.periode: unknown key (did you mean 'period'?)"));
}

// --- wrong types ------------------------------------------------------------

TEST_F(Refusal, WrongTypes) {
  const auto s = load("environment:\n  current: [1, 0]\n" + kCable + "  normal_drag: [1, 2]\n" + kSim +
                      "  write_nodes: yes\n  integrator: [rk4]\n"
                      "body: [3]\n"
                      "initial: 12\n");
  EXPECT_EQ(s.diags.str(), at("2:12: environment.current: expected a list of 3 numbers (got a list of 2)") +
                               at("8:16: cable.normal_drag: expected a number (got a list of 2)") +
                               at("11:16: simulation.write_nodes: expected true or false (got 'yes')") +
                               at("12:15: simulation.integrator: expected a single value (got a list of 1)") +
                               at("13:7: body: expected a mapping of keys (got a list of 1)") +
                               at("14:10: initial: expected one of hanging, steady (got '12')"));
}

TEST_F(Refusal, RootNotAMappingOrEmpty) {
  const auto list = load("- cable\n- simulation\n");
  EXPECT_EQ(list.diags.str(), at("1:1: (root): expected a mapping of keys (got a list of 2)"));
  const auto empty = load("# nothing but a comment\n");
  EXPECT_EQ(empty.diags.str(), at("1:1: (root): the scenario is empty (expected cable:, simulation:, ...)"));
}

TEST_F(Refusal, ElementsMustBeAnInteger) {
  const auto s = load("cable:\n  length: 100\n  elements: 2.5\n  mass_per_length: 1.5\n  diameter: 0.019\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("3:13: cable.elements: expected an integer (got '2.5')"));
}

// --- missing required keys and values ---------------------------------------

TEST_F(Refusal, MissingRequiredBodyAndPieceKeys) {
  const auto s = load(kCable + kSim + "body:\n  center_of_gravity: [0, 0, 0]\n  mass:\n" +
                      "tow:\n  motion:\n    - {speed: 2}\n");
  EXPECT_EQ(s.diags.str(), at("8:1: body.inertia: missing required key") +
                               at("8:1: body.link_point: missing required key") + at("10:3: body.mass: missing value") +
                               at("13:7: tow.motion.0.type: missing required key") +
                               at("13:8: tow.motion.0.speed: unknown key (expected one of: type)"));
}

// --- non-positive lengths, diameters, masses; too many elements -------------

TEST_F(Refusal, CableLengthsAndMassesMustBePositive) {
  const auto s = load("cable:\n  length: 0\n  elements: -3\n  mass_per_length: 0\n  diameter: 0\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("2:11: cable.length: must be > 0 (got 0)") +
                               at("3:13: cable.elements: must be >= 1 (got -3)") +
                               at("4:20: cable.mass_per_length: must be > 0 (got 0)") +
                               at("5:13: cable.diameter: must be > 0 (got 0)"));
}

TEST_F(Refusal, TooManyElements) {
  const auto s = load("cable:\n  length: 100\n  elements: 1000000000000\n  mass_per_length: 1.5\n  diameter: 0.019\n" +
                      kSim);
  EXPECT_EQ(s.diags.str(), at("3:13: cable.elements: must be <= 100000 (got 1000000000000)"));
}

// An empty section list was a cable of no element (a crash in check, statics
// and run); length and elements beside sections were silently ignored.
TEST_F(Refusal, EmptySectionListAndSingleFormKeysBesideSections) {
  const auto empty = load("cable: {sections: [], mass_per_length: 1.5, diameter: 0.02}\nsimulation: {duration: 1}\n");
  EXPECT_EQ(empty.diags.str(),
            at("1:19: cable.sections: the list is empty (give at least one section, or leave sections out)"));
  const auto beside = load(
      "cable:\n  length: 100\n  elements: 5\n  mass_per_length: 1.5\n  diameter: 0.019\n  sections:\n"
      "    - {length: 60, elements: 6}\n" +
      kSim);
  EXPECT_EQ(beside.diags.str(),
            at("2:11: cable.length: not used with cable.sections (each section gives its own)") +
                at("3:13: cable.elements: not used with cable.sections (each section gives its own)"));
}

// A second YAML document was silently ignored (only the first one ran).
TEST_F(Refusal, SecondYamlDocument) {
  const auto s = load(kCable + kSim + "---\nfoo: 1\n");
  EXPECT_EQ(s.diags.str(), at("9:1: (yaml): a second YAML document (after ---): a scenario is one document"));
  const auto trailing = load(kCable + kSim + "---\n");  // an empty one after: nothing lost
  EXPECT_TRUE(trailing.ok()) << trailing.diags.str();
}

// A value starting with ',' before a flow collection: yaml-cpp's LoadAll
// looped for ever on it, allocating (the fuzzer's timeout), in a file and in
// a --set value alike.
TEST_F(Refusal, ValueStartingWithACommaBeforeAFlowCollection) {
  const auto file = load(", {\n");
  EXPECT_EQ(file.diags.str(), at("1:1: (yaml): YAML syntax error: unexpected ','"));
  const auto set = load(kCable + kSim, {"tow.force=, 4]\n- {\n[]"});
  EXPECT_EQ(set.diags.str(), "--set:1:11: tow.force: YAML syntax error: unexpected ','\n");
}

// Not a scenario file: a directory (once "the scenario is empty"), a device
// without end (once read until memory ran out), a file beyond 4 MiB.
TEST_F(Refusal, ScenarioPathNotARegularFileOrTooLarge) {
  const auto dir = load_scenario_file(dir_.string(), {});
  EXPECT_EQ(dir.diags.str(), dir_.string() + ":0:0: (file): is a directory, not a scenario file\n");
  const std::string too_large =
      ":0:0: (file): larger than 4 MiB (give long tables, such as tracks and vessel "
      "motions, as CSV files)\n";
  const auto zero = load_scenario_file("/dev/zero", {});
  EXPECT_EQ(zero.diags.str(), "/dev/zero" + too_large);
  const std::string big = write(kCable + kSim + "description: \"" + std::string(std::size_t{4} << 20, 'x') + "\"\n");
  EXPECT_EQ(load_scenario_file(big, {}).diags.str(), big + too_large);
}

// Valid numbers whose derived volume overflows: once "valid" in check.
TEST_F(Refusal, InfiniteDisplacedVolume) {
  const auto s = load(kCable + kSim + kBody + "  spheres: [{center: [0, 0, 0], radius: 1e200}]\n");
  EXPECT_EQ(s.diags.str(),
            at("9:3: body: the displaced volume is not finite (got inf m^3: the sizes overflow double precision)"));
}

// Control bytes quoted from a binary file are escaped, not sent to the terminal.
TEST_F(Refusal, ControlBytesInMessagesAreEscaped) {
  write("time,x,y,z\n0,0,0,0\n1,\x1b[31mred,0,0\n", "track.csv");
  const auto s = load(kCable + kSim + "tow:\n  motion:\n    - {type: track, file: track.csv}\n");
  EXPECT_EQ(s.diags.str(), in("track.csv", "3:3: tow.motion.0.file: expected a number (got '\\x1b[31mred')"));
}

TEST_F(Refusal, BodyMassesAndSizesMustBePositive) {
  const auto s = load(kCable + kSim +
                      "body:\n  mass: -3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n  volume: -1\n"
                      "  spheres:\n    - {center: [0, 0, 0], radius: 0}\n"
                      "  cylinders:\n    - {center: [0, 0, 0], axis: [1, 0, 0], length: -1, diameter: 0}\n"
                      "  surfaces:\n    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [0, 0, 1], area: 0}\n");
  EXPECT_EQ(s.diags.str(), at("9:9: body.mass: must be > 0 (got -3)") +
                               at("12:11: body.volume: must be >= 0 (got -1)") +
                               at("14:35: body.spheres.0.radius: must be > 0 (got 0)") +
                               at("16:52: body.cylinders.0.length: must be > 0 (got -1)") +
                               at("16:66: body.cylinders.0.diameter: must be > 0 (got 0)") +
                               at("18:70: body.surfaces.0.area: must be > 0 (got 0)"));
}

// --- negative density and coefficients --------------------------------------

TEST_F(Refusal, NegativeDensityGravityAndCoefficients) {
  const auto s = load("environment:\n  water_density: -1025\n  gravity: -9.81\n" + kCable +
                      "  normal_drag: -1.8\n  tangential_drag: {law: pode, f: -0.1}\n  added_mass: -1\n" + kSim +
                      "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
                      "  linear_damping: [1, 1, -1, 1, 1, 1]\n"
                      "  spheres:\n    - {center: [0, 0, 0], radius: 0.1, drag: -0.5, added_mass: -0.5}\n");
  EXPECT_EQ(s.diags.str(), at("2:18: environment.water_density: must be >= 0 (got -1025)") +
                               at("3:12: environment.gravity: must be >= 0 (got -9.81)") +
                               at("9:16: cable.normal_drag: must be >= 0 (got -1.8)") +
                               at("10:35: cable.tangential_drag.f: must be >= 0 (got -0.1)") +
                               at("11:15: cable.added_mass: must be >= 0 (got -1)") +
                               at("18:19: body.linear_damping: diagonal terms must be >= 0 (got -1 at row 2)") +
                               at("20:46: body.spheres.0.drag: must be >= 0 (got -0.5)") +
                               at("20:64: body.spheres.0.added_mass: must be >= 0 (got -0.5)"));
}

TEST_F(Refusal, CurrentDepthsMustBeNonNegativeAndIncreasing) {
  const auto s = load(
      "environment:\n  current:\n    - {depth: -1, velocity: [1, 0, 0]}\n"
      "    - {depth: 5, velocity: [1, 0, 0]}\n    - {depth: 5, velocity: [0, 0, 0]}\n" +
      kCable + kSim);
  EXPECT_EQ(s.diags.str(), at("3:15: environment.current.0.depth: depth must be >= 0 (got -1)") +
                               at("5:15: environment.current.2.depth: depths must be strictly increasing (got 5 "
                                  "after 5)"));
}

// --- impossible inertia tensors ----------------------------------------------

TEST_F(Refusal, InertiaZeroOrWrongShape) {
  const auto zero = load(kCable + kSim + "body:\n  mass: 3\n  inertia: [0, 0, 0]\n  link_point: [0, 0, 0]\n");
  EXPECT_EQ(zero.diags.str(), at("10:12: body.inertia: must be positive definite (principal moments 0, 0, 0)"));
  const auto two = load(kCable + kSim + "body:\n  mass: 3\n  inertia: [[1, 0, 0], [0, 1]]\n  link_point: [0, 0, 0]\n");
  EXPECT_EQ(two.diags.str(), at("10:12: body.inertia: expected a list of 3 numbers or 3 rows of 3 (got a list of 2)"));
  const auto row = load(kCable + kSim +
                        "body:\n  mass: 3\n  inertia: [[1, 0, 0], [0, 1, 0], [0, 0]]\n  link_point: [0, 0, 0]\n");
  EXPECT_EQ(row.diags.str(), at("10:35: body.inertia.2: expected a list of 3 numbers (got a list of 2)"));
}

// --- directions: zero, too large, non-unit (accepted, normalised) ------------

TEST_F(Refusal, ZeroDirections) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: ramp, direction: [0, 0, 0], speed: 2, ramp_time: 1}\n"
                      "initial: {direction: [0, 0, 0]}\n" +
                      "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
                      "  cylinders:\n    - {center: [0, 0, 0], axis: [0, 0, 0], length: 1, diameter: 0.1}\n"
                      "  surfaces:\n    - {center: [0, 0, 0], chord: [0, 0, 0], normal: [0, 0, 1], area: 1}\n");
  EXPECT_EQ(s.diags.str(), at("10:31: tow.motion.0.direction: must be a non-zero vector (got [0, 0, 0])") +
                               at("11:22: initial.direction: must be a non-zero vector (got [0, 0, 0])") +
                               at("17:33: body.cylinders.0.axis: must be a non-zero vector (got [0, 0, 0])") +
                               at("19:34: body.surfaces.0.chord: must be a non-zero vector (got [0, 0, 0])"));
}

TEST_F(Refusal, DirectionTooLargeToNormalise) {
  const auto s = load(kCable + kSim + "initial: {direction: [1e200, 0, -1e200]}\n");
  EXPECT_EQ(s.diags.str(), at("8:22: initial.direction: is too large to normalise (got [1e+200, 0, -1e+200])"));
}

TEST_F(Refusal, NonUnitDirectionsAreNormalised) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: ramp, direction: [3, 4, 0], speed: 2, ramp_time: 1}\n"
                      "initial: {direction: [0, 0, -5]}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_NEAR(std::get<towsim::Ramp>(s.model->tow.pieces.at(0)).direction.x(), 0.6, 1e-15);
  EXPECT_NEAR(std::get<towsim::Ramp>(s.model->tow.pieces.at(0)).direction.y(), 0.8, 1e-15);
  EXPECT_NEAR(s.model->initial.direction.z(), -1.0, 1e-15);
}

// --- tracks -------------------------------------------------------------------

TEST_F(Refusal, TrackFileMissing) {
  const auto s = load(kCable + kSim + "tow:\n  motion:\n    - {type: track, file: nothere.csv}\n");
  EXPECT_EQ(s.diags.str(),
            at("10:27: tow.motion.0.file: cannot open the track file '" + (dir_ / "nothere.csv").string() + "'"));
}

TEST_F(Refusal, TrackFileNotARegularFile) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: track, file: /dev/zero}\n    - {type: track, file: .}\n");
  EXPECT_EQ(s.diags.str(),
            at("10:27: tow.motion.0.file: the track file '/dev/zero' is not a regular file") +
                at("11:27: tow.motion.1.file: the track file '" + (dir_ / ".").string() + "' is not a regular file"));
}

TEST_F(Refusal, TrackFileWithoutEnoughRows) {
  write("time,x,y,z\n# no data\n", "empty.csv");
  write("time,x,y,z\n0,0,0,0\n", "one.csv");
  write("0,0,0,0\n1,1,0\n2,2,0,0,0\n", "ragged.csv");
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: track, file: empty.csv}\n    - {type: track, file: one.csv}\n"
                      "    - {type: track, file: ragged.csv}\n    - {type: track, points: [[0, 0, 0, 0], [1, 1]]}\n");
  EXPECT_EQ(s.diags.str(), at("11:27: tow.motion.1.file: a track needs at least 2 rows (got 1)") +
                               at("13:44: tow.motion.3.points.1: expected a list of 4 numbers (got a list of 2)") +
                               in("empty.csv", "2:1: tow.motion.0.file: the track file has no data rows") +
                               in("ragged.csv", "2:1: tow.motion.2.file: expected 4 values time,x,y,z (got 3)") +
                               in("ragged.csv", "3:1: tow.motion.2.file: expected 4 values time,x,y,z (got 5)"));
}

TEST_F(Refusal, TrackNeedsFileOrPoints) {
  const auto s = load(kCable + kSim + "tow:\n  motion:\n    - {type: track}\n");
  EXPECT_EQ(s.diags.str(), at("10:7: tow.motion.0: a track needs exactly one of 'file' or 'points'"));
}

// --- turns without horizontal speed -----------------------------------------

TEST_F(Refusal, TurnWithOnlyVerticalSpeed) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: heave, amplitude: 1, period: 10}\n"
                      "    - {type: turn, radius: 5, start_time: 2}\n");
  EXPECT_EQ(s.diags.str(), at("11:7: tow.motion.1: a turn needs a non-zero horizontal tow speed at its start time "
                              "(got 0 m/s at t = 2 s)"));
}

TEST_F(Refusal, TurnRadiusAndSide) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: ramp, direction: [1, 0, 0], speed: 2, ramp_time: 1}\n"
                      "    - {type: turn, radius: 0, side: left}\n");
  EXPECT_EQ(s.diags.str(), at("11:28: tow.motion.1.radius: must be > 0 (got 0)") +
                               at("11:37: tow.motion.1.side: expected one of port, starboard (got 'left')"));
}

// --- simulation settings -----------------------------------------------------

TEST_F(Refusal, StepsAndSamplesBeyondLimits) {
  const auto s = load(kCable + "simulation:\n  duration: 1e300\n  output_interval: 1e-300\n");
  EXPECT_EQ(s.diags.str(),
            at("7:13: simulation.time_step: too small for the duration (duration / time_step is above 1e+12; "
               "default 0.01)") +
                at("8:20: simulation.output_interval: too small for the duration (duration / output_interval is "
                   "above 1e+09)"));
}

// --- rules between sections (checked by compile, so `check` refuses too) ----

TEST_F(Refusal, SteadyStartNeedsAnImposedTowMotion) {
  const std::string kProblem =
      "initial: steady needs tow.mode: motion (the steady velocity comes from the tow's motion; tow.mode is force)";
  const auto s = load(kCable + kSim + "tow:\n  mode: force\n  force: [10, 0, 0]\n" + "initial: steady\n");
  EXPECT_EQ(s.diags.str(), at("11:10: " + kProblem));
  // The same rule reached through --set: reported at the override that
  // breaks it, naming it and where `initial` is written.
  const auto set = load(kCable + kSim + "initial: steady\n", {"tow.mode=force", "tow.force=[10, 0, 0]"});
  std::string initial_at = at("8:10");
  initial_at.pop_back();  // the line's '\n'
  EXPECT_EQ(set.diags.str(), "--set:1:10: " + kProblem + " [caused by --set tow.mode=force; see " + initial_at + "]\n");
  const auto set_initial = load(kCable + kSim + "tow: {mode: force, force: [1, 0, 0]}\n", {"initial=steady"});
  EXPECT_EQ(set_initial.diags.str(), "--set:1:9: " + kProblem + "\n");
  // Accepted: steady with an imposed motion, force mode with another start.
  EXPECT_TRUE(load(kCable + kSim + "initial: steady\n").ok());
  EXPECT_TRUE(load(kCable + kSim + "tow: {mode: force, force: [1, 0, 0]}\ninitial: hanging\n").ok());
}

// --- YAML-level limits -------------------------------------------------------

TEST_F(Refusal, AliasBombIsRefused) {
  std::string yaml = "a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (char c = 'b'; c <= 'g'; ++c) {
    const char p = static_cast<char>(c - 1);
    yaml += std::string(1, c) + ": &" + c + " [";
    for (int i = 0; i < 10; ++i) yaml += std::string(i ? ", *" : "*") + p;
    yaml += "]\n";
  }
  yaml += kCable + kSim;
  const auto s = load(yaml);  // 10^7 values through aliases; at most 1000 + 10 per character
  ASSERT_EQ(s.diags.size(), 1u) << s.diags.str();
  EXPECT_EQ(s.diags.list()[0].path, "(yaml)");
  EXPECT_EQ(s.diags.list()[0].message, "the document has more than " + std::to_string(1000 + 10 * yaml.size()) +
                                           " values (counting each use of an alias)");
}

TEST_F(Refusal, SelfReferringAliasIsRefused) {
  // `&c [*c]` makes a cyclic node (found by fuzzing: a stack overflow).
  const std::string yaml = "c: &c [*c, 1]\n" + kCable + kSim;
  const auto s = load(yaml);
  ASSERT_EQ(s.diags.size(), 1u) << s.diags.str();
  EXPECT_EQ(s.diags.list()[0].path, "(yaml)");
  EXPECT_EQ(s.diags.list()[0].message, "nested more than 64 levels deep (or an alias refers to itself)");
}

// --- --set: bad paths and values ---------------------------------------------

TEST_F(Refusal, SetBadPathsAndValues) {
  const auto s = load(kCable + kSim + kBody + "  spheres:\n    - {center: [0, 0, 0], radius: 0.1}\n",
                      {"body.spheres.5.radius=1", "=3", "cable..length=1", "cable.elements=[1, 2",
                       "simulation.duration=ten", "body.spheres.x=1", "cable.elements=3=4",
                       "body.spheres.1={center: [0, 0, 0]}"});
  EXPECT_EQ(s.diags.str(),
            "--set:1:1: body.spheres.5: no list item 5 (the list has 1 item; an index equal to that adds one)\n"
            "--set:2:1: (key): expected KEY=VALUE (e.g. cable.elements=40)\n"
            "--set:3:1: cable..length: empty component in the key path\n"
            "--set:4:16: cable.elements: YAML syntax error: end of sequence flow not found\n"
            "--set:5:21: simulation.duration: expected a number (got 'ten')\n"
            "--set:6:1: body.spheres.x: no list item x (the list has 1 item; an index equal to that adds one)\n"
            "--set:7:16: cable.elements: expected an integer (got '3=4')\n"
            "--set:8:16: body.spheres.1.radius: missing required key\n");
}

// --- several errors at once, across files, in order --------------------------

TEST_F(Refusal, SeveralErrorsAcrossFilesInOrder) {
  write("time,x,y,z\n0,0,0,0\n1,1,0,0\n1,2,0,0\n", "track.csv");
  const auto s = load("cable:\n  length: 100\n  elements: 0\n  mass_per_length: 1.5\n  diameter: 0.019\n" + kSim +
                          "tow:\n  motion:\n    - {type: track, file: track.csv}\n"
                          "body:\n  mass: 3\n  inertia: [1, 2, 4]\n  link_point: [0, 0, 0]\n",
                      {"simulation.time_step=-1", "body.mass=0"});
  EXPECT_EQ(s.diags.str(),
            at("3:13: cable.elements: must be >= 1 (got 0)") +
                at("13:12: body.inertia: principal moments must satisfy the triangle inequality (got 1, 2, 4: 4 > 1 "
                   "+ 2)") +
                in("track.csv", "4:1: tow.motion.0.file: times must be strictly increasing (got 1 after 1)") +
                "--set:1:22: simulation.time_step: must be > 0 (got -1)\n"
                "--set:2:11: body.mass: must be > 0 (got 0)\n");
}

// --- the program: every class exits 2 and writes nothing ---------------------

TEST_F(Refusal, ProgramExits2AndWritesNothingForEachClass) {
  const std::vector<std::string> bad = {
      kCable + kSim + "colour: red\n",                                                                 // unknown key
      "cable: 3\n" + kSim,                                                                             // wrong type
      kSim,                                                                                            // missing key
      "cable:\n  length: -1\n  elements: 5\n  mass_per_length: 1.5\n  diameter: 0.019\n" + kSim,       // range
      kCable + kSim + "body:\n  mass: 3\n  inertia: [1, 1, 5]\n  link_point: [0, 0, 0]\n",             // inertia
      kCable + kSim + "initial: {direction: [0, 0, 0]}\n",                                             // zero direction
      kCable + kSim + "tow:\n  motion:\n    - {type: track, points: [[1, 0, 0, 0], [0, 1, 0, 0]]}\n",  // track
      kCable + kSim + "tow:\n  motion:\n    - {type: track, file: none.csv}\n",                        // track file
      kCable + kSim + "tow:\n  motion:\n    - {type: turn, radius: 5}\n",                              // turn speed
      "cable: [1, 2\n",                                                                                // YAML syntax
      kCable + kSim + "tow: {mode: force, force: [1, 0, 0]}\ninitial: steady\n",  // between sections
      "cable: {sections: [], mass_per_length: 1.5, diameter: 0.02}\n" + kSim,     // no section
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const std::string scen = write(bad[i], "bad" + std::to_string(i) + ".yaml");
    const fs::path out = dir_ / ("out" + std::to_string(i));
    const auto [status, text] = run_towsim("run '" + scen + "' --out '" + out.string() + "'");
    EXPECT_EQ(status, 2) << bad[i] << text;
    EXPECT_EQ(text.rfind(scen + ":", 0), 0u) << text;
    EXPECT_FALSE(fs::exists(out)) << bad[i];
    // `check` applies the same rules: what fails a run fails the check.
    const auto [check_status, check_text] = run_towsim("check '" + scen + "'");
    EXPECT_EQ(check_status, 2) << bad[i] << check_text;
    EXPECT_EQ(check_text, text) << bad[i];
  }
  const fs::path out = dir_ / "out-set";
  const auto [status, text] = run_towsim("run --example cable-tow --set cable.elemnts=3 --out '" + out.string() + "'");
  EXPECT_EQ(status, 2);
  EXPECT_EQ(text, "--set:1:1: cable.elemnts: unknown key (did you mean 'elements'?)\n");
  EXPECT_FALSE(fs::exists(out));
}

// An empty section list crashed statics and sweep too (exit 139): both exit 2
// with the message and write nothing, whether the base scenario or a case's
// override empties the list (a sweep's case: at the sweep file).
TEST_F(Refusal, EmptySectionListIsRefusedByStaticsAndSweep) {
  const std::string scen = write("cable: {sections: [], mass_per_length: 1.5, diameter: 0.02}\n" + kSim, "se.yaml");
  const std::string message =
      ":1:19: cable.sections: the list is empty (give at least one section, or leave sections "
      "out)\n";
  const fs::path out = dir_ / "out";
  const auto [status, text] = run_towsim("statics '" + scen + "' --out '" + out.string() + "'");
  EXPECT_EQ(status, 2) << text;
  EXPECT_EQ(text, scen + message);
  const std::string sweep = write("scenario: se.yaml\ngrid: {simulation.duration: [1, 2]}\n", "sweep.yaml");
  const auto [sweep_status, sweep_text] = run_towsim("sweep '" + sweep + "' --out '" + out.string() + "' --quiet");
  EXPECT_EQ(sweep_status, 2) << sweep_text;
  EXPECT_EQ(sweep_text, scen + message);
  const std::string by_case =
      write("example: two-part-tow\ncases:\n  - {cable.sections: []}\n  - {simulation.duration: 0.5}\n", "case.yaml");
  const auto [case_status, case_text] = run_towsim("sweep '" + by_case + "' --out '" + out.string() + "' --quiet");
  EXPECT_EQ(case_status, 2) << case_text;
  EXPECT_EQ(case_text, by_case +
                           ":3:22: cable.sections: the list is empty (give at least one section, or leave sections "
                           "out)\n");
  EXPECT_FALSE(fs::exists(out));
}

// Not a refusal: text in another encoding is kept, and the run still writes
// its summary (invalid UTF-8 becomes U+FFFD in summary.json).
TEST_F(Refusal, NonUtf8NameStillWritesTheSummary) {
  const std::string scen = write("name: \"caf\xe9\"\n" + kCable + "simulation:\n  duration: 0.2\n");
  const fs::path out = dir_ / "out";
  const auto [status, text] = run_towsim("run '" + scen + "' --out '" + out.string() + "' --quiet");
  ASSERT_EQ(status, 0) << text;
  std::ifstream in(out / "summary.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["model"], "caf\xef\xbf\xbd");
  EXPECT_EQ(j["status"], "ok");
}
