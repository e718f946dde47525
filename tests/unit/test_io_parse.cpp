// Scenario parsing and validation: exact error texts (FILE:LINE:COL: PATH: problem).
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>

#include <filesystem>
#include <fstream>
#include <string>

#include "../support/scenario_files.hpp"
#include "towsim/scenario/scenario.hpp"

namespace fs = std::filesystem;
using towsim::scenario::load_scenario_file;
using towsim::scenario::LoadedScenario;

namespace {

using ScenarioFile = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;

}  // namespace

TEST_F(ScenarioFile, MinimalScenarioCompiles) {
  const auto s = load(kCable + kSim);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_EQ(s.model->cable.n(), 5);
  EXPECT_DOUBLE_EQ(s.model->cable.elements[0].length, 20.0);
  EXPECT_DOUBLE_EQ(s.model->fluid.rho, 1025.0);
  EXPECT_TRUE(s.model->bodies.empty());
  EXPECT_EQ(s.model->name, "scen");
  EXPECT_DOUBLE_EQ(s.model->sim.duration, 10.0);
  EXPECT_DOUBLE_EQ(s.model->sim.time_step, 0.01);
}

TEST_F(ScenarioFile, UnknownKeyHasHint) {
  const auto s = load(
      "cable:\n  length: 100\n  elements: 5\n  mass_per_length: 1.5\n  diameter: 0.019\n  normal_darg: 1.8\n" + kSim);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.diags.str(), at("6:3: cable.normal_darg: unknown key (did you mean 'normal_drag'?)"));
}

TEST_F(ScenarioFile, UnknownKeyWithoutCloseMatchListsKeys) {
  const auto s = load(kCable + kSim + "initial: hanging\nzzz: 1\n");
  EXPECT_EQ(s.diags.str(),
            at("9:1: zzz: unknown key (expected one of: name, description, environment, cable, body, tow, "
               "initial, simulation, waves, vessel, winch)"));
}

