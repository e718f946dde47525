// A tree of lines: the one sweep run line by line, joined at the nodes, and
// its loops closed by one multiplier vector each (towsim/dynamics/tree.hpp,
// docs/theory.md §5.7).
#include "towsim/dynamics/tree.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "articulated.hpp"
#include "towsim/dynamics/dynamics.hpp"

namespace towsim {

namespace {

inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// The tree's entry check: every line after the one it hangs from, every
/// node a cable end or a body of that line, no winch below the vessel; each
/// loop from a cable end that carries no body to such a cable end or to a
/// body of a line.
void check_tree(const TreeModel& tree) {
  if (tree.tops.size() != tree.lines.size()) throw std::logic_error("towsim: tree: one top per line");
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    const LineTop& top = tree.tops[i];
    if (top.line < 0) continue;
    if (idx(top.line) >= i) throw std::logic_error("towsim: tree: a line must come after the line it hangs from");
    const Model& parent = tree.lines[idx(top.line)];
    if (top.body >= static_cast<int>(parent.bodies.size()))
      throw std::logic_error("towsim: tree: no such body on the line above");
    if (top.body < 0 && end_body(parent) != nullptr)
      throw std::logic_error("towsim: tree: a line hangs from a cable end that carries a body");
    if (tree.lines[i].winch.active()) throw std::logic_error("towsim: tree: a winch on a line below the vessel");
  }
  const auto nl = static_cast<int>(tree.lines.size());
  for (const LoopJoint& lp : tree.loops) {
    if (lp.line < 0 || lp.line >= nl || lp.node_line < 0 || lp.node_line >= nl)
      throw std::logic_error("towsim: tree: a loop joins no such line");
    const Model& m = tree.lines[idx(lp.line)];
    const Model& node = tree.lines[idx(lp.node_line)];
    if (m.cable.elements.empty() || end_body(m) != nullptr)
      throw std::logic_error("towsim: tree: a loop closes from a cable end without elements or with a body");
    if (lp.body >= static_cast<int>(node.bodies.size()))
      throw std::logic_error("towsim: tree: no such body for a loop");
    if (lp.body < 0 && (lp.node_line == lp.line || end_body(node) != nullptr))
      throw std::logic_error("towsim: tree: a loop closes on its own cable end or on one that carries a body");
  }
}

}  // namespace

TreeWorkspace::TreeWorkspace(const TreeModel& tree) {
  check_tree(tree);
  lines.reserve(tree.lines.size());
  for (const Model& m : tree.lines) lines.emplace_back(m);
  slot.assign(tree.lines.size(), -1);
  top.assign(tree.lines.size(), Vec3::Zero());
  top_velocity.assign(tree.lines.size(), Vec3::Zero());
  // Each node learns the lines hanging from it.
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    const LineTop& t = tree.tops[i];
    if (t.line < 0) continue;
    Workspace& parent = lines[idx(t.line)];
    if (t.body < 0) {
      parent.end_children = true;
      continue;
    }
    auto& children = parent.body[idx(t.body)].children;
    slot[i] = static_cast<int>(children.size());
    children.push_back(BodyChild{t.point});
  }
  // Each loop's two points take its force: cable ends as end loads, a
  // body's point as one more child (after the lines'); the lines from the
  // roots to them are the loops' paths.
  const std::size_t nloop = tree.loops.size();
  loop_slot.assign(nloop, -1);
  loop_force.assign(nloop, Vec3::Zero());
  if (nloop > 0) loop_path.assign(tree.lines.size(), 0);
  for (std::size_t j = 0; j < nloop; ++j) {
    const LoopJoint& lp = tree.loops[j];
    lines[idx(lp.line)].end_children = true;
    Workspace& node = lines[idx(lp.node_line)];
    if (lp.body < 0) {
      node.end_children = true;
    } else {
      auto& children = node.body[idx(lp.body)].children;
      loop_slot[j] = static_cast<int>(children.size());
      children.push_back(BodyChild{lp.point});
    }
    for (int l : {lp.line, lp.node_line})
      for (; l >= 0; l = tree.tops[idx(l)].line) loop_path[idx(l)] = 1;
  }
  const auto m = static_cast<Eigen::Index>(3 * nloop);
  loop_G.setZero(m, m);
  loop_gap.setZero(m);
  loop_lambda.setZero(m);
  loop_lu = Eigen::PartialPivLU<Eigen::MatrixXd>(m);
}

