// Networks in a scenario (docs/scenario.md "Networks"): lines:, bodies:,
// junctions: and vessel.tow_points read, checked (exact error texts) and
// compiled into a Network.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../support/scenario_files.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/tow/tow.hpp"
#include "towsim/waves/vessel.hpp"

namespace {

using towsim::Model;
using towsim::Network;
using towsim::Vec3;
using ScenarioFile = towsim::testing::ScenarioFiles;

const std::string kTowSim =
    "tow:\n"
    "  motion:\n"
    "    - {type: ramp, direction: [1, 1, 0], speed: 2, ramp_time: 10}\n"
    "simulation:\n"
    "  duration: 10\n";

// The example rig of docs/scenario.md "Networks" (lines 6-25).
const std::string kRig = kTowSim +
                         "vessel:\n"
                         "  tow_points: {stern: [-35, 0, 5], boom: [-20, -8, 3]}\n"
                         "bodies:\n"
                         "  - name: fish\n"
                         "    mass: 500\n"
                         "    inertia: [50, 100, 100]\n"
                         "    volume: 0.2\n"
                         "    spheres: [{center: [0, 0, 0], radius: 0.3}]\n"
                         "    points: {fwd: [0.5, 0, 0.3], aft: [-0.5, 0, 0.3]}\n"
                         "junctions:\n"
                         "  - {name: apex, mass: 5, volume: 0.001, drag_area: 0.02, added_mass: 1}\n"
                         "lines:\n"
                         "  - {name: main, from: vessel.stern, to: apex, length: 600, elements: 30, "
                         "mass_per_length: 1.5, diameter: 0.02}\n"
                         "  - {name: leg_fwd, from: apex, to: fish.fwd, length: 3, elements: 3, "
                         "mass_per_length: 1.5, diameter: 0.02}\n"
                         "  - {name: leg_aft, from: apex, to: fish.aft, length: 3, elements: 3, "
                         "mass_per_length: 1.5, diameter: 0.02}\n"
                         "  - {name: streamer, from: vessel.boom, to: free, length: 800, elements: 80, "
                         "mass_per_length: 1.5, diameter: 0.02}\n";

const std::string kLine = ", length: 10, elements: 2, mass_per_length: 1, diameter: 0.02}\n";

void expect_vec(const Vec3& a, const Vec3& b) {
  EXPECT_EQ(a.x(), b.x());
  EXPECT_EQ(a.y(), b.y());
  EXPECT_EQ(a.z(), b.z());
}

}  // namespace

