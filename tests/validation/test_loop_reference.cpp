// Loops over a tree of lines (TreeModel::loops, docs/theory.md §5.7
// "Loops"): the closing ball joints' multipliers in the forward dynamics and
// in the Rosenbrock stage solve, against the dense Newton-Euler +
// multiplier reference with the loops' rows (tests/support/kkt_reference.hpp),
// and tree_close_loops.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "../support/kkt_reference.hpp"
#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/tree.hpp"

namespace towsim {
namespace {

/// A cable of n elements over `length` [m], in a sheared current.
Model line(int n, double length, double mass_per_length, double diameter) {
  testing::CableSpec c;
  c.n = n;
  c.length = length;
  c.mass_per_length = mass_per_length;
  c.diameter = diameter;
  c.tangential = 0.02;
  Model m = testing::cable_model(c);
  m.fluid.current_depth = {0, 40, 300};
  m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.4, 0.1, 0), Vec3(0.1, 0, 0)};
  return m;
}

void make_elastic(Model& m) {
  for (Element& el : m.cable.elements) el.axial_stiffness = 3e5, el.axial_damping = 900;
}

/// A bridle: a main line from the vessel to a junction; from the junction
/// two legs to two points of one body: leg 1 (a heavy section, an in-line
/// body, a light section, the rich body at its end) in the tree, leg 2
/// (elastic) closing the loop on the end body's point.
TreeModel bridle() {
  TreeModel tree;
  Model main = line(4, 40, 1.5, 0.019);
  main.cable.attachments.push_back({4, 40.0, 12.0, 0.002, 0.04, 3.0});  // the junction
  main.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  Model leg1 = testing::two_part_model(2, 2);
  leg1.cable.attachments.clear();
  leg1.bodies.pop_back();  // the end sphere: the rich body instead
  testing::add_rich_body(leg1);
  Model leg2 = line(5, 60, 0.6, 0.01);
  make_elastic(leg2);
  tree.lines = {main, leg1, leg2};
  tree.tops = {LineTop{}, LineTop{0, -1, Vec3::Zero()}, LineTop{0, -1, Vec3::Zero()}};
  tree.loops = {LoopJoint{2, 1, 1, Vec3(-0.6, 0.1, 0.15)}};
  return tree;
}

/// A loop closing on a junction: two lines from two tow points meeting at
/// one junction (the first line's cable end), a line to a sphere below it.
TreeModel junction_loop() {
  TreeModel tree;
  Model a = line(4, 40, 1.5, 0.019);
  a.cable.attachments.push_back({4, 40.0, 12.0, 0.002, 0.04, 3.0});
  Model b = line(5, 50, 0.8, 0.012);
  make_elastic(b);
  for (Model* m : {&a, &b}) m->tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  b.tow.start = Vec3(-5, 8, 2);
  Model below = line(3, 12, 0.5, 0.01);
  testing::add_sphere_body(below, 6.0, 0.1);
  tree.lines = {a, b, below};
  tree.tops = {LineTop{}, LineTop{}, LineTop{0, -1, Vec3::Zero()}};
  tree.loops = {LoopJoint{1, 0, -1, Vec3::Zero()}};
  return tree;
}

/// Two loops: the bridle, and a second line from the vessel closing on its junction.
TreeModel two_loops() {
  TreeModel tree = bridle();
  Model second = line(5, 50, 0.8, 0.012);
  second.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  second.tow.start = Vec3(-5, 8, 2);
  tree.lines.push_back(second);
  tree.tops.push_back(LineTop{});
  tree.loops.push_back(LoopJoint{3, 0, -1, Vec3::Zero()});
  return tree;
}

/// A random state of each line, the roots on their tow law at t, elastic
/// elements strained by +0.2 % to +0.7 %, then closed onto the loops.
TreeState closed_state(const TreeModel& tree, std::mt19937& rng, double t) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  TreeState s;
  for (const Model& m : tree.lines) {
    PhysicalState ps = testing::random_state(m, rng);
    for (std::size_t k = 0; k < ps.length.size(); ++k) {
      if (!is_elastic(m.cable.elements[k])) continue;
      ps.length[k] = m.cable.elements[k].length * (1.0045 + 0.0025 * U(rng));
      ps.length_rate[k] = 0.3 * U(rng);
    }
    const TowKinematics k = tow_kinematics(m.tow, t);
    ps.r0 = k.pos, ps.v0 = k.vel;
    s.push_back(ps);
  }
  const double gap = tree_close_loops(tree, s);
  EXPECT_LT(gap, 1e-12);
  return s;
}