bool TreeWorkspace::fits(const TreeModel& tree) const {
  if (lines.size() != tree.lines.size() || slot.size() != tree.lines.size()) return false;
  if (loop_slot.size() != tree.loops.size()) return false;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (!lines[i].fits(tree.lines[i])) return false;
  return true;
}

namespace {

/// Kinematics down the tree: a line's top is its node's point.
void tree_kinematics(const TreeModel& tree, const TreeState& s, TreeWorkspace& ws) {
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    const LineTop& top = tree.tops[i];
    if (top.line < 0) {
      ws.top[i] = s[i].r0, ws.top_velocity[i] = s[i].v0;
    } else if (top.body < 0) {
      const Workspace& p = ws.lines[idx(top.line)];
      ws.top[i] = p.P.back(), ws.top_velocity[i] = p.vP.back();
    } else {
      const BodyWork& bw = ws.lines[idx(top.line)].body[idx(top.body)];
      const Vec3& r = bw.children[idx(ws.slot[i])].r;
      ws.top[i] = bw.O + r, ws.top_velocity[i] = bw.vO + bw.w.cross(r);
    }
    compute_kinematics(tree.lines[i], s[i], ws.top[i], ws.top_velocity[i], ws.lines[i]);
  }
}

/// Each loop's force into its two points: the line's cable end takes f (an
/// end load: -f in its end bias), its node -f (+f as a line below it would).
void apply_loop_forces(const TreeModel& tree, TreeWorkspace& ws) {
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    const Vec3& f = ws.loop_force[j];
    ws.lines[idx(lp.line)].end_b -= f;
    Workspace& node = ws.lines[idx(lp.node_line)];
    if (lp.body < 0)
      node.end_b += f;
    else
      node.body[idx(lp.body)].children[idx(ws.loop_slot[j])].b = f;
  }
}

/// Up the tree: each line's top force into its node, from the last line
/// up; path_only: the loops' paths only (the others' K_0, b_0 unchanged).
void tree_up(const TreeModel& tree, const TreeState& s, TreeWorkspace& ws, bool inertias_known, bool path_only) {
  for (auto& w : ws.lines) w.end_K.setZero(), w.end_b.setZero();
  if (!tree.loops.empty()) apply_loop_forces(tree, ws);
  for (std::size_t i = tree.lines.size(); i-- > 0;) {
    Workspace& w = ws.lines[i];
    if (!path_only || ws.loop_path[i]) chain::articulate(tree.lines[i], s[i], w, inertias_known);
    const LineTop& top = tree.tops[i];
    if (top.line < 0) continue;
    Workspace& p = ws.lines[idx(top.line)];
    if (top.body < 0) {
      p.end_K += w.K[0], p.end_b += w.b[0];
    } else {
      BodyChild& c = p.body[idx(top.body)].children[idx(ws.slot[i])];
      c.K = w.K[0], c.b = w.b[0];
    }
  }
}