TEST_F(ScenarioFile, NetworkRigCompilesInTreeOrder) {
  const auto s = load(kRig);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  ASSERT_TRUE(s.is_network());
  EXPECT_FALSE(s.model.has_value());
  const Network& n = *s.network;
  EXPECT_EQ(n.name, "scen");
  ASSERT_EQ(n.tree.lines.size(), 4u);
  EXPECT_EQ(n.line_names, (std::vector<std::string>{"main", "leg_fwd", "leg_aft", "streamer"}));
  EXPECT_EQ(n.line_from, (std::vector<std::string>{"vessel.stern", "apex", "apex", "vessel.boom"}));
  EXPECT_EQ(n.line_to, (std::vector<std::string>{"apex", "fish.fwd", "fish.aft", "free"}));
  EXPECT_EQ(n.tow_point, (std::vector<std::string>{"stern", "", "", "boom"}));
  // Tops: the roots on the vessel, the legs from main's cable end (the junction).
  const auto& tops = n.tree.tops;
  EXPECT_EQ(tops[0].line, -1);
  EXPECT_EQ(tops[1].line, 0);
  EXPECT_EQ(tops[1].body, -1);
  EXPECT_EQ(tops[2].line, 0);
  EXPECT_EQ(tops[2].body, -1);
  EXPECT_EQ(tops[3].line, -1);
  // The junction: main's attachment at its end joint.
  const Model& main = n.tree.lines[0];
  EXPECT_EQ(main.name, "main");
  ASSERT_EQ(main.cable.attachments.size(), 1u);
  const towsim::Attachment& a = main.cable.attachments[0];
  EXPECT_EQ(a.joint, 30);
  EXPECT_EQ(a.at, 600.0);
  EXPECT_EQ(a.mass, 5.0);
  EXPECT_EQ(a.volume, 0.001);
  EXPECT_EQ(a.drag_area, 0.02);
  EXPECT_EQ(a.added_mass, 1.0);
  ASSERT_EQ(n.junctions.size(), 1u);
  EXPECT_EQ(n.junctions[0].name, "apex");
  EXPECT_EQ(n.junctions[0].line, 0);
  // The body: leg_fwd's end body, hung at its point fwd.
  const Model& fwd = n.tree.lines[1];
  ASSERT_EQ(fwd.bodies.size(), 1u);
  EXPECT_EQ(fwd.bodies[0].name, "fish");
  expect_vec(fwd.bodies[0].link_point, Vec3(0.5, 0, 0.3));
  ASSERT_EQ(n.bodies.size(), 1u);
  EXPECT_EQ(n.bodies[0].name, "fish");
  EXPECT_EQ(n.bodies[0].line, 1);
  EXPECT_EQ(n.bodies[0].body, 0);
  // The bridle's second leg: a loop at fish.aft, its Model without end body or junction.
  const Model& aft = n.tree.lines[2];
  EXPECT_TRUE(aft.bodies.empty());
  EXPECT_TRUE(aft.cable.attachments.empty());
  ASSERT_EQ(n.tree.loops.size(), 1u);
  const towsim::LoopJoint& loop = n.tree.loops[0];
  EXPECT_EQ(loop.line, 2);
  EXPECT_EQ(loop.node_line, 1);
  EXPECT_EQ(loop.body, 0);
  expect_vec(loop.point, Vec3(-0.5, 0, 0.3));
  // The roots' tow points: sheaves of a vessel with no motion.
  ASSERT_TRUE(main.tow.vessel);
  expect_vec(main.tow.vessel->sheave(), Vec3(-35, 0, 5));
  ASSERT_TRUE(n.tree.lines[3].tow.vessel);
  expect_vec(n.tree.lines[3].tow.vessel->sheave(), Vec3(-20, -8, 3));
  EXPECT_EQ(n.tree.lines[3].cable.n(), 80);
  EXPECT_EQ(n.settings().sim.duration, 10.0);
}

TEST_F(ScenarioFile, NetworkTowPointIsTheLawPointPlusTheTurnedOffset) {
  const auto s = load(kRig);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const towsim::Tow& tow = s.network->tree.lines[3].tow;
  const Vec3 offset(-20, -8, 3);
  for (double t : {0.0, 1e-3, 5.0, 20.0}) {
    const towsim::TowKinematics law = towsim::tow_law_kinematics(tow, t);
    const towsim::TowKinematics k = towsim::tow_kinematics(tow, t);
    // Course 45 deg (the ramp along [1, 1, 0]), at rest too.
    const double c = std::cos(M_PI / 4), sn = std::sin(M_PI / 4);
    const Vec3 turned(c * offset.x() - sn * offset.y(), sn * offset.x() + c * offset.y(), offset.z());
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(k.pos[i], law.pos[i] + turned[i], 1e-12) << "t = " << t;
      EXPECT_NEAR(k.vel[i], law.vel[i], 1e-12) << "t = " << t;
      EXPECT_NEAR(k.acc[i], law.acc[i], 1e-12) << "t = " << t;
    }
  }
}