/// The loops' gaps: position, velocity, and the acceleration ws holds [m], [m/s], [m/s^2].
struct Gaps {
  double x = 0, v = 0, a = 0;
};
Gaps loop_gaps(const TreeModel& tree, const TreeWorkspace& ws) {
  Gaps g;
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    const Workspace& a = ws.lines[static_cast<std::size_t>(lp.line)];
    const Workspace& n = ws.lines[static_cast<std::size_t>(lp.node_line)];
    Vec3 x = n.P.back(), v = n.vP.back(), acc = n.acc.end_acc;
    if (lp.body >= 0) {
      const BodyWork& bw = n.body[static_cast<std::size_t>(lp.body)];
      const BodyChild& c = bw.children[static_cast<std::size_t>(ws.loop_slot[j])];
      x = bw.O + c.r, v = bw.vO + bw.w.cross(c.r), acc = c.a;
    }
    g.x = std::max(g.x, (a.P.back() - x).norm());
    g.v = std::max(g.v, (a.vP.back() - v).norm());
    g.a = std::max(g.a, (a.acc.end_acc - acc).norm());
  }
  return g;
}

/// Largest differences from the KKT reference, each relative to the
/// recursion's largest: {force, alpha, length acceleration, loop force}.
struct Errors {
  double force = 0, alpha = 0, length = 0, loop = 0;
  void max(const Errors& o) {
    force = std::max(force, o.force), alpha = std::max(alpha, o.alpha);
    length = std::max(length, o.length), loop = std::max(loop, o.loop);
  }
};

Errors against_reference(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double t) {
  std::vector<Vec3> a0;
  for (const Model& m : tree.lines) a0.push_back(tow_kinematics(m.tow, t).acc);
  const testing::KktReference ref(tree, s, ws, a0, t);
  double fs = 1, as = 1, ls = 1;
  Errors e;
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    const Accelerations& acc = ws.lines[l].acc;
    for (const Vec3& f : acc.joint_force) fs = std::max(fs, f.norm());
    for (const Vec3& a : acc.alpha) as = std::max(as, a.norm());
    for (const double a : acc.length_acc) ls = std::max(ls, std::abs(a));
  }
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    const Accelerations& acc = ws.lines[l].acc;
    const std::size_t n = acc.joint_force.size() - 1;
    e.force = std::max(e.force, (acc.tow_force - ref.force(ref.joint_of_node[l][0])).norm());
    for (std::size_t j = 1; j <= n; ++j) {
      const std::size_t rj = ref.joint_of_node[l][j];
      Vec3 expected = rj == ref.kNone ? Vec3::Zero() : ref.force(rj);
      // A loop's cable end (free in the tree): the force through it onto its node.
      for (std::size_t k = 0; k < tree.loops.size(); ++k)
        if (j == n && rj == ref.kNone && static_cast<std::size_t>(tree.loops[k].line) == l)
          expected = -ref.loop_force(k);
      e.force = std::max(e.force, (acc.joint_force[j] - expected).norm());
    }
    for (std::size_t b = 0; b < tree.lines[l].bodies.size(); ++b) {
      e.force = std::max(e.force, (acc.link_force[b] - ref.force(ref.upper_link[l][b])).norm());
      e.alpha = std::max(e.alpha, (acc.alpha_b[b] - ref.alpha_body(b, l)).norm());
    }
    for (std::size_t k = 0; k < acc.alpha.size(); ++k) {
      e.alpha = std::max(e.alpha, (acc.alpha[k] - ref.alpha(k, l)).norm());
      e.length = std::max(e.length, std::abs(acc.length_acc[k] - ref.length_acc(k, l)));
    }
  }
  for (std::size_t k = 0; k < tree.loops.size(); ++k)
    e.loop = std::max(e.loop, (ws.loop_force[k] - ref.loop_force(k)).norm());
  e.force /= fs, e.alpha /= as, e.length /= ls, e.loop /= fs;
  return e;
}