/// Down the tree: each line driven at its top by its node's acceleration
/// (a root line by its tow law's, or by root_a0[i] when given: an impulse).
void tree_down(const TreeModel& tree, const TreeState& s, double t, TreeWorkspace& ws, bool path_only,
               const std::vector<Vec3>* root_a0 = nullptr) {
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    if (path_only && !ws.loop_path[i]) continue;
    const LineTop& top = tree.tops[i];
    Vec3 a0 = Vec3::Zero();
    if (top.line >= 0) {
      const Workspace& p = ws.lines[idx(top.line)];
      a0 = top.body < 0 ? p.acc.end_acc : p.body[idx(top.body)].children[idx(ws.slot[i])].a;
    } else if (root_a0 != nullptr) {
      a0 = (*root_a0)[i];
    }
    chain::accelerate(tree.lines[i], s[i], t, ws.lines[i], top.line < 0 && root_a0 == nullptr ? nullptr : &a0);
  }
}

/// Each loop's gap acceleration (its line's cable end's minus its node
/// point's), into gap (3 per loop).
void loop_gaps(const TreeModel& tree, const TreeWorkspace& ws, Eigen::Ref<Eigen::VectorXd> gap) {
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    const Workspace& node = ws.lines[idx(lp.node_line)];
    const Vec3& a_node = lp.body < 0 ? node.acc.end_acc : node.body[idx(lp.body)].children[idx(ws.loop_slot[j])].a;
    gap.segment<3>(static_cast<Eigen::Index>(3 * j)) = ws.lines[idx(lp.line)].acc.end_acc - a_node;
  }
}

/// The loops' forces and the accelerations with them (docs/theory.md §5.7
/// "Loops"): the free sweep, one probe sweep per force component along the
/// loops' paths (bias and down passes: the inertias do not depend on the
/// forces), the dense solve G lambda = -gap, the final sweep with lambda.
void solve_loops(const TreeModel& tree, const TreeState& s, double t, TreeWorkspace& ws,
                 const std::vector<Vec3>* root_a0 = nullptr) {
  const std::size_t nloop = tree.loops.size();
  // Free sweep: no loop forces.
  std::fill(ws.loop_force.begin(), ws.loop_force.end(), Vec3::Zero());
  tree_up(tree, s, ws, false, false);
  tree_down(tree, s, t, ws, false, root_a0);
  loop_gaps(tree, ws, ws.loop_gap);
  // Probe force of the size of the tree's top forces: the responses stand
  // well above the free accelerations' round-off.
  double probe = 1;  // [N]
  for (const Workspace& w : ws.lines) probe = std::max(probe, w.acc.tow_force.norm());
  for (std::size_t c = 0; c < 3 * nloop; ++c) {
    std::fill(ws.loop_force.begin(), ws.loop_force.end(), Vec3::Zero());
    ws.loop_force[c / 3][static_cast<Eigen::Index>(c % 3)] = probe;
    tree_up(tree, s, ws, true, true);
    tree_down(tree, s, t, ws, true, root_a0);
    auto col = ws.loop_G.col(static_cast<Eigen::Index>(c));
    loop_gaps(tree, ws, col);
    col = (col - ws.loop_gap) / probe;
  }
  // The multipliers: the gaps' accelerations vanish.
  ws.loop_lu.compute(ws.loop_G);
  ws.loop_lambda = ws.loop_lu.solve(-ws.loop_gap);
  for (std::size_t j = 0; j < nloop; ++j)
    ws.loop_force[j] = ws.loop_lambda.segment<3>(static_cast<Eigen::Index>(3 * j));
  tree_up(tree, s, ws, true, true);
  tree_down(tree, s, t, ws, false, root_a0);
}

}  // namespace

void tree_forward_dynamics(const TreeModel& tree, const TreeState& s, double t, TreeWorkspace& ws) {
  const std::size_t nl = tree.lines.size();
  if (!ws.fits(tree) || s.size() != nl) throw std::logic_error("towsim: tree: workspace or state does not fit");
  for (std::size_t i = 0; i < nl; ++i)
    if (s[i].e.size() != tree.lines[i].cable.elements.size() || s[i].w.size() != s[i].e.size() ||
        s[i].bodies.size() != tree.lines[i].bodies.size())
      throw std::logic_error("towsim: tree: a line's state does not fit its model");
  tree_kinematics(tree, s, ws);
  // Every line's loads, from its own kinematics.
  for (std::size_t i = 0; i < nl; ++i) compute_loads(tree.lines[i], s[i], t, ws.lines[i]);
  if (!tree.loops.empty()) return solve_loops(tree, s, t, ws);
  tree_up(tree, s, ws, false, false);
  tree_down(tree, s, t, ws, false);
}

