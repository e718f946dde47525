// Trees of lines (towsim/dynamics/tree.hpp): the one sweep run line by line
// and joined at the nodes, against the dense Newton-Euler + multiplier
// reference (tests/support/kkt_reference.hpp) on a branched tree, and
// against the chain it reduces to.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <utility>

#include "../support/kkt_reference.hpp"
#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/tree.hpp"
#include "towsim/model/winch.hpp"

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

/// Every kind of node and line: a main line from the vessel to the rich
/// body; below the body, from two of its points, a line to a junction (a
/// point mass with volume, drag and added mass) and an elastic line with an
/// attachment; below the junction a line to a sphere and a free line; and a
/// second line from the vessel, on its own.
TreeModel branched_tree() {
  TreeModel tree;
  Model main = line(4, 60, 4.0, 0.03);
  testing::add_rich_body(main);
  Model to_junction = line(3, 18, 0.8, 0.012);
  to_junction.cable.attachments.push_back({3, 18.0, 5.0, 0.001, 0.02, 1.0});  // the junction
  Model elastic = line(4, 20, 0.6, 0.01);
  for (Element& el : elastic.cable.elements) el.axial_stiffness = 3e5, el.axial_damping = 900;
  elastic.cable.attachments.push_back({2, 10.0, 2.0, 0.004, 0.03, 2.0});
  Model to_sphere = line(2, 8, 0.5, 0.01);
  testing::add_sphere_body(to_sphere, 6.0, 0.1);
  Model free_end = line(3, 9, 0.5, 0.01);
  Model second = line(3, 30, 1.5, 0.019);
  for (Model* m : {&main, &second}) m->tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  second.tow.start = Vec3(-5, 8, 2);
  tree.lines = {main, to_junction, elastic, to_sphere, free_end, second};
  tree.tops = {LineTop{},
               LineTop{0, 0, Vec3(-0.5, 0.3, -0.2)},
               LineTop{0, 0, Vec3(-0.6, -0.3, -0.1)},
               LineTop{1, -1, Vec3::Zero()},
               LineTop{1, -1, Vec3::Zero()},
               LineTop{}};
  return tree;
}

/// A chain of 7 elements with a sphere at its end and an attachment at joint
/// 4, and the same chain as a tree: cut at joint 4 into two lines joined by
/// a junction (the attachment at the upper line's end).
std::pair<Model, TreeModel> cut_chain() {
  Model chain = line(7, 70, 1.5, 0.019);
  testing::add_sphere_body(chain, 8.0, 0.12);
  chain.cable.attachments.push_back({4, 40.0, 12.0, 0.002, 0.04, 3.0});
  chain.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  Model upper = line(4, 40, 1.5, 0.019), lower = line(3, 30, 1.5, 0.019);
  upper.cable.attachments.push_back({4, 40.0, 12.0, 0.002, 0.04, 3.0});
  testing::add_sphere_body(lower, 8.0, 0.12);
  upper.tow = chain.tow;
  return {chain, TreeModel{{upper, lower}, {LineTop{}, LineTop{0, -1, Vec3::Zero()}}, {}}};
}

/// A random state of each line; the roots on their tow law at t; elastic
/// elements strained by -0.3 % (slack) to +0.7 %.
TreeState random_tree_state(const TreeModel& tree, std::mt19937& rng, double t) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  TreeState s;
  for (const Model& m : tree.lines) {
    PhysicalState ps = testing::random_state(m, rng);
    for (std::size_t k = 0; k < ps.length.size(); ++k) {
      if (!is_elastic(m.cable.elements[k])) continue;
      ps.length[k] = m.cable.elements[k].length * (1.002 + 0.005 * U(rng));
      ps.length_rate[k] = 0.3 * U(rng);
    }
    const TowKinematics k = tow_kinematics(m.tow, t);
    ps.r0 = k.pos, ps.v0 = k.vel;
    s.push_back(ps);
  }
  return s;
}

/// Random stage right-hand sides for each line (increments of the rates and
/// rotation vectors of the positions; lengths for elastic elements).
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