// Forward dynamics with loops: every acceleration, joint force and loop
// force of every line equals the KKT solution of the whole tree with the
// loops' rows, on closed random states of each topology. Tolerance 1e-12
// relative to the largest: round-off, the dense LU of ~200-300 unknowns and
// the probe sweeps (responses differenced against the free sweep) measured
// below 1.2e-14 here, a margin of ~100. The wrong sign of the loop force on
// a body's point fails by 0.1 to 3. The loops' acceleration gaps: below
// 1e-10 m/s^2 (measured 5e-12: round-off of accelerations of order 10-100
// m/s^2 through G's solve).
TEST(LoopReference, ForwardDynamicsEqualsDenseMultiplierSolution) {
  const double t = 4.2;  // [s]
  const std::pair<const char*, TreeModel> cases[] = {{"bridle", bridle()},
                                                     {"junction loop", junction_loop()},
                                                     {"two loops", two_loops()}};
  for (const auto& [name, tree] : cases) {
    TreeWorkspace ws(tree);
    std::mt19937 rng(2031);
    Errors worst;
    Gaps worst_gap;
    for (int trial = 0; trial < 3; ++trial) {
      const TreeState s = closed_state(tree, rng, t);
      tree_forward_dynamics(tree, s, t, ws);
      worst.max(against_reference(tree, s, ws, t));
      const Gaps g = loop_gaps(tree, ws);
      worst_gap.x = std::max(worst_gap.x, g.x), worst_gap.v = std::max(worst_gap.v, g.v);
      worst_gap.a = std::max(worst_gap.a, g.a);
    }
    std::printf(
        "[measured] %s: force rel err %.2e, alpha %.2e, length acc %.2e, loop force %.2e; gaps %.1e m, %.1e m/s, "
        "%.1e m/s^2\n",
        name, worst.force, worst.alpha, worst.length, worst.loop, worst_gap.x, worst_gap.v, worst_gap.a);
    EXPECT_LT(worst.force, 1e-12) << name;
    EXPECT_LT(worst.alpha, 1e-12) << name;
    EXPECT_LT(worst.length, 1e-12) << name;
    EXPECT_LT(worst.loop, 1e-12) << name;
    EXPECT_LT(worst_gap.x, 1e-12) << name;
    EXPECT_LT(worst_gap.v, 1e-12) << name;
    EXPECT_LT(worst_gap.a, 1e-10) << name;
  }
}

// MODEL.md §10's bridle at rest: a body (a 50 kg sphere, its CG and
// centre of buoyancy at its centre) hung from a junction by two legs of
// length a (one element each, near massless) to its points (-b, 0, 0) and
// (b, 0, 0), below a vertical main line from a tow point at rest in still
// water: each leg's tension is W / (2 cos(asin(b/a))), W the body's
// apparent weight. Tolerance 1e-6 relative: the legs' own apparent weight
// (5e-5 N against W = 448 N; measured 3.6e-8) and round-off; the body and
// junction do not accelerate (below 1e-6 m/s^2, rad/s^2; measured 7e-10).
TEST(LoopReference, BridleAtRestHasTheStaticLegTensions) {
  const double a = 5, b = 3;  // leg length, half the points' spacing [m]
  auto still = [](int n, double length, double mpl, double d) {
    Model m = line(n, length, mpl, d);
    m.fluid.current_depth.clear(), m.fluid.current_velocity.clear();
    return m;
  };
  Model main = still(3, 30, 1.5, 0.019);
  main.cable.attachments.push_back({3, 30.0, 12.0, 0.002, 0.04, 3.0});  // the junction
  Model leg1 = still(1, a, 1e-6, 1e-5), leg2 = still(1, a, 1e-6, 1e-5);
  testing::add_sphere_body(leg1, 50.0, 0.1);
  leg1.bodies[0].link_point = Vec3(-b, 0, 0);
  TreeModel tree;
  tree.lines = {main, leg1, leg2};
  tree.tops = {LineTop{}, LineTop{0, -1, Vec3::Zero()}, LineTop{0, -1, Vec3::Zero()}};
  tree.loops = {LoopJoint{2, 1, 0, Vec3(b, 0, 0)}};
  TreeState s;
  for (const Model& m : tree.lines) s.push_back(PhysicalState::hanging(m));
  const double th = std::asin(b / a);
  s[1].e[0] = Vec3(-std::sin(th), 0, -std::cos(th)), s[2].e[0] = Vec3(std::sin(th), 0, -std::cos(th));
  s[0].r0 = tow_kinematics(main.tow, 0.0).pos;
  TreeWorkspace ws(tree);
  tree_forward_dynamics(tree, s, 0.0, ws);
  const Gaps g = loop_gaps(tree, ws);
  const double W = -ws.lines[1].body[0].Fb.z();  // apparent weight [N]
  const double expected = W / (2 * std::cos(th));
  const double t1 = ws.lines[1].acc.link_force[0].norm(), t2 = ws.loop_force[0].norm();
  const double acc = std::max(
      {ws.lines[1].acc.alpha_b[0].norm(), ws.lines[0].acc.end_acc.norm(), ws.lines[1].acc.end_acc.norm()});
  std::printf("[measured] bridle at rest: W %.3f N, leg tensions %.9f, %.9f N (expected %.9f), gap %.1e m, acc %.1e\n",
              W, t1, t2, expected, g.x, acc);
  EXPECT_LT(g.x, 1e-12);
  EXPECT_NEAR(t1, expected, 1e-6 * expected);
  EXPECT_NEAR(t2, expected, 1e-6 * expected);
  EXPECT_LT(acc, 1e-6);
}