void tree_tow_velocity_jump(const TreeModel& tree, const TreeState& s, const std::vector<Vec3>& dv, TreeWorkspace& ws) {
  const std::size_t nl = tree.lines.size();
  if (!ws.fits(tree) || s.size() != nl || dv.size() != nl)
    throw std::logic_error("towsim: tree: workspace, state or jumps do not fit");
  // The same sweep at zero velocity with zero finite loads: only inertia and
  // the joints' (and loops') impulses remain; "accelerations" are then
  // velocity jumps (as the chain's tow_velocity_jump).
  TreeState s0 = s;
  for (PhysicalState& p : s0) {
    p.v0.setZero();
    for (Vec3& w : p.w) w.setZero();
    for (double& r : p.length_rate) r = 0;
    for (BodyState& b : p.bodies) b.w.setZero();
  }
  tree_kinematics(tree, s0, ws);
  for (std::size_t i = 0; i < nl; ++i) {
    Workspace& w = ws.lines[i];
    compute_loads(tree.lines[i], s0[i], 0.0, w);
    for (std::size_t k = 0; k < w.F.size(); ++k) w.F[k].setZero(), w.Mom[k].setZero();
    for (Vec3& f : w.Fa) f.setZero();
    for (auto& ew : w.elastic) ew.T = 0;  // a finite tension gives no impulse
    for (BodyWork& bw : w.body) bw.Fb.setZero(), bw.Mb.setZero(), bw.hw.setZero();
  }
  if (!tree.loops.empty()) return solve_loops(tree, s0, 0.0, ws, &dv);
  tree_up(tree, s0, ws, false, false);
  tree_down(tree, s0, 0.0, ws, false, &dv);
}

TreeImplicitWorkspace::TreeImplicitWorkspace(const TreeModel& tree, const TreeWorkspace& ws) {
  lines.reserve(tree.lines.size());
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    lines.emplace_back(tree.lines[i]);
    lines[i].top_given = tree.tops[i].line >= 0;
    for (std::size_t b = 0; b < ws.lines[i].body.size(); ++b)
      lines[i].body_children[b].assign(ws.lines[i].body[b].children.size(), ImplicitWorkspace::Child{});
  }
  const std::size_t nloop = tree.loops.size();
  loop_impulse.assign(nloop, Vec3::Zero());
  if (nloop > 0)
    for (const Model& m : tree.lines) {
      const std::size_t n = m.cable.elements.size(), nb = m.bodies.size();
      StageRhs r;
      r.dw.assign(n, Vec3::Zero()), r.rot.assign(n, Vec3::Zero()), r.dl.assign(n, 0.0), r.dlr.assign(n, 0.0);
      r.dwb.assign(nb, Vec3::Zero()), r.rotb.assign(nb, Vec3::Zero());
      zero_rhs.push_back(r);
    }
  const auto m = static_cast<Eigen::Index>(3 * nloop);
  loop_G.setZero(m, m);
  loop_gap.setZero(m);
  loop_mu.setZero(m);
  loop_lu = Eigen::PartialPivLU<Eigen::MatrixXd>(m);
}

void tree_local_jacobian(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double t,
                         TreeImplicitWorkspace& iw) {
  for (std::size_t i = 0; i < tree.lines.size(); ++i)
    local_jacobian(tree.lines[i], s[i], ws.lines[i], t, iw.lines[i].jac);
}