/// A chain's right-hand side as its pieces for a tree whose lines are the
/// chain's runs [first[l], first[l] + elements of line l) and whose bodies are
/// the chain's, in order.
std::vector<StageRhs> split_rhs(const StageRhs& r, const TreeModel& tree) {
  std::vector<StageRhs> out(tree.lines.size());
  std::size_t k0 = 0, b0 = 0;
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    const std::size_t n = tree.lines[l].cable.elements.size(), nb = tree.lines[l].bodies.size();
    for (std::size_t k = k0; k < k0 + n; ++k) {
      out[l].dw.push_back(r.dw[k]), out[l].rot.push_back(r.rot[k]);
      out[l].dl.push_back(r.dl[k]), out[l].dlr.push_back(r.dlr[k]);
    }
    for (std::size_t b = b0; b < b0 + nb; ++b) out[l].dwb.push_back(r.dwb[b]), out[l].rotb.push_back(r.rotb[b]);
    k0 += n, b0 += nb;
  }
  return out;
}

/// A chain's state as the pieces of that tree (as split_rhs).
TreeState split_state(const PhysicalState& s, const TreeModel& tree) {
  TreeState out;
  std::size_t k0 = 0, b0 = 0;
  for (const Model& m : tree.lines) {
    PhysicalState p = PhysicalState::hanging(m);
    const std::size_t n = m.cable.elements.size(), nb = m.bodies.size();
    for (std::size_t k = 0; k < n; ++k) p.e[k] = s.e[k0 + k], p.w[k] = s.w[k0 + k];
    for (std::size_t b = 0; b < nb; ++b) p.bodies[b] = s.bodies[b0 + b];
    k0 += n, b0 += nb;
    out.push_back(p);
  }
  out[0].r0 = s.r0, out[0].v0 = s.v0;
  return out;
}

/// Largest difference between the chain's and the tree's accelerations
/// (forward dynamics) and stage increments, each relative to the chain's
/// largest: {alpha, alpha_b, stage alpha, stage alpha_b}.
std::array<double, 4> chain_against_tree(const Model& chain, const PhysicalState& s, const TreeModel& tree, double t,
                                         std::mt19937& rng) {
  Workspace wc(chain);
  forward_dynamics(chain, s, t, wc);
  const TreeState ts = split_state(s, tree);
  TreeWorkspace wt(tree);
  tree_forward_dynamics(tree, ts, t, wt);
  // The stage solve at hg = 0.05 s on a random right-hand side.
  const double hg = 0.05;
  ImplicitWorkspace ic(chain);
  local_jacobian(chain, s, wc, t, ic.jac);
  TreeModel one{{chain}, {LineTop{}}, {}};
  const StageRhs rc = random_rhs(one, rng)[0];
  implicit_stage_solve(chain, s, wc, hg, rc, ic);
  TreeImplicitWorkspace it(tree, wt);
  tree_local_jacobian(tree, ts, wt, t, it);
  tree_stage_solve(tree, ts, wt, hg, split_rhs(rc, tree), it);
  std::array<double, 4> err{}, scale{};
  std::size_t k0 = 0, b0 = 0;
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    for (std::size_t k = 0; k < tree.lines[l].cable.elements.size(); ++k) {
      scale[0] = std::max(scale[0], wc.acc.alpha[k0 + k].norm());
      err[0] = std::max(err[0], (wt.lines[l].acc.alpha[k] - wc.acc.alpha[k0 + k]).norm());
      scale[2] = std::max(scale[2], ic.alpha[k0 + k].norm());
      err[2] = std::max(err[2], (it.lines[l].alpha[k] - ic.alpha[k0 + k]).norm());
    }
    for (std::size_t b = 0; b < tree.lines[l].bodies.size(); ++b) {
      scale[1] = std::max(scale[1], wc.acc.alpha_b[b0 + b].norm());
      err[1] = std::max(err[1], (wt.lines[l].acc.alpha_b[b] - wc.acc.alpha_b[b0 + b]).norm());
      scale[3] = std::max(scale[3], ic.alpha_b[b0 + b].norm());
      err[3] = std::max(err[3], (it.lines[l].alpha_b[b] - ic.alpha_b[b0 + b]).norm());
    }
    k0 += tree.lines[l].cable.elements.size(), b0 += tree.lines[l].bodies.size();
  }
  for (int i = 0; i < 4; ++i) err[i] /= scale[i];
  return err;
}

