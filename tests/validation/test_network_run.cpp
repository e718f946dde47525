// Runs of networks of lines (towsim/sim/simulate_network.hpp) against
// independent results: each line's own single-line run, the statics of a
// tree at rest, and energy conservation of a swinging tree in vacuum.
#include <gtest/gtest.h>

#include <cstdio>

#include "../support/models.hpp"
#include "../support/networks.hpp"
#include "../support/physics.hpp"
#include "towsim/sim/network_discretisation.hpp"
#include "towsim/sim/simulate_network.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

using testing::body_energy;
using testing::cable_energy;
using testing::cable_model;
using testing::CableSpec;
using testing::Energy;
using testing::network_of;
using testing::rk4;

/// Largest |a - b| over the samples' nodes, relative to the largest |a| [-].
double node_difference(const std::vector<Sample>& a, const std::vector<NetworkSample>& b, std::size_t line) {
  double diff = 0, scale = 0;
  for (std::size_t j = 0; j < a.size(); ++j)
    for (std::size_t k = 0; k < a[j].node_pos.size(); ++k) {
      diff = std::max(diff, (a[j].node_pos[k] - b[j].lines[line].node_pos[k]).norm());
      scale = std::max(scale, a[j].node_pos[k].norm());
    }
  return diff / scale;
}

double force_difference(const std::vector<Sample>& a, const std::vector<NetworkSample>& b, std::size_t line) {
  double diff = 0, scale = 0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    diff = std::max(diff, (a[j].tow_force - b[j].lines[line].tow_force).norm());
    scale = std::max(scale, a[j].tow_force.norm());
  }
  return diff / scale;
}