namespace {

/// The node line i hangs from, in the stage solve's workspace.
ImplicitWorkspace::Child& stage_node(const TreeModel& tree, const TreeWorkspace& ws, std::size_t i,
                                     TreeImplicitWorkspace& iw) {
  const LineTop& top = tree.tops[i];
  ImplicitWorkspace& p = iw.lines[idx(top.line)];
  return top.body < 0 ? p.end : p.body_children[idx(top.body)][idx(ws.slot[i])];
}

/// Loop j's point on its node, in the stage solve's workspace.
ImplicitWorkspace::Child& stage_loop_node(const TreeModel& tree, const TreeWorkspace& ws, std::size_t j,
                                          TreeImplicitWorkspace& iw) {
  const LoopJoint& lp = tree.loops[j];
  ImplicitWorkspace& p = iw.lines[idx(lp.node_line)];
  return lp.body < 0 ? p.end : p.body_children[idx(lp.body)][idx(ws.loop_slot[j])];
}

/// A line's top term into its node: summed at a junction (every line below
/// it), set at a body's point (one line each).
template <class T>
void into_node(const LineTop& top, const T& x, T& node) {
  if (top.body < 0)
    node += x;
  else
    node = x;
}

/// The right-hand side down the tree: a line's top moves with its node.
void stage_rhs_down(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                    const std::vector<StageRhs>& r, TreeImplicitWorkspace& iw) {
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    if (tree.tops[i].line >= 0) {
      const ImplicitWorkspace::Child& node = stage_node(tree, ws, i, iw);
      iw.lines[i].top_dv = node.dv, iw.lines[i].top_dx = node.dx;
    }
    stage::loads(tree.lines[i], s[i], ws.lines[i], hg, r[i], iw.lines[i]);
  }
}

/// The bias up the tree: each line's top b_0 into its node, the loops'
/// impulses at their points (as apply_loop_forces); path_only as tree_up.
void stage_bias_up(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, TreeImplicitWorkspace& iw,
                   bool path_only) {
  for (auto& w : iw.lines) w.end.b.setZero();
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    iw.lines[idx(lp.line)].end.b -= iw.loop_impulse[j];
    ImplicitWorkspace::Child& node = stage_loop_node(tree, ws, j, iw);
    if (lp.body < 0)
      node.b += iw.loop_impulse[j];
    else
      node.b = iw.loop_impulse[j];
  }
  for (std::size_t i = tree.lines.size(); i-- > 0;) {
    if (!path_only || ws.loop_path[i]) stage::bias(tree.lines[i], s[i], ws.lines[i], iw.lines[i]);
    if (tree.tops[i].line < 0) continue;
    into_node(tree.tops[i], iw.lines[i].b[0], stage_node(tree, ws, i, iw).b);
  }
}

/// The increments down the tree: a line's top increment is its node's.
void stage_increments_down(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws,
                           TreeImplicitWorkspace& iw, bool path_only) {
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    if (path_only && !ws.loop_path[i]) continue;
    if (tree.tops[i].line >= 0) iw.lines[i].top_a = stage_node(tree, ws, i, iw).a;
    stage::increments(tree.lines[i], s[i], ws.lines[i], iw.lines[i]);
  }
}

/// Each loop's gap increment (its line's cable end's minus its node point's).
void stage_loop_gaps(const TreeModel& tree, const TreeWorkspace& ws, TreeImplicitWorkspace& iw,
                     Eigen::Ref<Eigen::VectorXd> gap) {
  for (std::size_t j = 0; j < tree.loops.size(); ++j)
    gap.segment<3>(static_cast<Eigen::Index>(3 * j)) = iw.lines[idx(tree.loops[j].line)].end.a -
                                                       stage_loop_node(tree, ws, j, iw).a;
}

}  // namespace