/// Largest differences of the tree's forward dynamics from the KKT
/// solution of the whole tree over 4 random states at t, each relative to
/// its largest value: {forces, angular accelerations, length (and pay-out)
/// accelerations}. A winch on line 0: its top element between 0.6 and 1.4
/// of its nominal length, paid out at up to 0.8 m/s.
std::array<double, 3> tree_against_reference(const TreeModel& tree, std::mt19937& rng, double t) {
  TreeWorkspace ws(tree);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::array<double, 3> worst{};
  for (int trial = 0; trial < 4; ++trial) {
    TreeState s = random_tree_state(tree, rng, t);
    const Model& m0 = tree.lines[0];
    if (m0.winch.active()) {
      s[0].length[0] = m0.cable.elements[0].length * (1.0 + 0.4 * U(rng));
      s[0].length_rate[0] = 0.8 * U(rng);
    }
    tree_forward_dynamics(tree, s, t, ws);
    std::vector<Vec3> a0;
    for (const Model& m : tree.lines) a0.push_back(tow_kinematics(m.tow, t).acc);
    const testing::KktReference ref(tree, s, ws, a0, t);
    double fs = 1, as = 1, ls = 1, ef = 0, ea = 0, el = 0;
    for (std::size_t l = 0; l < tree.lines.size(); ++l) {
      const Accelerations& acc = ws.lines[l].acc;
      for (const Vec3& f : acc.joint_force) fs = std::max(fs, f.norm());
      for (const Vec3& a : acc.alpha) as = std::max(as, a.norm());
      for (const double a : acc.length_acc) ls = std::max(ls, std::abs(a));
      ef = std::max(ef, (acc.tow_force - ref.force(ref.joint_of_node[l][0])).norm());
      for (std::size_t j = 1; j < acc.joint_force.size(); ++j) {
        const std::size_t rj = ref.joint_of_node[l][j];
        ef = std::max(ef, (acc.joint_force[j] - (rj == ref.kNone ? Vec3::Zero() : ref.force(rj))).norm());
      }
      for (std::size_t b = 0; b < tree.lines[l].bodies.size(); ++b) {
        ef = std::max(ef, (acc.link_force[b] - ref.force(ref.upper_link[l][b])).norm());
        ea = std::max(ea, (acc.alpha_b[b] - ref.alpha_body(b, l)).norm());
      }
      for (std::size_t e = 0; e < acc.alpha.size(); ++e) {
        ea = std::max(ea, (acc.alpha[e] - ref.alpha(e, l)).norm());
        el = std::max(el, std::abs(acc.length_acc[e] - ref.length_acc(e, l)));
      }
    }
    // The winch's pay-out acceleration (imposed, or the drum's).
    if (m0.winch.active()) el = std::max(el, std::abs(ws.lines[0].acc.top_length_acc - ref.pay_acc()));
    worst[0] = std::max(worst[0], ef / fs);
    worst[1] = std::max(worst[1], ea / as);
    worst[2] = std::max(worst[2], el / ls);
  }
  return worst;
}

// Every acceleration and force of every line equals the KKT solution of the
// whole tree. Tolerance 1e-9 relative to the largest force (and angular and
// length acceleration), as for the chains (test_chain_reference.cpp): the
// dense LU of ~250 unknowns loses ~1e-10; a wrong node term shows at 1e-5
// or more (breaking the body's child centripetal term or a line's top force
// fails it).
TEST(TreeReference, BranchedTreeEqualsDenseMultiplierSolution) {
  std::mt19937 rng(2027);
  const auto worst = tree_against_reference(branched_tree(), rng, 4.2);
  std::printf(
      "[measured] tree of 6 lines (a body with two lines below, a junction with two, an elastic line, two roots): "
      "force rel err %.2e, alpha rel err %.2e, length acc rel err %.2e\n",
      worst[0], worst[1], worst[2]);
  EXPECT_LT(worst[0], 1e-9);
  EXPECT_LT(worst[1], 1e-9);
  EXPECT_LT(worst[2], 1e-9);
}