/// Random stage right-hand sides for each line (as test_tree_reference.cpp's).
std::vector<StageRhs> random_rhs(const TreeModel& tree, std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  auto rnd = [&] { return Vec3(N(rng), N(rng), N(rng)); };
  std::vector<StageRhs> r(tree.lines.size());
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    const std::size_t n = tree.lines[l].cable.elements.size(), nb = tree.lines[l].bodies.size();
    for (std::size_t k = 0; k < n; ++k) r[l].dw.push_back(0.1 * rnd()), r[l].rot.push_back(0.01 * rnd());
    for (std::size_t b = 0; b < nb; ++b) r[l].dwb.push_back(0.1 * rnd()), r[l].rotb.push_back(0.01 * rnd());
    for (std::size_t k = 0; k < n; ++k) r[l].dl.push_back(1e-3 * N(rng)), r[l].dlr.push_back(1e-2 * N(rng));
  }
  return r;
}

/// The stage solve at hg against the dense stage system (KktReference's
/// stage form, the loops' rows included): {alpha and alpha_b, l' increments,
/// loop impulses} relative to the recursion's largest, and the loops' gap
/// increment [m/s].
std::array<double, 4> stage_against_reference(const TreeModel& tree, const TreeState& s, double t, double hg,
                                              std::mt19937& rng) {
  TreeWorkspace ws(tree);
  tree_forward_dynamics(tree, s, t, ws);
  TreeImplicitWorkspace iw(tree, ws);
  tree_local_jacobian(tree, s, ws, t, iw);
  tree_stage_solve(tree, s, ws, hg, random_rhs(tree, rng), iw);
  const testing::KktReference ref(tree, s, ws, iw, hg);
  double as = 1e-300, ls = 1e-300, ms = 1e-300;
  std::array<double, 4> e{};
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    const ImplicitWorkspace& w = iw.lines[l];
    for (std::size_t k = 0; k < w.alpha.size(); ++k) {
      as = std::max(as, w.alpha[k].norm()), ls = std::max(ls, std::abs(w.zl[k]));
      e[0] = std::max(e[0], (w.alpha[k] - ref.alpha(k, l)).norm());
      e[1] = std::max(e[1], std::abs(w.zl[k] - ref.length_acc(k, l)));
    }
    for (std::size_t b = 0; b < w.alpha_b.size(); ++b) {
      as = std::max(as, w.alpha_b[b].norm());
      e[0] = std::max(e[0], (w.alpha_b[b] - ref.alpha_body(b, l)).norm());
    }
  }
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    ms = std::max(ms, iw.loop_impulse[j].norm());
    e[2] = std::max(e[2], (iw.loop_impulse[j] - ref.loop_force(j)).norm());
    const ImplicitWorkspace& node = iw.lines[static_cast<std::size_t>(lp.node_line)];
    const Vec3& a =
        lp.body < 0
            ? node.end.a
            : node.body_children[static_cast<std::size_t>(lp.body)][static_cast<std::size_t>(ws.loop_slot[j])].a;
    e[3] = std::max(e[3], (iw.lines[static_cast<std::size_t>(lp.line)].end.a - a).norm());
  }
  e[0] /= as, e[1] /= ls, e[2] /= ms;
  return e;
}