void tree_implicit_factor(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                          TreeImplicitWorkspace& iw) {
  // Up the tree: each line's factor, its top's K_0 into its node.
  for (auto& w : iw.lines) w.end.K.setZero();
  for (std::size_t i = tree.lines.size(); i-- > 0;) {
    implicit_factor(tree.lines[i], s[i], ws.lines[i], hg, iw.lines[i]);
    if (tree.tops[i].line < 0) continue;
    into_node(tree.tops[i], iw.lines[i].K[0], stage_node(tree, ws, i, iw).K);
  }
  if (tree.loops.empty()) return;
  // The loops' responses (docs/theory.md §5.7 "Loops"): zero right-hand
  // side, then one unit impulse per component along the loops' paths.
  stage_rhs_down(tree, s, ws, hg, iw.zero_rhs, iw);
  std::fill(iw.loop_impulse.begin(), iw.loop_impulse.end(), Vec3::Zero());
  stage_bias_up(tree, s, ws, iw, false);
  for (std::size_t c = 0; c < 3 * tree.loops.size(); ++c) {
    std::fill(iw.loop_impulse.begin(), iw.loop_impulse.end(), Vec3::Zero());
    iw.loop_impulse[c / 3][static_cast<Eigen::Index>(c % 3)] = 1;
    stage_bias_up(tree, s, ws, iw, true);
    stage_increments_down(tree, s, ws, iw, true);
    stage_loop_gaps(tree, ws, iw, iw.loop_G.col(static_cast<Eigen::Index>(c)));
  }
  iw.loop_lu.compute(iw.loop_G);
}

void tree_stage_solve(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                      const std::vector<StageRhs>& r, TreeImplicitWorkspace& iw) {
  const std::size_t nl = tree.lines.size();
  if (r.size() != nl || iw.lines.size() != nl)
    throw std::logic_error("towsim: tree: one stage right-hand side per line");
  if (std::any_of(iw.lines.begin(), iw.lines.end(), [&](const ImplicitWorkspace& w) { return w.hg != hg; }))
    tree_implicit_factor(tree, s, ws, hg, iw);
  stage_rhs_down(tree, s, ws, hg, r, iw);
  if (tree.loops.empty()) {
    stage_bias_up(tree, s, ws, iw, false);
    stage_increments_down(tree, s, ws, iw, false);
    return;
  }
  // Loops: the free increments along the paths, the impulses that close
  // the gaps (G mu = -gap), the increments with them.
  std::fill(iw.loop_impulse.begin(), iw.loop_impulse.end(), Vec3::Zero());
  stage_bias_up(tree, s, ws, iw, false);
  stage_increments_down(tree, s, ws, iw, true);
  stage_loop_gaps(tree, ws, iw, iw.loop_gap);
  iw.loop_mu = iw.loop_lu.solve(-iw.loop_gap);
  for (std::size_t j = 0; j < tree.loops.size(); ++j)
    iw.loop_impulse[j] = iw.loop_mu.segment<3>(static_cast<Eigen::Index>(3 * j));
  stage_bias_up(tree, s, ws, iw, true);
  stage_increments_down(tree, s, ws, iw, false);
}

namespace {

/// The rotations that move a point of the tree, each with its lever r
/// (dX = dtheta x r): per line, one per element (r = l_k e_k) then one per
/// body (an in-line body above the point: r = Q2 - Q; the body the point is
/// on: r = X - Q).
struct LoopVars {
  std::vector<std::size_t> first;  // per line: its first rotation
  std::vector<double> weight;      // per rotation: the part's rotational inertia [kg m^2]
};

LoopVars loop_vars(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws) {
  LoopVars v;
  for (std::size_t l = 0; l < tree.lines.size(); ++l) {
    const Model& m = tree.lines[l];
    v.first.push_back(v.weight.size());
    for (std::size_t k = 0; k < m.cable.elements.size(); ++k) {
      const Element& el = m.cable.elements[k];
      const double len = s[l].length_of(m, k);
      v.weight.push_back((el.mass + el.added_mass) * len * len / 3 + 1e-12);
    }
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const Body& body = m.bodies[b];
      v.weight.push_back(body.total_mass.bottomRightCorner<3, 3>().trace() / 3 +
                         body.mass * ws.lines[l].body[b].rQ.squaredNorm() + 1e-12);
    }
  }
  return v;
}