namespace {

/// The Model fields a line shares with its single-chain form.
void expect_same_chain(const Model& a, const Model& b) {
  ASSERT_EQ(a.cable.n(), b.cable.n());
  for (std::size_t k = 0; k < a.cable.elements.size(); ++k) {
    const auto &x = a.cable.elements[k], &y = b.cable.elements[k];
    EXPECT_EQ(x.length, y.length);
    EXPECT_EQ(x.mass, y.mass);
    EXPECT_EQ(x.weight, y.weight);
    EXPECT_EQ(x.added_mass, y.added_mass);
    EXPECT_EQ(x.drag_factor, y.drag_factor);
    EXPECT_EQ(x.friction_factor, y.friction_factor);
    EXPECT_EQ(x.axial_stiffness, y.axial_stiffness);
    EXPECT_EQ(x.bending_stiffness, y.bending_stiffness);
  }
  EXPECT_EQ(a.cable.sections.size(), b.cable.sections.size());
  ASSERT_EQ(a.cable.attachments.size(), b.cable.attachments.size());
  for (std::size_t k = 0; k < a.cable.attachments.size(); ++k) {
    EXPECT_EQ(a.cable.attachments[k].joint, b.cable.attachments[k].joint);
    EXPECT_EQ(a.cable.attachments[k].mass, b.cable.attachments[k].mass);
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    EXPECT_EQ(a.bodies[k].total_mass, b.bodies[k].total_mass);
    expect_vec(a.bodies[k].link_point, b.bodies[k].link_point);
    EXPECT_EQ(a.bodies[k].displaced_volume, b.bodies[k].displaced_volume);
  }
  EXPECT_EQ(a.tow.vessel == nullptr, b.tow.vessel == nullptr);
  expect_vec(a.tow.start, b.tow.start);
  EXPECT_EQ(a.tow.pieces.size(), b.tow.pieces.size());
  EXPECT_EQ(a.fluid.rho, b.fluid.rho);
  EXPECT_EQ(a.sim.duration, b.sim.duration);
  EXPECT_EQ(a.sim.time_step, b.sim.time_step);
  EXPECT_EQ(a.sim.integrator, b.sim.integrator);
  EXPECT_EQ(a.sim.tolerance, b.sim.tolerance);
  EXPECT_EQ(a.initial.kind, b.initial.kind);
  EXPECT_EQ(a.winch.active(), b.winch.active());
  for (double t : {0.0, 3.0, 12.0}) {
    const auto ka = towsim::tow_kinematics(a.tow, t), kb = towsim::tow_kinematics(b.tow, t);
    expect_vec(ka.pos, kb.pos);
    expect_vec(ka.vel, kb.vel);
  }
}

const std::string kBody =
    "  mass: 500\n"
    "  inertia: [50, 100, 100]\n"
    "  volume: 0.2\n"
    "  spheres: [{center: [0, 0, 0], radius: 0.3}]\n";

}  // namespace

TEST_F(ScenarioFile, NetworkLineAtTheTowLawPointIsTheChain) {
  const std::string cable =
      "  length: 100\n  elements: 10\n  mass_per_length: 1.5\n  diameter: 0.02\n  axial_stiffness: 1e7\n"
      "  axial_damping: 100\n";
  const auto chain = load(kTowSim + "cable:\n" + cable + "body:\n" + kBody + "  link_point: [0.5, 0, 0.3]\n" +
                          "winch: {rate: [[0, 0], [5, 1]]}\n");
  ASSERT_TRUE(chain.ok()) << chain.diags.str();
  std::string indented;  // the cable's keys under a line item
  for (std::size_t p = 0, q; p < cable.size(); p = q + 1) {
    q = cable.find('\n', p);
    indented += "  " + cable.substr(p, q - p + 1);
  }
  std::string body;
  for (std::size_t p = 0, q; p < kBody.size(); p = q + 1) {
    q = kBody.find('\n', p);
    body += "  " + kBody.substr(p, q - p + 1);
  }
  const auto net = load(kTowSim + "vessel: {tow_points: {origin: [0, 0, 0]}}\nbodies:\n  - name: fish\n" + body +
                        "    points: {p: [0.5, 0, 0.3]}\nlines:\n  - name: tow\n    from: vessel.origin\n"
                        "    to: fish.p\n    winch: {rate: [[0, 0], [5, 1]]}\n" +
                        indented);
  ASSERT_TRUE(net.ok()) << net.diags.str();
  ASSERT_EQ(net.network->tree.lines.size(), 1u);
  const Model& line = net.network->tree.lines[0];
  EXPECT_FALSE(line.tow.vessel);  // [0, 0, 0]: the tow law's point itself
  expect_same_chain(line, *chain.model);
  EXPECT_EQ(line.bodies[0].name, "fish");
  EXPECT_EQ(chain.model->bodies[0].name, "body");
}