// The stage solve with loops: the increments z of every line and the
// loops' impulses equal the dense stage system's (M + hg C + hg^2 K with
// the loops' rows J z = 0, its right-hand side the loads pass's), at two
// steps hg. Tolerance 1e-10 relative: round-off of a dense system whose
// elastic rows carry (hg)^2 EA / L ~ 1e3-1e4 times their mass at hg = 0.5 s
// (measured below 1.5e-12, with or without the loops). The loops' gap
// increment J z: below 1e-12 m/s (measured 4e-14; the stage's increments
// are of order 0.1-1 m/s). The same trees without their loops check the dense
// stage system itself (the tree's stage solve without loops is checked
// against chains in test_tree_reference.cpp).
TEST(LoopStageSolve, EqualsDenseStageSystemWithLoopRows) {
  const double t = 4.2;  // [s]
  const std::pair<const char*, TreeModel> cases[] = {{"bridle", bridle()},
                                                     {"junction loop", junction_loop()},
                                                     {"two loops", two_loops()}};
  for (const auto& [name, tree] : cases) {
    std::mt19937 rng(77);
    for (const double hg : {0.02, 0.5}) {
      std::array<double, 4> worst{}, worst_free{};
      for (int trial = 0; trial < 2; ++trial) {
        const TreeState s = closed_state(tree, rng, t);
        const auto e = stage_against_reference(tree, s, t, hg, rng);
        TreeModel open = tree;
        open.loops.clear();
        const auto f = stage_against_reference(open, s, t, hg, rng);
        for (int i = 0; i < 4; ++i) worst[i] = std::max(worst[i], e[i]), worst_free[i] = std::max(worst_free[i], f[i]);
      }
      std::printf(
          "[measured] stage %s, hg %.2f s: z rel err %.2e, l' %.2e, loop impulse %.2e, gap %.1e m/s (without the "
          "loops: z %.2e, l' %.2e)\n",
          name, hg, worst[0], worst[1], worst[2], worst[3], worst_free[0], worst_free[1]);
      EXPECT_LT(worst[0], 1e-10) << name;
      EXPECT_LT(worst[1], 1e-10) << name;
      EXPECT_LT(worst[2], 1e-10) << name;
      EXPECT_LT(worst[3], 1e-12) << name;
      EXPECT_LT(worst_free[0], 1e-10) << name;
      EXPECT_LT(worst_free[1], 1e-10) << name;
    }
  }
}

// tree_close_loops from a perturbed closed state (directions and attitudes
// turned by ~1e-3 rad, angular velocities moved by ~0.05 rad/s): the gaps
// close to 1e-12 m (Gauss-Newton: quadratic, a few steps), the velocity gaps
// to round-off (1e-12 m/s: one linear projection of velocities of order 1
// m/s), the directions stay unit vectors and the angular velocities normal
// to them.
// The tree's impulsive response to a jump of the tow velocities
// (tree_tow_velocity_jump, loops closed by impulses) is the tree's
// acceleration at rest without finite loads and with the roots accelerated
// by the jumps: the same tree without gravity (no weight, no buoyancy; the
// added mass stays), at zero velocity (no drag), its tow laws accelerating
// by dv, in still water (no drag at rest), its elements weightless (their
// weight is compiled with g), through tree_forward_dynamics, which the
// dense multiplier reference above checks. Rigid lines here (an elastic line's finite tension is no
// impulse but would be a load). To round-off: 1e-12 of the largest jump.
TEST(LoopImpulse, TowVelocityJumpIsTheUnloadedSweepAtRest) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (TreeModel tree : {bridle(), junction_loop(), two_loops()}) {
    for (Model& m : tree.lines)
      for (Element& el : m.cable.elements) el.axial_stiffness = 0, el.axial_damping = 0;
    TreeState s = closed_state(tree, rng, 3.0);
    for (PhysicalState& p : s) {
      p.v0.setZero();
      for (Vec3& w : p.w) w.setZero();
      for (BodyState& b : p.bodies) b.w.setZero();
    }
    std::vector<Vec3> dv(tree.lines.size(), Vec3::Zero());
    TreeModel ref = tree;
    for (std::size_t i = 0; i < tree.lines.size(); ++i) {
      Model& m = ref.lines[i];
      m.fluid.g = 0;
      m.fluid.current_depth.clear(), m.fluid.current_velocity.clear();  // no drag at rest
      for (Element& el : m.cable.elements) el.weight = 0;               // compiled with g
      if (tree.tops[i].line >= 0) continue;
      dv[i] = Vec3(U(rng), U(rng), U(rng));
      const Vec3 r0 = s[i].r0;
      m.tow.pieces = {testing::ramp_piece(dv[i].normalized(), 2 * dv[i].norm(), 2.0)};  // accelerating by dv
      m.tow.start = r0 - 0.25 * dv[i];  // at t = 1 s it is at r0 (the ramp's half-way: dv t^2 / 2 behind)
      finalize_tow(m.tow);
    }
    TreeWorkspace ws(tree), wr(ref);
    tree_tow_velocity_jump(tree, s, dv, ws);
    tree_forward_dynamics(ref, s, 1.0, wr);
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < tree.lines.size(); ++i) {
      const Accelerations &a = ws.lines[i].acc, &b = wr.lines[i].acc;
      for (std::size_t k = 0; k < a.alpha.size(); ++k)
        diff = std::max(diff, (a.alpha[k] - b.alpha[k]).norm()), scale = std::max(scale, a.alpha[k].norm());
      for (std::size_t k = 0; k < a.alpha_b.size(); ++k)
        diff = std::max(diff, (a.alpha_b[k] - b.alpha_b[k]).norm()), scale = std::max(scale, a.alpha_b[k].norm());
    }
    std::printf("[measured] tow velocity jump vs the unloaded sweep at rest: %.2e of %.3e rad/s\n", diff, scale);
    ASSERT_GT(scale, 0);
    EXPECT_LT(diff, 1e-12 * scale);
  }
}

