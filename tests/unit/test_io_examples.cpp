// Built-in examples: all present, each parses and compiles; outputs' format.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support/cli.hpp"
#include "towsim/output/output.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"

namespace fs = std::filesystem;
using namespace towsim::scenario;
using namespace towsim::output;

TEST(IoExamples, FourPaperAndCableExamplesAreBuiltIn) {
  for (const char* name : {"paper-planar-a", "paper-planar-b", "paper-3d-turn", "cable-tow"}) {
    const Example* e = find_example(name);
    ASSERT_NE(e, nullptr) << name;
    EXPECT_FALSE(e->description.empty()) << name;
  }
  EXPECT_NE(find_example(kDefaultExample), nullptr);
  EXPECT_EQ(find_example("no-such-example"), nullptr);
}

TEST(IoExamples, EveryExampleParsesAndCompiles) {
  ASSERT_GE(examples().size(), 4u);
  for (const auto& e : examples()) {
    const auto s = load_scenario_text(e.yaml, e.name + ".yaml", e.name, "");
    EXPECT_TRUE(s.ok()) << e.name << ":\n" << s.diags.str();
    if (s.ok()) {
      EXPECT_EQ(s.model->name, e.name);
    }
  }
}

TEST(IoExamples, DescriptionsAreWhatTheScenarioReaderReads) {
  // The list reads each example's `description:` line alone (start-up); the
  // same text as the scenario reader gets from the whole document.
  for (const auto& e : examples()) {
    const auto s = load_scenario_text(e.yaml, e.name + ".yaml", e.name, "");
    ASSERT_TRUE(s.ok()) << e.name;
    EXPECT_EQ(e.description, s.spec.description) << e.name;
  }
}

TEST(IoExamples, PaperPlanarValues) {
  const Example* e = find_example("paper-planar-a");
  ASSERT_NE(e, nullptr);
  const auto s = load_scenario_text(e->yaml, "a.yaml", "a", "");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& m = *s.model;
  EXPECT_EQ(m.cable.n(), 5);
  EXPECT_DOUBLE_EQ(m.cable.total_length(), 100.0);
  EXPECT_DOUBLE_EQ(m.cable.elements[0].mass, 30.0);
  ASSERT_TRUE(!m.bodies.empty());
  // Zero apparent weight: body mass = mass of the water displaced by the two spheres.
  const double displaced = 1025.0 * 2 * 4.0 / 3.0 * M_PI * std::pow(0.25, 3);
  EXPECT_NEAR(m.bodies[0].mass, displaced, 1e-6);
  EXPECT_NEAR(m.bodies[0].displaced_volume * 1025.0, m.bodies[0].mass, 1e-6);
  EXPECT_NEAR(m.bodies[0].inertia_cg(1, 1), 2 * (0.4 * displaced / 2 * 0.0625) + displaced * 0.5625, 1e-6);
  const auto b = load_scenario_text(find_example("paper-planar-b")->yaml, "b.yaml", "b", "");
  ASSERT_TRUE(b.ok());
  ASSERT_EQ(b.model->tow.pieces.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<towsim::Heave>(b.model->tow.pieces[1]));
}

TEST(IoExamples, Paper3dTurnValues) {
  const auto s = load_scenario_text(find_example("paper-3d-turn")->yaml, "t.yaml", "t", "");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& m = *s.model;
  EXPECT_EQ(m.cable.n(), 10);
  EXPECT_DOUBLE_EQ(m.cable.elements[0].length, 30.0);
  EXPECT_DOUBLE_EQ(m.bodies[0].inertia_cg(2, 2), 0.003);
  EXPECT_DOUBLE_EQ(m.bodies[0].link_point.z(), 0.05);
  ASSERT_EQ(m.tow.pieces.size(), 2u);
  ASSERT_TRUE(std::holds_alternative<towsim::Turn>(m.tow.pieces[1]));
  EXPECT_TRUE(std::get<towsim::Turn>(m.tow.pieces[1]).port);
  EXPECT_DOUBLE_EQ(std::get<towsim::Turn>(m.tow.pieces[1]).radius, 7.5);
}