/// Adds sign * d(X)/d(rotations) to the 3 rows of J, X on line l: its
/// cable end (body < 0) or the point x of its body `body`, up to the root.
void point_jacobian(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, const LoopVars& v,
                    std::size_t l, int body, Vec3 x, double sign, Eigen::Ref<Eigen::MatrixXd> J) {
  for (;;) {
    const Model& m = tree.lines[l];
    const Workspace& w = ws.lines[l];
    const std::size_t n = m.cable.elements.size();
    auto add = [&](std::size_t var, const Vec3& r) {
      J.middleCols<3>(static_cast<Eigen::Index>(3 * var)) -= sign * skew(r);
    };
    std::size_t below = n;  // the point hangs below the joints above `below`
    if (body >= 0) {
      const std::size_t b = idx(body);
      below = m.bodies[b].joint < 0 ? n : idx(m.bodies[b].joint);
      add(v.first[l] + n + b, x - (w.body[b].O + w.body[b].rQ));
    }
    for (std::size_t k = 0; k < below; ++k) add(v.first[l] + k, s[l].length_of(m, k) * s[l].e[k]);
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const Body& bd = m.bodies[b];
      if (bd.inline_body && bd.joint >= 0 && idx(bd.joint) < below)
        add(v.first[l] + n + b, w.body[b].rQ2 - w.body[b].rQ);
    }
    const LineTop& top = tree.tops[l];
    if (top.line < 0) return;
    x = ws.top[l], body = top.body, l = idx(top.line);
  }
}

/// The loops' Jacobian (3L rows) at the kinematics ws holds.
void loops_jacobian(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, const LoopVars& v,
                    Eigen::MatrixXd& J) {
  J.setZero(static_cast<Eigen::Index>(3 * tree.loops.size()), static_cast<Eigen::Index>(3 * v.weight.size()));
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    auto rows = J.middleRows<3>(static_cast<Eigen::Index>(3 * j));
    point_jacobian(tree, s, ws, v, idx(lp.line), -1, ws.lines[idx(lp.line)].P.back(), +1, rows);
    const Workspace& node = ws.lines[idx(lp.node_line)];
    const Vec3 x = lp.body < 0
                       ? node.P.back()
                       : Vec3(node.body[idx(lp.body)].O + node.body[idx(lp.body)].children[idx(ws.loop_slot[j])].r);
    point_jacobian(tree, s, ws, v, idx(lp.node_line), lp.body, x, -1, rows);
  }
}

/// The loops' position gaps (its line's cable end minus its node point) and velocity gaps.
void loop_position_gaps(const TreeModel& tree, const TreeWorkspace& ws, Eigen::VectorXd& g, Eigen::VectorXd& gv) {
  g.resize(static_cast<Eigen::Index>(3 * tree.loops.size()));
  gv.resize(g.size());
  for (std::size_t j = 0; j < tree.loops.size(); ++j) {
    const LoopJoint& lp = tree.loops[j];
    const Workspace& a = ws.lines[idx(lp.line)];
    const Workspace& node = ws.lines[idx(lp.node_line)];
    Vec3 x = node.P.back(), vx = node.vP.back();
    if (lp.body >= 0) {
      const BodyWork& bw = node.body[idx(lp.body)];
      const Vec3& r = bw.children[idx(ws.loop_slot[j])].r;
      x = bw.O + r, vx = bw.vO + bw.w.cross(r);
    }
    g.segment<3>(static_cast<Eigen::Index>(3 * j)) = a.P.back() - x;
    gv.segment<3>(static_cast<Eigen::Index>(3 * j)) = a.vP.back() - vx;
  }
}