// Two lines that touch only through the prescribed vessel: the network's
// run gives each line's own run. Fixed-step rk4 acts row by row on the
// flat state, so the same arithmetic gives the same bits; the tolerance
// (1e-13 of the largest value) only allows for round-off in another order.
TEST(NetworkRun, LinesJoinedOnlyThroughTheVesselGiveTheirSingleLineRuns) {
  Model a = testing::paper52_turn(10, 30);
  Model b = cable_model(testing::paper52_cable(6, 20, 0.01));
  b.tow = a.tow;
  rk4(a, 30, 0.01);
  rk4(b, 30, 0.01);
  const std::vector<Sample> ra = testing::run(a), rb = testing::run(b);
  const Network net = network_of({a, b}, {LineTop{}, LineTop{}});
  NetworkMemorySink sink;
  const RunStats st = simulate_network(net, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  ASSERT_EQ(sink.samples.size(), ra.size());
  constexpr double kRoundOff = 1e-13;  // relative: the same operations per line
  std::printf("[measured] rk4: nodes %.2e, %.2e, tow force %.2e, %.2e of their peaks\n",
              node_difference(ra, sink.samples, 0), node_difference(rb, sink.samples, 1),
              force_difference(ra, sink.samples, 0), force_difference(rb, sink.samples, 1));
  EXPECT_LE(node_difference(ra, sink.samples, 0), kRoundOff);
  EXPECT_LE(node_difference(rb, sink.samples, 1), kRoundOff);
  EXPECT_LE(force_difference(ra, sink.samples, 0), kRoundOff);
  EXPECT_LE(force_difference(rb, sink.samples, 1), kRoundOff);
  // Rosenbrock-W controls one step for both lines: each within its tolerance of its own run.
  for (Model* m : {&a, &b}) m->sim.integrator = Integrator::Rosenbrock, m->sim.tolerance = 1e-7;
  const std::vector<Sample> qa = testing::run(a), qb = testing::run(b);
  const Network net2 = network_of({a, b}, {LineTop{}, LineTop{}});
  NetworkMemorySink sink2;
  ASSERT_EQ(simulate_network(net2, sink2).status, "ok");
  std::printf("[measured] rosenbrock 1e-7: tow force %.2e, %.2e of their peaks\n",
              force_difference(qa, sink2.samples, 0), force_difference(qb, sink2.samples, 1));
  constexpr double kTolerance = 1e-5;  // a hundred times the tolerance: both runs' errors against the exact one
  EXPECT_LE(force_difference(qa, sink2.samples, 0), kTolerance);
  EXPECT_LE(force_difference(qb, sink2.samples, 1), kTolerance);
}

/// A tree of every kind of node: a root line to a junction (a 2 kg point
/// mass), a free line and a line to a sphere below the junction, and a
/// free line hanging from a point of the sphere. rho: the water's density.
Network every_node_tree(double rho) {
  CableSpec c;
  c.mass_per_length = 1.2;
  c.n = 5, c.length = 10;
  Model root = cable_model(c, rho);
  Attachment junction;
  junction.joint = root.cable.n(), junction.at = c.length, junction.mass = 2.0, junction.volume = 5e-4;
  root.cable.attachments.push_back(junction);
  c.n = 4, c.length = 6;
  Model free_line = cable_model(c, rho);
  c.n = 3, c.length = 5;
  Model body_line = cable_model(c, rho);
  testing::add_sphere_body(body_line, 20.0, 0.1);
  c.n = 2, c.length = 3;
  Model tail = cable_model(c, rho);
  return network_of({root, free_line, body_line, tail},
                    {LineTop{}, LineTop{0, -1, Vec3::Zero()}, LineTop{0, -1, Vec3::Zero()},
                     LineTop{2, 0, Vec3(0, 0, -0.1)}});
}

/// Apparent weight of everything in the network [N].
double apparent_weight(const Network& net) {
  double w = 0;
  for (const Model& m : net.tree.lines) {
    for (const Element& el : m.cable.elements) w += el.weight;
    for (const Attachment& a : m.cable.attachments) w += (a.mass - m.fluid.rho * a.volume) * m.fluid.g;
    for (const Body& b : m.bodies) w += (b.mass - m.fluid.rho * b.displaced_volume) * m.fluid.g;
  }
  return w;
}

// At rest, hanging: the vessel carries the whole tree's apparent weight
// and nothing moves. The hanging start is the equilibrium, so the
// tolerances are round-off of the sums (1e-10 relative) and of 10 s of
// steps from it (1e-9 m).
TEST(NetworkRun, ATreeAtRestHangsInEquilibrium) {
  Network net = every_node_tree(1025);
  for (Model& m : net.tree.lines) rk4(m, 10, 0.01);
  NetworkMemorySink sink;
  const RunStats st = simulate_network(net, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  const double W = apparent_weight(net);
  for (const NetworkSample& s : sink.samples) {
    EXPECT_NEAR(s.lines[0].tow_force.z(), W, 1e-10 * W) << "t = " << s.t;
    for (std::size_t i = 0; i < s.lines.size(); ++i)
      for (std::size_t k = 0; k < s.lines[i].node_pos.size(); ++k)
        EXPECT_LE((s.lines[i].node_pos[k] - sink.samples.front().lines[i].node_pos[k]).norm(), 1e-9);
  }
  // Each line's top is its node: the junction and the sphere's point.
  const NetworkSample& s = sink.samples.back();
  EXPECT_LE((s.lines[1].node_pos.front() - s.lines[0].node_pos.back()).norm(), 1e-12);
  EXPECT_LE((s.lines[2].node_pos.front() - s.lines[0].node_pos.back()).norm(), 1e-12);
}

/// Total energy of the network's sample in vacuum [J]: the lines, the
/// junction (an attachment at a line's end) and the bodies.
double energy(const Network& net, const NetworkSample& s) {
  double E = 0;
  for (std::size_t i = 0; i < net.tree.lines.size(); ++i) {
    const Model& m = net.tree.lines[i];
    E += cable_energy(m, s.lines[i]).total();
    for (const Attachment& a : m.cable.attachments) {
      const std::size_t k = static_cast<std::size_t>(a.joint);
      E += 0.5 * a.mass * s.lines[i].node_vel[k].squaredNorm() + a.mass * m.fluid.g * s.lines[i].node_pos[k].z();
    }
    if (!m.bodies.empty()) E += body_energy(m, s.lines[i]).total();
  }
  return E;
}

// Without fluid, a tree released from a tilted start swings with its
// energy conserved: a check of the tree's coupling at the nodes (a wrong
// node force does work). rk4 at 1 ms conserves it to 2e-10 of the energy
// swing here; the tolerance 1e-6 of the potential energy change is a
// thousand times that.
TEST(NetworkRun, ASwingingTreeInVacuumConservesEnergy) {
  Network net = every_node_tree(0.0);
  for (Model& m : net.tree.lines) {
    rk4(m, 4, 0.001);
    m.initial.kind = Initial::Kind::Direction;
    m.initial.direction = Vec3(1, 0.3, -1).normalized();
  }
  NetworkMemorySink sink;
  const RunStats st = simulate_network(net, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  const double E0 = energy(net, sink.samples.front());
  double swing = 0, drift = 0;
  for (const NetworkSample& s : sink.samples) {
    double kinetic = 0;
    for (std::size_t i = 0; i < net.tree.lines.size(); ++i)
      kinetic += cable_energy(net.tree.lines[i], s.lines[i]).kinetic;
    swing = std::max(swing, kinetic);
    drift = std::max(drift, std::abs(energy(net, s) - E0));
  }
  std::printf("[measured] energy drift %.2e J over a kinetic energy of up to %.3g J\n", drift, swing);
  ASSERT_GT(swing, 10.0);  // it does swing [J]
  EXPECT_LE(drift, 1e-6 * swing);
}

// ---------------------------------------------------------------------------
// The steady start of a network (network_steady_state: the tree's own
// dynamics relaxed in the tow's frame) against an independent formulation:
// two lines joined only through the vessel, towed at 1.5 m/s, a cable with
// a 20 kg sphere and a free cable, are each their own chain's steady tow
// from solve_statics (Newton on the chain's recursion, converged to
// 1e-12 rad/s^2). The relaxation stops when every joint moves by less than
// kNetworkSettledSpeed = 1e-6 m/s; over the slowest mode's time (~10 s
// here) that leaves the shape within ~1e-5 m: measured element directions
// within 6.0e-7 and tow forces within 1.8e-6 relative (181 s relaxed, 2638
// steps). Checked to 1e-5 (the directions, rad) and 1e-5 (the forces,
// relative): the settled speed times the slowest mode's 10 s, relative to
// the 20-30 m lines.
// ---------------------------------------------------------------------------
TEST(NetworkSteady, LinesJoinedOnlyThroughTheVesselAreEachTheirOwnStatics) {
  const Vec3 V(1.5, 0, 0);
  Model a = cable_model(testing::paper52_cable(10, 30));
  testing::add_sphere_body(a, 20.0, 0.15, 0.5, 0.5);
  Model b = cable_model(testing::paper52_cable(6, 20, 0.01));
  b.tow.start = Vec3(0, 5, 0);
  for (Model* m : {&a, &b}) {
    m->tow.mode = Tow::Mode::Motion;
    m->tow.pieces = {testing::ramp_piece(Vec3::UnitX(), V.norm(), 0.0)};
    finalize_tow(m->tow);
    m->initial.kind = Initial::Kind::Steady;
  }
  const StaticsResult sa = solve_statics(a, V), sb = solve_statics(b, V);
  ASSERT_TRUE(sa.converged && sb.converged) << sa.message << " / " << sb.message;
  const Network net = network_of({a, b}, {LineTop{}, LineTop{}});
  const NetworkSteady st = network_steady_state(net);
  EXPECT_LT((st.velocity - V).norm(), 1e-12);
  ASSERT_EQ(st.state.size(), 2u);
  // Tow forces: one evaluation of the tree at the steady state.
  TreeWorkspace ws(net.tree);
  tree_forward_dynamics(net.tree, st.state, 0.0, ws);
  double de = 0, df = 0;
  const StaticsResult* ref[2] = {&sa, &sb};
  for (std::size_t i = 0; i < 2; ++i) {
    for (std::size_t k = 0; k < ref[i]->state.e.size(); ++k)
      de = std::max(de, (st.state[i].e[k] - ref[i]->state.e[k]).norm());
    df = std::max(df, (ws.lines[i].acc.tow_force - ref[i]->tow_force).norm() / ref[i]->tow_force.norm());
  }
  std::printf(
      "[measured] steady network vs chain statics: directions %.2e, tow forces %.2e relative; relaxed %.0f s "
      "in %ld steps, joints left at %.1e m/s\n",
      de, df, st.relaxed_time, st.steps, st.residual_speed);
  EXPECT_LT(st.residual_speed, kNetworkSettledSpeed);
  EXPECT_LT(de, 1e-5);
  EXPECT_LT(df, 1e-5);
  // Every point moves with the tow: no rates.
  for (const PhysicalState& s : st.state) {
    EXPECT_LT((s.v0 - V).norm(), 1e-12);
    for (const Vec3& w : s.w) EXPECT_EQ(w.norm(), 0.0);
  }
}

// A cable dragged over a flat bottom with friction (300 m over 110 m at
// 0.5 m/s, mu 0.5, a 20 kg clump at its middle), as a tree: a line from the
// vessel to a junction (the clump) and a line on from it. The network's
// steady tow relaxes in the tow's frame, where the bottom moves at -V;
// against the chain's Newton statics of the same cable: directions 1e-5,
// tow force 1e-5 relative (the relaxation stops at 1e-6 m/s). A run from
// that start keeps it: after 20 s the tow force within 1e-4 of it.
TEST(NetworkSteady, ACableDraggedOverTheBottomIsItsChainsStatics) {
  const double U = 0.5;
  CableSpec cs;
  cs.n = 30, cs.length = 300, cs.tangential = 0;
  auto on_bottom = [&](Model& m) {
    m.seabed = Seabed::flat(110, 1e5, 1e3, 0.5);
    m.tow.mode = Tow::Mode::Motion;
    m.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), U, 0.0)};
    finalize_tow(m.tow);
    m.initial.kind = Initial::Kind::Steady;
    m.sim.integrator = Integrator::Rosenbrock;
    m.sim.duration = 20;
    m.sim.output_interval = 1;
  };
  const Attachment clump{15, 150.0, 20.0, 0.002, 0.05, 2.0};
  Model chain = cable_model(cs);
  chain.cable.attachments.push_back(clump);
  on_bottom(chain);
  const StaticsResult ref = solve_statics(chain, Vec3(U, 0, 0));
  ASSERT_TRUE(ref.converged) << ref.message;
  cs.n = 15, cs.length = 150;
  Model upper = cable_model(cs), lower = cable_model(cs);
  upper.cable.attachments.push_back(clump);
  on_bottom(upper);
  on_bottom(lower);
  const Network net = network_of({upper, lower}, {LineTop{}, LineTop{0, -1, Vec3::Zero()}});
  const NetworkSteady st = network_steady_state(net);
  TreeWorkspace ws(net.tree);
  tree_forward_dynamics(net.tree, st.state, 0.0, ws);
  double de = 0;
  for (std::size_t k = 0; k < 30; ++k) de = std::max(de, (st.state[k < 15 ? 0 : 1].e[k % 15] - ref.state.e[k]).norm());
  const double df = (ws.lines[0].acc.tow_force - ref.tow_force).norm() / ref.tow_force.norm();
  // The run from it.
  NetworkMemorySink sink;
  const RunStats run = simulate_network(net, sink);
  ASSERT_EQ(run.status, "ok") << run.message;
  const double drift = (sink.samples.back().lines[0].tow_force - sink.samples.front().lines[0].tow_force).norm() /
                       ref.tow_force.norm();
  std::printf(
      "[measured] dragged over the bottom: steady network vs chain statics: directions %.2e, tow force %.2e "
      "(T = %.3f N, %.0f m lying); relaxed %.0f s; after 20 s of the run: %.2e\n",
      de, df, ref.tow_force.norm(), ref.sample.lying_length, st.relaxed_time, drift);
  EXPECT_GT(ref.sample.lying_length, 100.0);  // the lower line lies on the bottom
  EXPECT_LT(de, 1e-5);
  EXPECT_LT(df, 1e-5);
  EXPECT_LT(drift, 1e-4);
  // The element count's share of the error, from two such steady tows,
  // against Richardson on the chain's two Newton statics (n and 2n, without
  // the touchdown joint the chain's own estimate adds: the network's
  // relaxation has none): 1e-5 absolute, as for the lines in open water
  // (NetworkDiscretisation.*).
  const DiscretisationEstimate dn = estimate_network_discretisation(net);
  ASSERT_TRUE(dn.available()) << dn.message;
  const StaticsResult cn = solve_statics(chain, Vec3(U, 0, 0)),
                      c2n = solve_statics(refined_model(chain, 2), Vec3(U, 0, 0));
  ASSERT_TRUE(cn.converged && c2n.converged);
  const double Tn = cn.tow_force.norm(), T2n = c2n.tow_force.norm();
  const double dc = std::abs(Tn - T2n) / (1 - std::pow(2.0, -kDiscretisationOrder)) / Tn;
  std::printf("[measured] dragged over the bottom: discretisation estimate network %.6e, chain %.6e\n", dn.estimate,
              dc);
  EXPECT_NEAR(dn.estimate, dc, 1e-5);
}