// The same tree with a winch on its main line (a network's winch: on a line
// from the vessel), length-controlled and tension-controlled: the paid-out
// top element and the drum carry the whole tree below. Same tolerances.
TEST(TreeReference, WinchOnARootLineEqualsDenseMultiplierSolution) {
  for (const Winch::Mode mode : {Winch::Mode::Imposed, Winch::Mode::Tension}) {
    TreeModel tree = branched_tree();
    Model& m = tree.lines[0];
    m.cable.sections.push_back({"cable", 0, m.cable.n(), 60.0, 0});
    m.winch.mode = mode;
    m.winch.nominal_length = m.cable.elements[0].length;
    if (mode == Winch::Mode::Imposed) {
      m.winch.schedule = schedule_from_rate({0, 10}, {0.2, 1.2}, 60.0, 0, m.winch.max_length);
    } else {
      m.winch.tension = 1500;     // [N]
      m.winch.drum_inertia = 80;  // [kg]
      m.winch.damping = 300;      // [N s/m]
    }
    std::mt19937 rng(2029);
    const auto worst = tree_against_reference(tree, rng, 4.2);
    std::printf("[measured] the tree with a%s winch on its main line: force %.2e, alpha %.2e, length acc %.2e\n",
                mode == Winch::Mode::Imposed ? "n imposed" : " tension", worst[0], worst[1], worst[2]);
    EXPECT_LT(worst[0], 1e-9);
    EXPECT_LT(worst[1], 1e-9);
    EXPECT_LT(worst[2], 1e-9);
  }
}

// Lines that hang only from the vessel are independent chains: each line's
// accelerations and forces are its own forward_dynamics', bit for bit.
TEST(TreeReference, LinesFromTheVesselAloneAreTheirChainsBitForBit) {
  TreeModel tree = branched_tree();
  tree.lines = {tree.lines[0], tree.lines[5]};
  tree.tops = {LineTop{}, LineTop{}};
  TreeWorkspace ws(tree);
  std::mt19937 rng(11);
  const TreeState s = random_tree_state(tree, rng, 7.0);
  tree_forward_dynamics(tree, s, 7.0, ws);
  for (std::size_t l = 0; l < 2; ++l) {
    Workspace alone(tree.lines[l]);
    forward_dynamics(tree.lines[l], s[l], 7.0, alone);
    EXPECT_EQ(alone.acc.tow_force, ws.lines[l].acc.tow_force);
    EXPECT_EQ(alone.acc.alpha, ws.lines[l].acc.alpha);
    EXPECT_EQ(alone.acc.joint_force, ws.lines[l].acc.joint_force);
    EXPECT_EQ(alone.acc.alpha_b, ws.lines[l].acc.alpha_b);
  }
}

// A chain cut at a joint into two lines joined by a junction (the
// attachment at that joint) is the same system: the elements' angular
// accelerations and the joint forces below the junction agree with the
// chain's to round-off. Tolerance 1e-12 relative: the same operations,
// summed in another order at the junction only.
TEST(TreeReference, ChainCutAtAJunctionIsTheSameChain) {
  const auto [chain, tree] = cut_chain();
  std::mt19937 rng(5);
  PhysicalState s = testing::random_state(chain, rng);
  const TowKinematics k = tow_kinematics(chain.tow, 3.0);
  s.r0 = k.pos, s.v0 = k.vel;
  TreeState ts(2);
  ts[0] = PhysicalState::hanging(tree.lines[0]), ts[1] = PhysicalState::hanging(tree.lines[1]);
  ts[0].r0 = s.r0, ts[0].v0 = s.v0;
  for (std::size_t i = 0; i < 7; ++i) {
    PhysicalState& p = i < 4 ? ts[0] : ts[1];
    p.e[i < 4 ? i : i - 4] = s.e[i], p.w[i < 4 ? i : i - 4] = s.w[i];
  }
  ts[1].bodies = s.bodies;
  Workspace wc(chain);
  forward_dynamics(chain, s, 3.0, wc);
  TreeWorkspace wt(tree);
  tree_forward_dynamics(tree, ts, 3.0, wt);
  double scale_a = 0, scale_f = 0, err_a = 0, err_f = 0;
  for (std::size_t i = 0; i < 7; ++i) {
    const Vec3& a = i < 4 ? wt.lines[0].acc.alpha[i] : wt.lines[1].acc.alpha[i - 4];
    scale_a = std::max(scale_a, wc.acc.alpha[i].norm());
    err_a = std::max(err_a, (a - wc.acc.alpha[i]).norm());
  }
  for (std::size_t j = 5; j <= 7; ++j) {
    scale_f = std::max(scale_f, wc.acc.joint_force[j].norm());
    err_f = std::max(err_f, (wt.lines[1].acc.joint_force[j - 4] - wc.acc.joint_force[j]).norm());
  }
  err_f = std::max(err_f, (wt.lines[1].acc.link_force[0] - wc.acc.link_force[0]).norm());
  std::printf("[measured] chain cut at a junction: alpha rel err %.2e, force rel err %.2e\n", err_a / scale_a,
              err_f / scale_f);
  EXPECT_LT(err_a, 1e-12 * scale_a);
  EXPECT_LT(err_f, 1e-12 * scale_f);
  EXPECT_LT((wt.lines[1].acc.alpha_b[0] - wc.acc.alpha_b[0]).norm(), 1e-12 * wc.acc.alpha_b[0].norm());
}

