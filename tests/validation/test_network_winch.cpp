// A winch on a network's line (docs/scenario.md "Networks"): its pay-out,
// haul-in and tension control, with the events that split and remove the
// line's top element, against independent results: each line's own run
// (lines joined only through the vessel), the same chain run as one line
// (a chain cut at a junction into a tree is the same system), and the
// static weight of a bridled body lowered at constant speed in vacuum.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

#include "../support/models.hpp"
#include "../support/networks.hpp"
#include "../support/physics.hpp"
#include "towsim/sim/simulate_network.hpp"

namespace towsim {
namespace {

using testing::cable_model;
using testing::CableSpec;
using testing::network_of;
using testing::rk4;

/// A tension winch on the whole cable of m (n elements over `length` [m]):
/// set tension T [N], drum inertia M_d [kg], stopped at max_length [m].
void tension_winch(Model& m, int n, double length, double T, double Md, double max_length) {
  m.cable.sections.push_back({"cable", 0, n, length, 0});
  m.winch.mode = Winch::Mode::Tension;
  m.winch.tension = T;
  m.winch.drum_inertia = Md;
  m.winch.nominal_length = length / n;
  m.winch.min_length = length / n;
  m.winch.max_length = max_length;
  m.winch.max_speed = 2.0;
}

/// Largest difference of the samples' joints, tow forces and deployed
/// lengths, each relative to the largest of a's: {nodes, force, length}.
/// Every sample must have the same joints (the same events at the same steps).
std::array<double, 3> line_difference(const std::vector<Sample>& a, const std::vector<NetworkSample>& b,
                                      std::size_t line) {
  std::array<double, 3> diff{}, scale{};
  EXPECT_EQ(a.size(), b.size());
  for (std::size_t j = 0; j < a.size() && j < b.size(); ++j) {
    const Sample& x = a[j];
    const Sample& y = b[j].lines[line];
    EXPECT_EQ(x.node_pos.size(), y.node_pos.size()) << "t = " << x.t;
    for (std::size_t k = 0; k < x.node_pos.size() && k < y.node_pos.size(); ++k) {
      diff[0] = std::max(diff[0], (x.node_pos[k] - y.node_pos[k]).norm());
      scale[0] = std::max(scale[0], x.node_pos[k].norm());
    }
    diff[1] = std::max(diff[1], (x.tow_force - y.tow_force).norm());
    scale[1] = std::max(scale[1], x.tow_force.norm());
    diff[2] = std::max(diff[2], std::abs(x.deployed_length - y.deployed_length));
    scale[2] = std::max(scale[2], x.deployed_length);
  }
  for (int i = 0; i < 3; ++i) diff[i] /= scale[i];
  return diff;
}

// Two lines from the vessel, each on its own winch: the first pays out from
// rest (a speed jump at t = 0) then hauls in through a turn (its top element
// split, then removed), the second pays out under a set tension until its
// drum is full (the stop an impulse). Each line alone as a network is its
// chain's run bit for bit (fixed-step rk4 does the same arithmetic row by
// row, the events at the same steps). Together, the first line's run is
// unchanged to 1e-13 (round-off in another order); the second's steps are
// cut at the first's winch breakpoint (10 s), when its drum is held at its
// stop by an impulse after every step, so its tension moves by up to 2e-9
// of its peak there and 1e-10 after: the tolerance is 1e-8.
TEST(NetworkWinch, LinesJoinedOnlyThroughTheVesselGiveTheirSingleLineRuns) {
  Model a = testing::paper52_turn(10, 30);
  testing::impose_winch(a, 10, 30, {0, 10}, {0.5, -0.3});
  Model b = cable_model(testing::paper52_cable(6, 20, 0.01));
  b.tow = a.tow;
  tension_winch(b, 6, 20, 4.0, 5.0, 24.0);
  rk4(a, 30, 0.005);
  rk4(b, 30, 0.005);
  RunStats sa, sb;
  const std::vector<Sample> ra = testing::run(a, &sa), rb = testing::run(b, &sb);
  ASSERT_GT(sa.winch_splits, 0);
  ASSERT_GT(sa.winch_removals, 0);
  ASSERT_GT(sb.winch_splits, 0);
  ASSERT_NEAR(rb.back().deployed_length, 24.0, 1e-9);  // the drum full: stopped
  // Each line alone.
  for (const auto& [m, r] : {std::pair{&a, &ra}, std::pair{&b, &rb}}) {
    NetworkMemorySink one;
    ASSERT_EQ(simulate_network(network_of({*m}, {LineTop{}}), one).status, "ok");
    const auto d = line_difference(*r, one.samples, 0);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(d[i], 0.0);
  }
  // Both.
  const Network net = network_of({a, b}, {LineTop{}, LineTop{}});
  NetworkMemorySink sink;
  const RunStats st = simulate_network(net, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_EQ(st.winch_splits, sa.winch_splits + sb.winch_splits);
  EXPECT_EQ(st.winch_removals, sa.winch_removals + sb.winch_removals);
  const auto da = line_difference(ra, sink.samples, 0), db = line_difference(rb, sink.samples, 1);
  std::printf("[measured] %ld splits, %ld removals; nodes %.2e, %.2e, tow force %.2e, %.2e, length %.2e, %.2e\n",
              st.winch_splits, st.winch_removals, da[0], db[0], da[1], db[1], da[2], db[2]);
  constexpr double kRoundOff = 1e-13;  // relative: the same operations per line
  constexpr double kCutSteps = 1e-8;   // relative: the second line's steps cut at the first's breakpoint
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(da[i], kRoundOff);
    EXPECT_LE(db[i], kCutSteps);
  }
}

/// A chain of 7 elements on a winch, a sphere at its end and a 12 kg
/// attachment at joint 4; and the same chain as a tree, cut at joint 4 into
/// a line from the vessel on the winch down to a junction (the attachment)
/// and a line below it to the sphere.
/// `winch(L)`: the winch for a line of deployed length L (its lengths are the line's).
std::pair<Model, Network> cut_chain_on_a_winch(const std::function<Winch(double)>& winch) {
  CableSpec spec;  // 1.5 kg/m, 19 mm
  spec.n = 7, spec.length = 70;
  CableSpec upper_spec = spec, lower_spec = spec;
  upper_spec.n = 4, upper_spec.length = 40;
  lower_spec.n = 3, lower_spec.length = 30;
  Model chain = cable_model(spec), upper = cable_model(upper_spec), lower = cable_model(lower_spec);
  testing::add_sphere_body(chain, 8.0, 0.12);
  testing::add_sphere_body(lower, 8.0, 0.12);
  chain.cable.attachments.push_back({4, 40.0, 12.0, 0.002, 0.04, 3.0});
  upper.cable.attachments.push_back({4, 40.0, 12.0, 0.002, 0.04, 3.0});
  chain.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 1.5, 10.0));
  upper.tow = chain.tow;
  // The winch on the top section: 4 elements of 10 m in both.
  chain.cable.sections.push_back({"top", 0, 4, 40, 0});
  chain.cable.sections.push_back({"bottom", 4, 3, 30, 0});
  upper.cable.sections.push_back({"top", 0, 4, 40, 0});
  chain.winch = winch(70), upper.winch = winch(40);
  for (Model* m : {&chain, &upper, &lower}) rk4(*m, 30, 0.002);
  return {chain, network_of({upper, lower}, {LineTop{}, LineTop{0, -1, Vec3::Zero()}})};
}