// ---------------------------------------------------------------------------
// The element count's share of a network's error
// (estimate_network_discretisation: Richardson on two relaxed steady tows)
// against the chains' own (estimate_discretisation_error: Newton statics of
// each line): the two lines of the steady test above, joined only through
// the vessel, give the larger of the two lines' estimates. Checked to 1e-5
// absolute: each relaxed tension is within ~2e-6 of its Newton value
// (above), so a difference of two, over 1 - 2^-2, is within ~5e-6. Line b
// ends in a 5 kg sphere here: its free end at 12 elements whips in the flow
// (a limit cycle at 0.5 m/s, which the relaxation reports as no steady tow;
// Newton's statics finds the unstable equilibrium).
// ---------------------------------------------------------------------------
TEST(NetworkDiscretisation, LinesJoinedOnlyThroughTheVesselGiveTheirChainsEstimate) {
  Model a = cable_model(testing::paper52_cable(10, 30));
  testing::add_sphere_body(a, 20.0, 0.15, 0.5, 0.5);
  Model b = cable_model(testing::paper52_cable(6, 20, 0.01));
  testing::add_sphere_body(b, 5.0, 0.1, 0.5, 0.5);
  b.tow.start = Vec3(0, 5, 0);
  for (Model* m : {&a, &b}) {
    m->tow.mode = Tow::Mode::Motion;
    m->tow.pieces = {testing::ramp_piece(Vec3::UnitX(), 1.5, 0.0)};
    finalize_tow(m->tow);
  }
  const DiscretisationEstimate da = estimate_discretisation_error(a), db = estimate_discretisation_error(b);
  ASSERT_TRUE(da.available() && db.available()) << da.message << " / " << db.message;
  const DiscretisationEstimate dn = estimate_network_discretisation(network_of({a, b}, {LineTop{}, LineTop{}}));
  ASSERT_TRUE(dn.available()) << dn.message;
  const double chains = std::max(da.estimate, db.estimate);
  std::printf("[measured] discretisation estimate: network %.6e, chains %.6e and %.6e\n", dn.estimate, da.estimate,
              db.estimate);
  EXPECT_NEAR(dn.estimate, chains, 1e-5);
  EXPECT_EQ(dn.elements, 16);
}