TEST_F(ScenarioFile, NetworkLineTakesEveryCableKey) {
  const auto s = load(kTowSim +
                      "vessel: {tow_points: {stern: [-10, 0, 2]}}\n"
                      "lines:\n"
                      "  - name: tow\n"
                      "    from: vessel.stern\n"
                      "    to: free\n"
                      "    mass_per_length: 2\n"
                      "    diameter: 0.03\n"
                      "    axial_stiffness: 1e7\n"
                      "    bending_stiffness: 50\n"
                      "    normal_drag: {law: cross_flow, cd: 1.5}\n"
                      "    attachments: [{at: 20, mass: 4, volume: 0.002}]\n"
                      "    sections:\n"
                      "      - {name: upper, length: 50, elements: 5}\n"
                      "      - body: {name: depressor, mass: 100, inertia: [5, 10, 10], link_point: [0, 0, 0.2],\n"
                      "               lower_link_point: [0, 0, -0.2]}\n"
                      "      - {name: lower, length: 20, elements: 4, axial_stiffness: 2e6}\n"
                      "  - {name: tail, from: depressor.lower_link_point, to: free" +
                      kLine);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const Network& n = *s.network;
  const Model& tow = n.tree.lines[0];
  EXPECT_EQ(tow.cable.n(), 9);
  EXPECT_EQ(tow.cable.sections.size(), 2u);
  EXPECT_EQ(tow.cable.elements.back().axial_stiffness, 2e6);
  EXPECT_EQ(tow.cable.elements.front().bending_stiffness, 50.0);
  ASSERT_EQ(tow.cable.attachments.size(), 1u);
  EXPECT_EQ(tow.cable.attachments[0].joint, 2);
  ASSERT_EQ(tow.bodies.size(), 1u);
  EXPECT_TRUE(tow.bodies[0].inline_body);
  EXPECT_EQ(tow.bodies[0].name, "depressor");
  // tail hangs from the in-line body's lower link.
  EXPECT_EQ(n.tree.tops[1].line, 0);
  EXPECT_EQ(n.tree.tops[1].body, 0);
  expect_vec(n.tree.tops[1].point, Vec3(0, 0, -0.2));
  ASSERT_EQ(n.bodies.size(), 1u);
  EXPECT_EQ(n.bodies[0].name, "depressor");
}

TEST_F(ScenarioFile, NetworkOrdersLinesAfterTheirNodes) {
  // Written bottom up: the tree puts each line after the one it hangs from.
  const auto s = load(kTowSim +
                      "vessel: {tow_points: {stern: [0, 0, 0]}}\n"
                      "junctions: [{name: a}, {name: b}]\n"
                      "lines:\n"
                      "  - {name: low, from: b, to: free" +
                      kLine + "  - {name: mid, from: a, to: b" + kLine + "  - {name: top, from: vessel.stern, to: a" +
                      kLine);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_EQ(s.network->line_names, (std::vector<std::string>{"top", "mid", "low"}));
  EXPECT_EQ(s.network->tree.tops[1].line, 0);
  EXPECT_EQ(s.network->tree.tops[2].line, 1);
  EXPECT_EQ(s.network->junctions[0].line, 0);
  EXPECT_EQ(s.network->junctions[1].line, 1);
  EXPECT_TRUE(s.network->tree.loops.empty());
}

namespace {

// The rig's first 16 lines (tow, simulation, vessel, bodies, junctions), then lines: at line 17.
std::string rig_nodes() {
  std::size_t p = 0;
  for (int i = 0; i < 16; ++i) p = kRig.find('\n', p) + 1;
  return kRig.substr(0, p) + "lines:\n";
}

const std::string kL = ", length: 3, elements: 3, mass_per_length: 1.5, diameter: 0.02}\n";

}  // namespace

