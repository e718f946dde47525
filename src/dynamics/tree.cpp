// A tree of lines: the one sweep run line by line, joined at the nodes
// (towsim/dynamics/tree.hpp, docs/theory.md §5.7).
#include "towsim/dynamics/tree.hpp"

#include <algorithm>
#include <stdexcept>

#include "articulated.hpp"
#include "towsim/dynamics/dynamics.hpp"

namespace towsim {

namespace {

inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// The tree's entry check: every line after the one it hangs from, every
/// node a cable end or a body of that line, no winch below the vessel.
void check_tree(const TreeModel& tree) {
  if (tree.tops.size() != tree.lines.size()) throw std::logic_error("towsim: tree: one top per line");
  if (!tree.loops.empty()) throw std::logic_error("towsim: tree: loops are not solved by the tree's sweep");
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
}

bool TreeWorkspace::fits(const TreeModel& tree) const {
  if (lines.size() != tree.lines.size() || slot.size() != tree.lines.size()) return false;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (!lines[i].fits(tree.lines[i])) return false;
  return true;
}

void tree_forward_dynamics(const TreeModel& tree, const TreeState& s, double t, TreeWorkspace& ws) {
  const std::size_t nl = tree.lines.size();
  if (!ws.fits(tree) || s.size() != nl) throw std::logic_error("towsim: tree: workspace or state does not fit");
  for (std::size_t i = 0; i < nl; ++i)
    if (s[i].e.size() != tree.lines[i].cable.elements.size() || s[i].w.size() != s[i].e.size() ||
        s[i].bodies.size() != tree.lines[i].bodies.size())
      throw std::logic_error("towsim: tree: a line's state does not fit its model");
  // Kinematics down the tree: a line's top is its node's point.
  for (std::size_t i = 0; i < nl; ++i) {
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
  // Every line's loads, from its own kinematics.
  for (std::size_t i = 0; i < nl; ++i) compute_loads(tree.lines[i], s[i], t, ws.lines[i]);
  // Up the tree: each line's top force into its node, from the last line up.
  for (auto& w : ws.lines) w.end_K.setZero(), w.end_b.setZero();
  for (std::size_t i = nl; i-- > 0;) {
    Workspace& w = ws.lines[i];
    chain::articulate(tree.lines[i], s[i], w, false);
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
  // Down the tree: each line driven at its top by its node's acceleration.
  for (std::size_t i = 0; i < nl; ++i) {
    const LineTop& top = tree.tops[i];
    Vec3 a0 = Vec3::Zero();
    if (top.line >= 0) {
      const Workspace& p = ws.lines[idx(top.line)];
      a0 = top.body < 0 ? p.acc.end_acc : p.body[idx(top.body)].children[idx(ws.slot[i])].a;
    }
    chain::accelerate(tree.lines[i], s[i], t, ws.lines[i], top.line < 0 ? nullptr : &a0);
  }
}

TreeImplicitWorkspace::TreeImplicitWorkspace(const TreeModel& tree, const TreeWorkspace& ws) {
  lines.reserve(tree.lines.size());
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    lines.emplace_back(tree.lines[i]);
    lines[i].top_given = tree.tops[i].line >= 0;
    for (std::size_t b = 0; b < ws.lines[i].body.size(); ++b)
      lines[i].body_children[b].assign(ws.lines[i].body[b].children.size(), ImplicitWorkspace::Child{});
  }
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

/// A line's top term into its node: summed at a junction (every line below
/// it), set at a body's point (one line each).
template <class T>
void into_node(const LineTop& top, const T& x, T& node) {
  if (top.body < 0)
    node += x;
  else
    node = x;
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
}

void tree_stage_solve(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                      const std::vector<StageRhs>& r, TreeImplicitWorkspace& iw) {
  const std::size_t nl = tree.lines.size();
  if (r.size() != nl || iw.lines.size() != nl)
    throw std::logic_error("towsim: tree: one stage right-hand side per line");
  if (std::any_of(iw.lines.begin(), iw.lines.end(), [&](const ImplicitWorkspace& w) { return w.hg != hg; }))
    tree_implicit_factor(tree, s, ws, hg, iw);
  // Right-hand side down the tree: a line's top moves with its node.
  for (std::size_t i = 0; i < nl; ++i) {
    if (tree.tops[i].line >= 0) {
      const ImplicitWorkspace::Child& node = stage_node(tree, ws, i, iw);
      iw.lines[i].top_dv = node.dv, iw.lines[i].top_dx = node.dx;
    }
    stage::loads(tree.lines[i], s[i], ws.lines[i], hg, r[i], iw.lines[i]);
  }
  // Bias up the tree: each line's top b_0 into its node.
  for (auto& w : iw.lines) w.end.b.setZero();
  for (std::size_t i = nl; i-- > 0;) {
    stage::bias(tree.lines[i], s[i], ws.lines[i], iw.lines[i]);
    if (tree.tops[i].line < 0) continue;
    into_node(tree.tops[i], iw.lines[i].b[0], stage_node(tree, ws, i, iw).b);
  }
  // Increments down the tree: a line's top increment is its node's.
  for (std::size_t i = 0; i < nl; ++i) {
    if (tree.tops[i].line >= 0) iw.lines[i].top_a = stage_node(tree, ws, i, iw).a;
    stage::increments(tree.lines[i], s[i], ws.lines[i], iw.lines[i]);
  }
}

}  // namespace towsim