/// The least-norm rotations (in the weights) that move the gaps by -gap: W^-1 J^T (J W^-1 J^T)^-1 (-gap).
Eigen::VectorXd least_norm(const Eigen::MatrixXd& J, const LoopVars& v, const Eigen::VectorXd& gap) {
  Eigen::VectorXd winv(J.cols());
  for (Eigen::Index i = 0; i < J.cols(); ++i) winv(i) = 1 / v.weight[static_cast<std::size_t>(i / 3)];
  const Eigen::MatrixXd JW = J * winv.asDiagonal();
  const Eigen::MatrixXd A = JW * J.transpose();
  return JW.transpose() * A.fullPivLu().solve(-gap);
}

}  // namespace

double tree_close_loops(const TreeModel& tree, TreeState& s) {
  if (tree.loops.empty()) return 0;
  TreeWorkspace ws(tree);
  Eigen::VectorXd g, gv;
  Eigen::MatrixXd J;
  // Positions: Gauss-Newton on the rotations, each step's largest turn held to 0.5 rad.
  constexpr double kTol = 1e-13;  // [m]
  constexpr int kSteps = 50;
  for (int step = 0;; ++step) {
    tree_kinematics(tree, s, ws);
    loop_position_gaps(tree, ws, g, gv);
    if (g.lpNorm<Eigen::Infinity>() <= kTol || step == kSteps) break;
    const LoopVars v = loop_vars(tree, s, ws);
    loops_jacobian(tree, s, ws, v, J);
    Eigen::VectorXd d = least_norm(J, v, g);
    double turn = 0;
    for (Eigen::Index i = 0; i < d.size(); i += 3) turn = std::max(turn, d.segment<3>(i).norm());
    if (turn > 0.5) d *= 0.5 / turn;
    for (std::size_t l = 0; l < tree.lines.size(); ++l) {
      PhysicalState& p = s[l];
      const std::size_t n = p.e.size();
      auto rotation = [&](std::size_t var) {
        const Vec3 th = d.segment<3>(static_cast<Eigen::Index>(3 * (v.first[l] + var)));
        const double a = th.norm();
        return a > 0 ? Eigen::AngleAxisd(a, th / a) : Eigen::AngleAxisd(0, Vec3::UnitZ());
      };
      for (std::size_t k = 0; k < n; ++k) {
        const Mat3 R = rotation(k).toRotationMatrix();
        p.e[k] = (R * p.e[k]).normalized();
        p.w[k] = R * p.w[k];
        p.w[k] -= p.w[k].dot(p.e[k]) * p.e[k];
      }
      for (std::size_t b = 0; b < p.bodies.size(); ++b)
        p.bodies[b].q = (Quat(rotation(n + b)) * p.bodies[b].q).normalized();
    }
  }
  const double gap = g.lpNorm<Eigen::Infinity>();
  // Velocities: the angular velocities projected onto the velocity constraint (linear: twice for round-off).
  for (int pass = 0; pass < 2; ++pass) {
    const LoopVars v = loop_vars(tree, s, ws);
    loops_jacobian(tree, s, ws, v, J);
    const Eigen::VectorXd d = least_norm(J, v, gv);
    for (std::size_t l = 0; l < tree.lines.size(); ++l) {
      PhysicalState& p = s[l];
      const std::size_t n = p.e.size();
      for (std::size_t k = 0; k < n; ++k) {
        p.w[k] += d.segment<3>(static_cast<Eigen::Index>(3 * (v.first[l] + k)));
        p.w[k] -= p.w[k].dot(p.e[k]) * p.e[k];
      }
      for (std::size_t b = 0; b < p.bodies.size(); ++b)
        p.bodies[b].w += d.segment<3>(static_cast<Eigen::Index>(3 * (v.first[l] + n + b)));
    }
    tree_kinematics(tree, s, ws);
    loop_position_gaps(tree, ws, g, gv);
  }
  return gap;
}

}  // namespace towsim