TEST_F(ScenarioFile, WrongType) {
  const auto s = load("cable:\n  length: 100\n  elements: five\n  mass_per_length: 1.5\n  diameter: 0.019\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("3:13: cable.elements: expected an integer (got 'five')"));
}

TEST_F(ScenarioFile, WrongTypeListForNumber) {
  const auto s = load("cable:\n  length: [1, 2]\n  elements: 5\n  mass_per_length: 1.5\n  diameter: 0.019\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("2:11: cable.length: expected a number (got a list of 2)"));
}

TEST_F(ScenarioFile, MissingRequiredKey) {
  const auto s = load("cable:\n  length: 100\n  elements: 5\n  mass_per_length: 1.5\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("1:1: cable.diameter: missing required key"));
}

TEST_F(ScenarioFile, MissingSection) {
  const auto s = load(kCable);
  EXPECT_EQ(s.diags.str(), at("1:1: simulation: missing required key"));
}

TEST_F(ScenarioFile, NegativeDiameter) {
  const auto s = load("cable:\n  length: 100\n  elements: 5\n  mass_per_length: 1.5\n  diameter: -0.01\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("5:13: cable.diameter: must be > 0 (got -0.01)"));
}

TEST_F(ScenarioFile, ZeroElements) {
  const auto s = load("cable:\n  length: 100\n  elements: 0\n  mass_per_length: 1.5\n  diameter: 0.019\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("3:13: cable.elements: must be >= 1 (got 0)"));
}

TEST_F(ScenarioFile, BadInertiaTriangleInequality) {
  const auto s = load(kCable + kSim + "body:\n  mass: 3\n  inertia: [1, 1, 5]\n  link_point: [0, 0, 0]\n");
  EXPECT_EQ(s.diags.str(),
            at("10:12: body.inertia: principal moments must satisfy the triangle inequality (got 1, 1, 5: 5 > 1 + 1)"));
}

TEST_F(ScenarioFile, BadInertiaNotPositiveDefinite) {
  const auto s = load(kCable + kSim + "body:\n  mass: 3\n  inertia: [1, -1, 1]\n  link_point: [0, 0, 0]\n");
  EXPECT_EQ(s.diags.str(), at("10:12: body.inertia: must be positive definite (principal moments -1, 1, 1)"));
}

TEST_F(ScenarioFile, BadInertiaNotSymmetric) {
  const auto s = load(kCable + kSim +
                      "body:\n  mass: 3\n  inertia: [[1, 0.1, 0], [0, 1, 0], [0, 0, 1]]\n  link_point: [0, 0, 0]\n");
  EXPECT_EQ(s.diags.str(),
            at("10:12: body.inertia: must be symmetric (got 0.1 at row 0, column 1 but 0 at row 1, column 0)"));
}

TEST_F(ScenarioFile, NonIncreasingTrackTimesInline) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - type: track\n      points: [[0, 0, 0, 0], [2, 1, 0, 0], [2, 2, 0, 0]]\n");
  EXPECT_EQ(s.diags.str(), at("11:44: tow.motion.0.points.2: times must be strictly increasing (got 2 after 2)"));
}

TEST_F(ScenarioFile, NonIncreasingTrackTimesInCsvRelativeToScenario) {
  write("time,x,y,z\n0,0,0,0\n1,1,0,0\n0.5,2,0,0\n", "track.csv");
  const auto s = load(kCable + kSim + "tow:\n  motion:\n    - {type: track, file: track.csv}\n");
  const std::string csv = (dir_ / "track.csv").string();
  EXPECT_EQ(s.diags.str(), csv + ":4:1: tow.motion.0.file: times must be strictly increasing (got 0.5 after 1)\n");
}

TEST_F(ScenarioFile, TrackCsvBadNumberAndMissingFile) {
  write("0,0,0,0\n1,1,x,0\n", "track.csv");
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: track, file: track.csv}\n    - {type: track, file: none.csv}\n");
  const std::string csv = (dir_ / "track.csv").string();
  EXPECT_EQ(s.diags.str(),
            at("11:27: tow.motion.1.file: cannot open the track file '" + (dir_ / "none.csv").string() + "'") + csv +
                ":2:5: tow.motion.0.file: expected a number (got 'x')\n");
}

TEST_F(ScenarioFile, SetOverridesValue) {
  const auto s = load(kCable + kSim, {"cable.elements=40", "simulation.time_step=0.005"});
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_EQ(s.model->cable.n(), 40);
  EXPECT_DOUBLE_EQ(s.model->cable.elements[0].length, 2.5);
  EXPECT_DOUBLE_EQ(s.model->sim.time_step, 0.005);
}

TEST_F(ScenarioFile, SetCreatesSectionsAndIndexesLists) {
  const auto s = load(kCable + kSim +
                          "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
                          "  spheres:\n    - {center: [0, 0, 0], radius: 0.05}\n",
                      {"body.spheres.0.radius=0.1", "tow.mode=force", "tow.force=[0,0,10]",
                       "environment.current=[0.5, 0, 0]"});
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_DOUBLE_EQ(s.model->bodies.at(0).spheres.at(0).radius, 0.1);
  EXPECT_EQ(s.model->tow.mode, towsim::Tow::Mode::Force);
  ASSERT_EQ(s.model->tow.force_value.size(), 1u);
  EXPECT_DOUBLE_EQ(s.model->tow.force_value[0].z(), 10.0);
  ASSERT_EQ(s.model->fluid.current_velocity.size(), 1u);
  EXPECT_DOUBLE_EQ(s.model->fluid.current_velocity[0].x(), 0.5);
}

// A file named with --set is relative to the current directory (like any
// command-line path), one in the scenario to the scenario's folder: the same
// name in both places, different contents, tell which was read.
TEST_F(ScenarioFile, SetFilePathIsRelativeToTheCurrentDirectory) {
  write("time,x,y,z\n0,0,0,0\n1,1,0,0\n", "t.csv");  // valid, in the scenario's folder
  const fs::path cwd = dir_ / "cwd";
  fs::create_directories(cwd);
  std::ofstream(cwd / "t.csv") << "time,x,y,z\n0,0,0,0\n1,1,0,0\n0.5,2,0,0\n";  // invalid
  const fs::path before = fs::current_path();
  fs::current_path(cwd);
  const auto s = load(kCable + kSim, {"tow.motion.0={type: track, file: t.csv}"});
  const auto in_file = load(kCable + kSim + "tow:\n  motion:\n    - {type: track, file: t.csv}\n");
  fs::current_path(before);
  EXPECT_EQ(s.diags.str(), "t.csv:4:1: tow.motion.0.file: times must be strictly increasing (got 0.5 after 1)\n");
  EXPECT_TRUE(in_file.ok()) << in_file.diags.str();
}

// An index into a list the scenario does not have starts the list; the new
// item's missing keys are reported (not "expected a list (got a mapping)").
TEST_F(ScenarioFile, SetIndexStartsAMissingList) {
  const auto s = load(kCable + kSim +
                          "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
                          "  cylinders:\n    - {center: [0, 0, 0], axis: [1, 0, 0], length: 1, diameter: 0.2}\n",
                      {"body.spheres.0.radius=0.1"});
  EXPECT_EQ(s.diags.str(), "--set:1:1: body.spheres.0.center: missing required key\n");
}

TEST_F(ScenarioFile, SetBadValueNamesSet) {
  const auto s = load(kCable + kSim, {"cable.elements=40", "cable.diameter=-1"});
  EXPECT_EQ(s.diags.str(), "--set:2:16: cable.diameter: must be > 0 (got -1)\n");
}

TEST_F(ScenarioFile, SetUnknownKeyAndSyntax) {
  const auto s = load(kCable + kSim, {"cable.diamter=1", "cable.length", "cable.length.x=1"});
  EXPECT_EQ(s.diags.str(),
            "--set:1:1: cable.diamter: unknown key (did you mean 'diameter'?)\n"
            "--set:2:1: cable.length: expected KEY=VALUE (e.g. cable.elements=40)\n"
            "--set:3:1: cable.length.x: cannot go into '100': it is a single value\n");
}

TEST_F(ScenarioFile, SeveralErrorsAtOnce) {
  const auto s = load(
      "cable:\n  length: -100\n  elements: 0\n  mass_per_length: abc\n  diameter: -0.01\n  colour: red\n"
      "simulation:\n  duration: 0\n  integrator: rk5\n",
      {"simulation.time_step=0"});
  EXPECT_EQ(s.diags.str(),
            at("2:11: cable.length: must be > 0 (got -100)") + at("3:13: cable.elements: must be >= 1 (got 0)") +
                at("4:20: cable.mass_per_length: expected a number (got 'abc')") +
                at("5:13: cable.diameter: must be > 0 (got -0.01)") +
                at("6:3: cable.colour: unknown key (expected one of: length, elements, mass_per_length, diameter, "
                   "normal_drag, tangential_drag, added_mass, added_mass_model, sign_smoothing_speed, breaking_load, "
                   "axial_stiffness, axial_damping, bending_stiffness, sections, attachments)") +
                at("8:13: simulation.duration: must be > 0 (got 0)") +
                at("9:15: simulation.integrator: expected one of rk4, dopri5, cash_karp54, rosenbrock (got 'rk5'; did "
                   "you mean "
                   "'rk4'?)") +
                "--set:1:22: simulation.time_step: must be > 0 (got 0)\n");
}

TEST_F(ScenarioFile, RosenbrockNeedsTheDefaultFormulation) {
  const auto s = load(kCable + kSim + "  integrator: rosenbrock\n  formulation: paper\n");
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.diags.str(),
            at("8:15: simulation.integrator: rosenbrock needs formulation: default (its stage solves use the O(n) "
               "recursion)"));
  const auto ok = load(kCable + kSim + "  integrator: rosenbrock\n");
  ASSERT_TRUE(ok.ok()) << ok.diags.str();
  EXPECT_EQ(ok.model->sim.integrator, towsim::Integrator::Rosenbrock);
}

// The default integrator depends on the formulation only (docs/scenario.md
// "simulation"): rosenbrock with the default one, rk4 with the paper's
// (rosenbrock refuses it); an explicit integrator is always kept.
TEST_F(ScenarioFile, DefaultIntegratorFollowsTheFormulation) {
  const auto def = load(kCable + kSim);
  ASSERT_TRUE(def.ok()) << def.diags.str();
  EXPECT_EQ(def.spec.simulation.integrator.value, "rosenbrock");
  EXPECT_FALSE(def.spec.simulation.integrator.given);
  EXPECT_EQ(def.model->sim.integrator, towsim::Integrator::Rosenbrock);
  EXPECT_EQ(def.model->sim.formulation, towsim::Formulation::Default);
  const auto named = load(kCable + kSim + "  formulation: default\n");
  ASSERT_TRUE(named.ok()) << named.diags.str();
  EXPECT_EQ(named.model->sim.integrator, towsim::Integrator::Rosenbrock);
  const auto paper = load(kCable + kSim + "  formulation: paper\n");
  ASSERT_TRUE(paper.ok()) << paper.diags.str();
  EXPECT_EQ(paper.model->sim.integrator, towsim::Integrator::RK4);
  EXPECT_EQ(paper.model->sim.formulation, towsim::Formulation::Paper);
  // Given by --set: the formulation's default follows the override.
  const auto set = load(kCable + kSim, {"simulation.formulation=paper"});
  ASSERT_TRUE(set.ok()) << set.diags.str();
  EXPECT_EQ(set.model->sim.integrator, towsim::Integrator::RK4);
  for (const auto& [key, integrator] :
       {std::pair{"rk4", towsim::Integrator::RK4}, std::pair{"dopri5", towsim::Integrator::DOPRI5},
        std::pair{"cash_karp54", towsim::Integrator::CashKarp54}}) {
    const auto explicit_ = load(kCable + kSim + "  integrator: " + key + "\n");
    ASSERT_TRUE(explicit_.ok()) << explicit_.diags.str();
    EXPECT_EQ(explicit_.model->sim.integrator, integrator) << key;
  }
  EXPECT_EQ(towsim::default_integrator(towsim::Formulation::Default), towsim::Integrator::Rosenbrock);
  EXPECT_EQ(towsim::default_integrator(towsim::Formulation::Paper), towsim::Integrator::RK4);
}

// The default tolerance is the integrator's own: 1e-4 for rosenbrock (whose
// error control includes the forces; the default accuracy, 0.1 % of the
// peak tow force), 1e-6 for dopri5 and cash_karp54; a
// given tolerance is kept whatever the integrator.
TEST_F(ScenarioFile, DefaultToleranceIsPerIntegrator) {
  const auto def = load(kCable + kSim);
  ASSERT_TRUE(def.ok()) << def.diags.str();
  EXPECT_EQ(def.model->sim.tolerance, 1e-4);
  for (const auto& [key, tol] : {std::pair{"rosenbrock", 1e-4}, std::pair{"dopri5", 1e-6},
                                 std::pair{"cash_karp54", 1e-6}, std::pair{"rk4", 1e-6}}) {
    const auto s = load(kCable + kSim + "  integrator: " + key + "\n");
    ASSERT_TRUE(s.ok()) << s.diags.str();
    EXPECT_EQ(s.model->sim.tolerance, tol) << key;
  }
  const auto given = load(kCable + kSim + "  tolerance: 3.0e-4\n");
  ASSERT_TRUE(given.ok()) << given.diags.str();
  EXPECT_EQ(given.model->sim.integrator, towsim::Integrator::Rosenbrock);
  EXPECT_EQ(given.model->sim.tolerance, 3e-4);
  const auto given_dopri = load(kCable + kSim + "  integrator: dopri5\n  tolerance: 1.0e-5\n");
  ASSERT_TRUE(given_dopri.ok()) << given_dopri.diags.str();
  EXPECT_EQ(given_dopri.model->sim.tolerance, 1e-5);
  EXPECT_EQ(towsim::default_tolerance(towsim::Integrator::Rosenbrock), 1e-4);
  EXPECT_EQ(towsim::default_tolerance(towsim::Integrator::DOPRI5), 1e-6);
}

TEST_F(ScenarioFile, DuplicateKey) {
  const auto s = load(kCable + "  elements: 6\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("6:3: cable.elements: duplicate key (first given at line 3)"));
}

TEST_F(ScenarioFile, YamlSyntaxError) {
  const auto s = load("cable: [1, 2\nsimulation: 3\n");
  EXPECT_EQ(s.diags.str(), at("2:11: (yaml): YAML syntax error: end of sequence flow not found"));
}

// A tab in the indentation (YAML allows only spaces) is named, not just
// yaml-cpp's "illegal map value".
TEST_F(ScenarioFile, TabIndentationIsNamed) {
  const auto s = load("cable:\n\tlength: 100\n");
  EXPECT_EQ(s.diags.str(), at("2:8: (yaml): YAML syntax error: illegal map value (line 2 is indented with a tab: "
                              "YAML indentation must use spaces)"));
}

TEST_F(ScenarioFile, MissingFile) {
  const auto s = load_scenario_file((dir_ / "nope.yaml").string());
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.diags.str(),
            (dir_ / "nope.yaml").string() + ":0:0: (file): cannot open the file (No such file or directory)\n");
}

TEST_F(ScenarioFile, TurnNeedsHorizontalSpeed) {
  const auto s = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: ramp, direction: [1, 0, 0], speed: 2, ramp_time: 10}\n"
                      "    - {type: turn, radius: 5, start_time: 0}\n"
                      "    - {type: turn, radius: 5, start_time: 3}\n");
  EXPECT_EQ(s.diags.str(), at("12:7: tow.motion.2: a turn cannot start while the turn tow.motion.1 goes on (it has no "
                              "angle_deg: it never ends)"));
  const auto t = load(kCable + kSim +
                      "tow:\n  motion:\n    - {type: ramp, direction: [1, 0, 0], speed: 2, ramp_time: 10}\n"
                      "    - {type: turn, radius: 5, start_time: 0}\n");
  EXPECT_EQ(t.diags.str(), at("11:7: tow.motion.1: a turn needs a non-zero horizontal tow speed at its start time "
                              "(got 0 m/s at t = 0 s)"));
}