TEST_F(ScenarioFile, NetworkEndsAndNamesAreChecked) {
  const auto s = load(rig_nodes() + "  - {name: main, from: vessel.stren, to: apx" + kL +
                      "  - {name: main, from: free, to: fish.fwdd" + kL + "  - {name: c, from: fish, to: vessel.stern" +
                      kL + "  - {name: d, from: apex.x, to: fish.fwd, winch: {rate: 0}" + kL);
  EXPECT_EQ(s.diags.str(),
            at("16:5: junctions.0: 'apex' is not reached from the vessel (no line has to: apex)") +
                at("18:24: lines.0.from: unknown tow point 'stren' (did you mean 'stern'?)") +
                at("18:42: lines.0.to: unknown junction or body 'apx' (did you mean 'apex'?)") +
                at("19:12: lines.1.name: 'main' is already the name of lines.0 (line names must be distinct)") +
                at("19:24: lines.1.from: 'free' is only for to: (a line's top hangs from vessel.<tow point>, a "
                   "junction or a body's point)") +
                at("19:34: lines.1.to: unknown point 'fwdd' of body 'fish' (did you mean 'fwd'?)") +
                at("20:21: lines.2.from: 'fish' is a body: give one of its points, fish.<point> (one of fwd, aft)") +
                at("20:31: lines.2.to: a line cannot end at the vessel (write it from the vessel: from: "
                   "vessel.stern)") +
                at("21:21: lines.3.from: 'apex' is a junction: write apex (a junction has no points)"));
  EXPECT_FALSE(s.ok());
  EXPECT_FALSE(s.network.has_value());
}

TEST_F(ScenarioFile, NetworkTwoLinesIntoOneBodyPointNeedAJunction) {
  const auto s = load(rig_nodes() + "  - {name: a, from: vessel.stern, to: fish.fwd, winch: {rate: 0}" + kL +
                      "  - {name: b, from: vessel.boom, to: fish.fwd" + kL + "  - {name: c, from: apex, to: free" + kL);
  EXPECT_EQ(
      s.diags.str(),
      at("19:38: lines.1.to: line a already ends at fish.fwd: two lines into one point of a body, use a junction"));
}

TEST_F(ScenarioFile, NetworkWinchesOnlyAtTheVesselAndOutsideLoops) {
  const auto loop = load(rig_nodes() + "  - {name: a, from: vessel.stern, to: fish.fwd, winch: {rate: 0}" + kL +
                         "  - {name: b, from: vessel.boom, to: fish.aft, diameter_x: 1" + kL);
  EXPECT_EQ(loop.diags.str(),
            at("16:5: junctions.0: 'apex' is not reached from the vessel (no line has to: apex)") +
                at("18:56: lines.0.winch: not on a line of a loop (line b closes a loop at fish.aft that this line is "
                   "part of)") +
                at("19:48: lines.1.diameter_x: unknown key (did you mean 'diameter'?)"));
  const auto below = load(rig_nodes() + "  - {name: a, from: vessel.stern, to: apex" + kL +
                          "  - {name: b, from: apex, to: fish.fwd, winch: {rate: 0}" + kL);
  EXPECT_EQ(below.diags.str(),
            at("19:48: lines.1.winch: a winch is only at a line's top on the vessel (this line hangs from apex)"));
}

TEST_F(ScenarioFile, NetworkCyclesAndNodesNothingHolds) {
  const auto cycle = load(rig_nodes() + "  - {name: a, from: vessel.stern, to: free" + kL +
                          "  - {name: b, from: apex, to: fish.fwd" + kL + "  - {name: c, from: fish.aft, to: apex" +
                          kL);
  EXPECT_EQ(cycle.diags.str(),
            at("19:21: lines.1.from: 'apex' hangs below this line itself (its lines form a cycle that does not "
               "reach the vessel)") +
                at("20:21: lines.2.from: 'fish' hangs below this line itself (its lines form a cycle that does not "
                   "reach the vessel)"));
  const auto held = load(rig_nodes() + "  - {name: a, from: vessel.stern, to: free" + kL +
                         "  - {name: b, from: fish.fwd, to: free" + kL + "  - {name: c, from: apex, to: free" + kL +
                         "cable: {length: 1, elements: 1, mass_per_length: 1, diameter: 0.1}\n");
  EXPECT_EQ(held.diags.str(),
            at("17:1: lines: give either 'cable' or 'lines', not both") +
                at("19:21: lines.1.from: nothing holds 'fish': no line ends at it (give a line to: fish.<point>)") +
                at("20:21: lines.2.from: nothing holds 'apex': no line ends at it (give a line to: apex)"));
}

TEST_F(ScenarioFile, NetworkKeysNeedLines) {
  const auto s = load(towsim::testing::kCable + towsim::testing::kSim + "junctions: [{name: a}]\n");
  EXPECT_EQ(s.diags.str(), at("8:1: junctions: needs lines: (junctions join the lines of a network)"));
}