/// The cut chain's run against the chain's: the tree's joints are the
/// chain's (the upper line's, then the lower line's below its top).
void expect_cut_chain_is_the_chain(const std::function<Winch(double)>& winch, const char* what) {
  const auto [chain, net] = cut_chain_on_a_winch(winch);
  RunStats sc;
  const std::vector<Sample> rc = testing::run(chain, &sc);
  NetworkMemorySink sink;
  const RunStats st = simulate_network(net, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_EQ(st.winch_splits, sc.winch_splits);
  EXPECT_EQ(st.winch_removals, sc.winch_removals);
  ASSERT_EQ(sink.samples.size(), rc.size());
  double dn = 0, sn = 0, df = 0, sf = 0;
  for (std::size_t j = 0; j < rc.size(); ++j) {
    const Sample& c = rc[j];
    const Sample& up = sink.samples[j].lines[0];
    const Sample& lo = sink.samples[j].lines[1];
    ASSERT_EQ(up.node_pos.size() + lo.node_pos.size() - 1, c.node_pos.size()) << "t = " << c.t;
    for (std::size_t k = 0; k < c.node_pos.size(); ++k) {
      const Vec3& p = k < up.node_pos.size() ? up.node_pos[k] : lo.node_pos[k - up.node_pos.size() + 1];
      dn = std::max(dn, (p - c.node_pos[k]).norm()), sn = std::max(sn, c.node_pos[k].norm());
    }
    df = std::max(df, (up.tow_force - c.tow_force).norm()), sf = std::max(sf, c.tow_force.norm());
  }
  std::printf(
      "[measured] %s: %ld splits, %ld removals; nodes %.2e, tow force %.2e of their peaks; removals' energy %.6g J "
      "(chain %.6g J)\n",
      what, st.winch_splits, st.winch_removals, dn / sn, df / sf, st.winch_energy_lost, sc.winch_energy_lost);
  // The removals' kinetic energy change, the tree's against the chain's:
  // 1e-6 relative (the states agree to 1e-10, the energies are sums over the tree).
  EXPECT_NEAR(st.winch_energy_lost, sc.winch_energy_lost, 1e-6 * std::abs(sc.winch_energy_lost) + 1e-12);
  // The same system summed in another order at the junction (1e-12 per
  // evaluation, ChainCutAtAJunctionIsTheSameChain), over the steps of a
  // swinging chain (15000 steps): 1e-9 relative.
  constexpr double kRoundOff = 1e-9;
  EXPECT_LE(dn, kRoundOff * sn);
  EXPECT_LE(df, kRoundOff * sf);
}

// The winch's events in a tree: a split moves the joints below the top
// element down the line, a removal's impulse runs through the whole tree
// (the line carries the junction and the line below it), a tension winch's
// stop likewise. The tree gives the chain's run to round-off.
TEST(NetworkWinch, AChainCutAtAJunctionIsTheSameChainThroughItsWinchEvents) {
  // 1.5 m/s out for 15 s, then in: deployed 70 -> 92.5 -> 70 m (the line 40 -> 62.5 -> 40 m).
  const auto payout = [](double L) {
    Winch w;
    w.mode = Winch::Mode::Imposed;
    w.nominal_length = 10;
    w.min_length = L - 25;
    w.schedule = schedule_from_rate({0, 15}, {1.5, -1.5}, L, w.min_length, w.max_length);
    return w;
  };
  expect_cut_chain_is_the_chain(payout, "pay-out then haul-in");
  // 900 N set under ~1000 N of weight: paid out until the drum holds 10 m more.
  const auto tension = [](double L) {
    Winch w;
    w.mode = Winch::Mode::Tension;
    w.tension = 900;
    w.drum_inertia = 300;
    w.damping = 100;
    w.nominal_length = 10;
    w.min_length = L - 25;
    w.max_length = L + 10;
    return w;
  };
  expect_cut_chain_is_the_chain(tension, "tension winch to its stop");
  const auto [chain, net] = cut_chain_on_a_winch(tension);
  (void)net;
  EXPECT_NEAR(testing::run(chain).back().deployed_length, 80, 1e-9);  // the stop was reached: 70 + 10 m
}

// A body on a bridle (a junction, two rigid legs of length a to hull
// points 2b apart: a loop) lowered by the winch at a constant speed c in
// vacuum: everything moves at c, so the winch carries the weight of all
// that hangs, g (m' L(t) + M_junction + 2 m' a + M_body), with
// L(t) = L0 + c t, and each leg half of the body's and the legs' weight.
// Raising likewise (the top element removed as it comes in); with rk4 and
// with the Rosenbrock-W (the winch's rows and the loop in its stage solve).
// Tolerance 1e-9 relative: sums of a few hundred terms, the loop closed to
// 1e-12 m; the motion is uniform, so no time-step error.
TEST(NetworkWinch, ABridledBodyLoweredAtConstantSpeedHangsByItsWeight) {
  const double g = 9.81, mpl = 1.5, a = 3.0, b = 1.0, zp = 0.3, Mj = 5.0, Mb = 200.0, L0 = 40;
  const double sn = b / a, cs = std::sqrt(1 - sn * sn);
  for (const Integrator integ : {Integrator::RK4, Integrator::Rosenbrock})
    for (const double c : {0.8, -0.8}) {
      CableSpec spec;
      spec.mass_per_length = mpl, spec.cd = 0, spec.n = 8, spec.length = L0;
      Model main = cable_model(spec, 0.0, g);
      main.cable.attachments.push_back({8, L0, Mj, 0, 0, 0});
      testing::impose_winch(main, 8, L0, {0.0}, {c});
      // One element per leg: straight, so the start is the equilibrium.
      spec.n = 1, spec.length = a;
      Model fwd = cable_model(spec, 0.0, g), aft = cable_model(spec, 0.0, g);
      testing::add_sphere_body(fwd, Mb, 0.3);
      fwd.bodies[0].link_point = Vec3(b, 0, zp);
      finalize_body(fwd.bodies[0], fwd.fluid);
      fwd.initial = {Initial::Kind::Direction, Vec3(sn, 0, -cs)};
      aft.initial = {Initial::Kind::Direction, Vec3(-sn, 0, -cs)};
      for (Model* m : {&main, &fwd, &aft}) rk4(*m, 20, 0.002), m->sim.integrator = integ;
      const Network net = network_of({main, fwd, aft},
                                     {LineTop{}, LineTop{0, -1, Vec3::Zero()}, LineTop{0, -1, Vec3::Zero()}},
                                     {LoopJoint{2, 1, 0, Vec3(-b, 0, zp)}});
      NetworkMemorySink sink;
      const RunStats st = simulate_network(net, sink);
      ASSERT_EQ(st.status, "ok") << st.message;
      EXPECT_GT(c > 0 ? st.winch_splits : st.winch_removals, 0);
      double worst = 0, worst_leg = 0;
      const double W_legs = g * (Mb + 2 * mpl * a);  // the body and both legs [N]
      for (const NetworkSample& ns : sink.samples) {
        if (ns.t == 0) continue;  // before the first step: at rest, the pay-out starts as an impulse
        const double L = L0 + c * ns.t;
        const double W = g * (mpl * L + Mj) + W_legs;
        worst = std::max(worst, std::abs(ns.lines[0].tow_force.z() - W) / W);
        EXPECT_NEAR(ns.lines[0].deployed_length, L, 1e-9 * L);
        for (std::size_t leg = 1; leg <= 2; ++leg)
          worst_leg = std::max(worst_leg, std::abs(ns.lines[leg].tow_force.z() - W_legs / 2) / W_legs);
      }
      std::printf("[measured] %s, bridle moved at %+.1f m/s: winch tension off the weight by %.2e, legs by %.2e\n",
                  integrator_key(integ), c, worst, worst_leg);
      EXPECT_LE(worst, 1e-9);
      EXPECT_LE(worst_leg, 1e-9);
    }
}

}  // namespace
}  // namespace towsim