// Above kNetworkEstimateMaxElements elements in all the estimate is not
// made (its relaxations' cost grows as the square of the count), and says
// so: two lines of 126 elements, 252 in all.
TEST(NetworkDiscretisation, LargeNetworkIsNotEstimatedAndSaysWhy) {
  Model a = cable_model(testing::paper52_cable(126, 126));
  a.tow.mode = Tow::Mode::Motion;
  a.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), 1.5, 0.0)};
  finalize_tow(a.tow);
  Model b = a;
  b.tow.start = Vec3(0, 5, 0);
  finalize_tow(b.tow);
  const DiscretisationEstimate d = estimate_network_discretisation(network_of({a, b}, {LineTop{}, LineTop{}}));
  EXPECT_FALSE(d.available());
  EXPECT_EQ(d.elements, 252);
  EXPECT_EQ(d.message,
            "not made above 250 elements (this network has 252; its two steady tows by relaxation would cost more "
            "than the run: towsim statics on the network with its elements doubled gives the refined tensions)");
}

// ---------------------------------------------------------------------------
// A jump of the tow velocity on a tree with nodes (NetworkSystem's
// apply_tow_jump: the tree's impulsive response) against the dynamics: the
// tree of every node towed at 1 m/s from rest, once by a jump at t = 0 and
// once by a ramp over eps (a continuous law, integrated), both by rk4 at
// eps / 100 to t = 2 eps. As eps -> 0 the ramp's response tends to the
// impulse: the finite loads (gravity, drag) and the lag of the ramp add
// O(eps) to the joint velocities. eps = 1, 0.5, 0.25 ms (much steeper
// ramps put the difference quotient at the ramp's end above the round-off
// jump, which is then applied): measured differences 7.5e-4, 4.1e-4,
// 2.1e-4 m/s, orders 0.89, 0.98 (0.72 from 2 ms: pre-asymptotic). Checked:
// each order 1 within 0.15, and the difference at 0.25 ms below 5e-4 m/s
// (0.05 % of the jump).
// ---------------------------------------------------------------------------
TEST(NetworkJump, TreeImpulseIsTheLimitOfSteeperRamps) {
  auto last_velocities = [](double ramp, double eps) {
    Network net = every_node_tree(1025);
    Model& root = net.tree.lines[0];
    root.tow.mode = Tow::Mode::Motion;
    root.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), 1.0, ramp)};
    finalize_tow(root.tow);
    for (Model& m : net.tree.lines) rk4(m, 2 * eps, eps / 100), m.sim.output_interval = 2 * eps;
    NetworkMemorySink sink;
    const RunStats st = simulate_network(net, sink);
    EXPECT_EQ(st.status, "ok") << st.message;
    return sink.samples.back();
  };
  std::vector<double> diffs;
  for (double eps : {1e-3, 5e-4, 2.5e-4}) {
    const NetworkSample a = last_velocities(0.0, eps), b = last_velocities(eps, eps);
    double diff = 0;
    for (std::size_t i = 0; i < a.lines.size(); ++i)
      for (std::size_t k = 0; k < a.lines[i].node_vel.size(); ++k)
        diff = std::max(diff, (a.lines[i].node_vel[k] - b.lines[i].node_vel[k]).norm());
    std::printf("[measured] tree impulse vs a %.0e s ramp: joint velocities %.2e m/s apart\n", eps, diff);
    diffs.push_back(diff);
  }
  for (std::size_t i = 0; i + 1 < diffs.size(); ++i) EXPECT_NEAR(std::log2(diffs[i] / diffs[i + 1]), 1.0, 0.15);
  EXPECT_LT(diffs.back(), 5e-4);
}

}  // namespace
}  // namespace towsim