TEST_F(ScenarioFile, PieceKeysDependOnType) {
  const auto s = load(kCable + kSim + "tow:\n  motion:\n    - {type: heave, amplitude: 1, period: 0, speed: 2}\n");
  EXPECT_EQ(s.diags.str(), at("10:43: tow.motion.0.period: must be > 0 (got 0)") +
                               at("10:46: tow.motion.0.speed: unknown key (expected one of: type, amplitude, period, "
                                  "start_time)"));
}

TEST_F(ScenarioFile, ForceModeNeedsForce) {
  const auto s = load(kCable + kSim + "tow:\n  mode: force\n");
  EXPECT_EQ(s.diags.str(), at("9:3: tow.force: missing required key (with mode: force)"));
}

TEST_F(ScenarioFile, SurfacesAndCurrentTable) {
  const auto s = load(kCable + kSim +
                      "environment:\n  current:\n    - {depth: 0, velocity: [1, 0, 0]}\n"
                      "    - {depth: 200, velocity: [0.3, 0, 0]}\n"
                      "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
                      "  initial_attitude_deg: [0, 0, 90]\n"
                      "  surfaces:\n    - {center: [0, 0, 0], chord: [2, 0, 0], normal: [0, 0, 3], area: 0.5,"
                      " deflection_deg: [[0, 0], [10, 5]]}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& f = s.model->fluid;
  ASSERT_EQ(f.current_depth.size(), 2u);
  EXPECT_DOUBLE_EQ(f.current_depth[1], 200.0);
  EXPECT_DOUBLE_EQ(f.current_velocity[1].x(), 0.3);
  const auto& surf = s.model->bodies.at(0).surfaces.at(0);
  EXPECT_DOUBLE_EQ(surf.chord.x(), 1.0);
  EXPECT_DOUBLE_EQ(surf.normal.z(), 1.0);
  EXPECT_NEAR(surf.deflection_angle[1], 5.0 * M_PI / 180.0, 1e-15);
  EXPECT_NEAR(surf.stall_angle, 15.0 * M_PI / 180.0, 1e-15);
  const towsim::Vec3 x = s.model->bodies.at(0).initial_attitude * towsim::Vec3::UnitX();
  EXPECT_NEAR(x.y(), 1.0, 1e-12);  // yaw 90 deg: body x along global y
}

TEST_F(ScenarioFile, SurfaceChordNormalOrthogonal) {
  const auto s = load(kCable + kSim +
                      "body:\n  mass: 3\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
                      "  surfaces:\n    - {center: [0, 0, 0], chord: [1, 0, 0], normal: [1, 0, 1], area: 0.5}\n");
  EXPECT_EQ(s.diags.str(), at("13:53: body.surfaces.0.normal: must be orthogonal to chord (the angle between them "
                              "is 45 deg)"));
}

TEST_F(ScenarioFile, DefaultsAndChoices) {
  const auto s = load(kCable + "  tangential_drag: {law: skin}\n  added_mass_model: morison\n" + kSim +
                      "  integrator: dopri5\n  formulation: paper\n  write_nodes: false\n"
                      "initial: {direction: [1, 0, -1]}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& m = *s.model;
  EXPECT_EQ(m.cable.tangential_law, towsim::TangentialLaw::Skin);
  EXPECT_EQ(m.cable.added_mass_model, towsim::AddedMassModel::Morison);
  EXPECT_EQ(m.sim.integrator, towsim::Integrator::DOPRI5);
  EXPECT_EQ(m.sim.formulation, towsim::Formulation::Paper);
  EXPECT_FALSE(m.sim.write_nodes);
  EXPECT_EQ(m.initial.kind, towsim::Initial::Kind::Direction);
  EXPECT_NEAR(m.initial.direction.norm(), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(m.sim.tolerance, 1e-6);
  EXPECT_DOUBLE_EQ(m.sim.max_step, 1.0);
}

// rosenbrock's steps are bounded by accuracy only: no default max_step
// (docs/scenario.md); a given one still applies.
TEST_F(ScenarioFile, RosenbrockHasNoDefaultMaxStep) {
  const auto a = load(kCable + kSim + "  integrator: rosenbrock\n");
  ASSERT_TRUE(a.ok()) << a.diags.str();
  EXPECT_TRUE(std::isinf(a.model->sim.max_step));
  const auto b = load(kCable + kSim + "  integrator: rosenbrock\n  max_step: 2\n");
  ASSERT_TRUE(b.ok()) << b.diags.str();
  EXPECT_DOUBLE_EQ(b.model->sim.max_step, 2.0);
}

TEST_F(ScenarioFile, EchoIsJsonAfterSet) {
  const auto s = load(kCable + kSim + "name: \"007\"\n", {"cable.elements=7"});
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto j = towsim::scenario::to_json(s.tree);
  EXPECT_EQ(j["cable"]["elements"], 7);
  EXPECT_EQ(j["cable"]["diameter"], 0.019);
  EXPECT_EQ(j["name"], "007");
  EXPECT_EQ(s.model->name, "007");
}