// Lines that hang only from the vessel are independent chains: each line's
// stage solve is its own implicit_stage_solve, bit for bit.
TEST(TreeStageSolve, LinesFromTheVesselAloneAreTheirChainsBitForBit) {
  TreeModel tree = branched_tree();
  tree.lines = {tree.lines[0], tree.lines[5]};
  tree.tops = {LineTop{}, LineTop{}};
  TreeWorkspace ws(tree);
  std::mt19937 rng(12);
  const TreeState s = random_tree_state(tree, rng, 7.0);
  tree_forward_dynamics(tree, s, 7.0, ws);
  TreeImplicitWorkspace iw(tree, ws);
  tree_local_jacobian(tree, s, ws, 7.0, iw);
  const std::vector<StageRhs> r = random_rhs(tree, rng);
  tree_stage_solve(tree, s, ws, 0.04, r, iw);
  for (std::size_t l = 0; l < 2; ++l) {
    Workspace alone(tree.lines[l]);
    forward_dynamics(tree.lines[l], s[l], 7.0, alone);
    ImplicitWorkspace ia(tree.lines[l]);
    local_jacobian(tree.lines[l], s[l], alone, 7.0, ia.jac);
    implicit_stage_solve(tree.lines[l], s[l], alone, 0.04, r[l], ia);
    EXPECT_EQ(ia.alpha, iw.lines[l].alpha);
    EXPECT_EQ(ia.alpha_b, iw.lines[l].alpha_b);
    EXPECT_EQ(ia.a0, iw.lines[l].a0);
  }
}

// A chain with an in-line body, and the same chain as a tree (the upper
// section to the body, the lower section from the body's lower link point):
// a body carrying a line at a point is the in-line body's algebra. The
// elements' and the bodies' angular accelerations, and the stage solve's
// increments, agree to round-off. Tolerance 1e-12 relative: the same
// operations in another order at the body.
TEST(TreeStageSolve, InlineBodyAsATreeIsTheSameChain) {
  Model chain = testing::two_part_model(5, 4);
  chain.cable.attachments.clear();
  chain.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  Model upper = chain, lower = chain;
  upper.cable.elements.resize(5);
  upper.bodies.resize(1);
  upper.bodies[0].inline_body = false;
  upper.bodies[0].joint = -1;
  lower.cable.elements.erase(lower.cable.elements.begin(), lower.cable.elements.begin() + 5);
  lower.bodies.erase(lower.bodies.begin());
  const TreeModel tree{{upper, lower}, {LineTop{}, LineTop{0, 0, chain.bodies[0].lower_link_point}}, {}};
  std::mt19937 rng(21);
  PhysicalState s = testing::random_state(chain, rng);
  const TowKinematics k = tow_kinematics(chain.tow, 3.0);
  s.r0 = k.pos, s.v0 = k.vel;
  const auto err = chain_against_tree(chain, s, tree, 3.0, rng);
  std::printf("[measured] in-line body as a tree: alpha %.2e, alpha_b %.2e, stage alpha %.2e, stage alpha_b %.2e\n",
              err[0], err[1], err[2], err[3]);
  for (const double e : err) EXPECT_LT(e, 1e-12);
}

// The chain cut at a junction (the attachment at the cut), in the stage
// solve as in the forward dynamics (ChainCutAtAJunctionIsTheSameChain).
TEST(TreeStageSolve, ChainCutAtAJunctionIsTheSameChain) {
  const auto [chain, tree] = cut_chain();
  std::mt19937 rng(6);
  PhysicalState s = testing::random_state(chain, rng);
  const TowKinematics k = tow_kinematics(chain.tow, 3.0);
  s.r0 = k.pos, s.v0 = k.vel;
  const auto err = chain_against_tree(chain, s, tree, 3.0, rng);
  std::printf("[measured] chain cut at a junction: alpha %.2e, alpha_b %.2e, stage alpha %.2e, stage alpha_b %.2e\n",
              err[0], err[1], err[2], err[3]);
  for (const double e : err) EXPECT_LT(e, 1e-12);
}

}  // namespace
}  // namespace towsim