namespace {

using towsim::testing::fresh_dir;
using towsim::testing::lines_of;

towsim::Sample sample(double t) {
  towsim::Sample s;
  s.t = t;
  s.tow_pos = towsim::Vec3(t, 0, 0);
  s.tow_force = towsim::Vec3(3, 0, 4);
  s.node_pos = {towsim::Vec3(t, 0, 0), towsim::Vec3(t, 0, -10)};
  s.node_vel = {towsim::Vec3(1, 0, 0), towsim::Vec3(1, 0, 0)};
  s.tension = {5, 2};
  s.axial = {5, -2};
  s.strain = {0, 1.5e-3};
  s.bodies.resize(1);
  s.bodies[0].pos = towsim::Vec3(t, 0, -10.5);
  s.bodies[0].rpy_deg = towsim::Vec3(0, -t, 0);
  s.bodies[0].link_force = towsim::Vec3(0, 0, 2);
  return s;
}

}  // namespace

/// A model with one cable element and, optionally, an end body (the writer's
/// columns depend on the chain only).
towsim::Model writer_model(bool body) {
  towsim::Model m;
  m.cable.elements.resize(1);
  if (body) m.bodies.emplace_back();
  return m;
}

TEST(IoOutput, TimeseriesColumnsAndExtremes) {
  const fs::path dir = fresh_dir("out_writer");
  const towsim::Model model = writer_model(true);
  {
    RunWriter w(dir.string(), model, true);
    w.write(sample(0));
    w.write(sample(0.5));
    w.flush();
    EXPECT_EQ(w.samples(), 2);
    EXPECT_DOUBLE_EQ(w.extremes().max_tow_tension.value, 5.0);
    EXPECT_DOUBLE_EQ(w.extremes().end_body_extremes.max_depth.value, 10.5);
    EXPECT_DOUBLE_EQ(w.extremes().end_body_extremes.min_deg[1].value, -0.5);
    EXPECT_DOUBLE_EQ(w.extremes().end_body_extremes.min_deg[1].time, 0.5);
    EXPECT_DOUBLE_EQ(w.extremes().min_axial_force.value, -2.0);
    towsim::RunStats st;
    st.end_time = 0.5;
    const auto j = make_summary({{"cable", {{"elements", 1}}}}, "m", st, w, true);
    ASSERT_TRUE(write_summary(dir.string(), j));
  }
  const auto ts = lines_of(dir / "timeseries.csv");
  ASSERT_EQ(ts.size(), 3u);
  EXPECT_EQ(ts[0].rfind("time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z,"
                        "body_x,body_y,body_z,body_roll_deg,body_pitch_deg,body_yaw_deg,"
                        "link_force_x,link_force_y,link_force_z,",
                        0),
            0u);
  EXPECT_EQ(ts[2].rfind("0.5,0.5,0,0,3,0,4,0.5,0,-10,0.5,0,-10.5,0,-0.5,0,0,0,2,5,10,", 0), 0u) << ts[2];
  const auto nodes = lines_of(dir / "nodes.csv");
  ASSERT_EQ(nodes.size(), 5u);
  EXPECT_EQ(nodes[0], "time,node,x,y,z,vx,vy,vz,tension,axial_force,strain");
  EXPECT_EQ(nodes[4], "0.5,1,0.5,0,-10,1,0,0,2,-2,0.0015");
  std::ifstream in(dir / "summary.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["scenario"]["cable"]["elements"], 1);
  EXPECT_EQ(j["extremes"]["max_end_depth"]["value"], 10.0);
  EXPECT_EQ(j["samples"], 2);
  fs::remove_all(dir);
}

TEST(IoOutput, NoBodyHeaderAndNoNodes) {
  const fs::path dir = fresh_dir("out_nobody");
  const towsim::Model model = writer_model(false);
  {
    RunWriter w(dir.string(), model, false);
    towsim::Sample s = sample(0);
    s.bodies.clear();
    w.write(s);
  }
  EXPECT_FALSE(fs::exists(dir / "nodes.csv"));
  const auto ts = lines_of(dir / "timeseries.csv");
  EXPECT_EQ(ts[0].rfind("time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z,tow_tension", 0),
            0u);
  fs::remove_all(dir);
}