TEST(LoopClose, PerturbedClosedStateClosesToRoundOff) {
  const double t = 4.2;  // [s]
  const std::pair<const char*, TreeModel> cases[] = {{"bridle", bridle()},
                                                     {"junction loop", junction_loop()},
                                                     {"two loops", two_loops()}};
  for (const auto& [name, tree] : cases) {
    std::mt19937 rng(9);
    std::normal_distribution<double> N(0.0, 1.0);
    auto rnd = [&] { return Vec3(N(rng), N(rng), N(rng)); };
    TreeState s = closed_state(tree, rng, t);
    TreeWorkspace ws(tree);
    tree_forward_dynamics(tree, s, t, ws);
    const Gaps before = loop_gaps(tree, ws);
    for (PhysicalState& p : s) {
      for (std::size_t k = 0; k < p.e.size(); ++k) {
        p.e[k] = (p.e[k] + 1e-3 * rnd()).normalized();
        p.w[k] += 0.05 * rnd();
        p.w[k] -= p.w[k].dot(p.e[k]) * p.e[k];
      }
      for (BodyState& b : p.bodies) {
        const Vec3 th = 1e-3 * rnd();
        b.q = (Quat(Eigen::AngleAxisd(th.norm(), th.normalized())) * b.q).normalized();
        b.w += 0.05 * rnd();
      }
    }
    tree_forward_dynamics(tree, s, t, ws);
    const Gaps perturbed = loop_gaps(tree, ws);
    const double gap = tree_close_loops(tree, s);
    tree_forward_dynamics(tree, s, t, ws);
    const Gaps after = loop_gaps(tree, ws);
    double unit = 0, normal = 0;
    for (const PhysicalState& p : s)
      for (std::size_t k = 0; k < p.e.size(); ++k)
        unit = std::max(unit, std::abs(p.e[k].norm() - 1)), normal = std::max(normal, std::abs(p.w[k].dot(p.e[k])));
    std::printf(
        "[measured] close %s: closed state %.1e m, %.1e m/s; perturbed %.1e m, %.1e m/s; closed again %.1e m "
        "(returned %.1e), %.1e m/s\n",
        name, before.x, before.v, perturbed.x, perturbed.v, after.x, gap, after.v);
    EXPECT_LT(after.x, 1e-12) << name;
    EXPECT_LT(gap, 1e-12) << name;
    EXPECT_LT(after.v, 1e-12) << name;
    EXPECT_LT(unit, 1e-15) << name;
    EXPECT_LT(normal, 1e-14) << name;
  }
}

}  // namespace
}  // namespace towsim
