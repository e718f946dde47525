// A tree of lines (docs/theory.md §5.7 "Trees of lines"): several chains
// joined at nodes. Each line is a chain of its own Model (cable, sections,
// attachments, in-line and end bodies, elasticity, bending); it hangs from
// the vessel (a root line, moved by its own tow law) or from a node of a
// line above it: that line's cable end (a junction: a point mass, the
// line's attachment there) or a point of one of its bodies. A node may carry
// any number of lines. A chain is the tree of one line.
//
// Forward dynamics run the one sweep (sweep::up, sweep::down) line by line:
// up from the last line, each line's top force f_0 = K_0 a + b_0 taken into
// its node's articulated inertia and bias (as an in-line body takes the
// cable below it); down from the roots, each line driven at its top by its
// node's acceleration. Cost O(total elements).
#pragma once

#include <vector>

#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/state.hpp"
#include "towsim/model/network.hpp"

namespace towsim {

/// Each line's physical state (a child line's r0, v0 are its node's, computed: unused).
using TreeState = std::vector<PhysicalState>;

/// Each line's workspace, with the nodes' children registered.
struct TreeWorkspace {
  explicit TreeWorkspace(const TreeModel& tree);
  std::vector<Workspace> lines;
  std::vector<int> slot;                // per line hanging from a body: its index in that body's children, else -1
  std::vector<Vec3> top, top_velocity;  // per line: its top joint P_0 and its velocity [m], [m/s], R_g
  /// True when this workspace was sized for `tree`.
  bool fits(const TreeModel& tree) const;
};

/// Accelerations of every line of the tree at (s, t): each line's ws.acc as
/// forward_dynamics gives a chain's (acc.tow_force: the force on the line at
/// its top, from the vessel or its node). Throws std::logic_error when the
/// workspace or state does not fit the tree.
void tree_forward_dynamics(const TreeModel& tree, const TreeState& s, double t, TreeWorkspace& ws);

/// Each line's stage-solve workspace, with the nodes' children sized.
struct TreeImplicitWorkspace {
  TreeImplicitWorkspace(const TreeModel& tree, const TreeWorkspace& ws);
  std::vector<ImplicitWorkspace> lines;
};

/// Each line's local Jacobian (local_jacobian) at the evaluation ws holds
/// (tree_forward_dynamics at (s, t)).
void tree_local_jacobian(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double t,
                         TreeImplicitWorkspace& iw);

/// The stage matrix M + hg C + hg^2 K of the whole tree factorised in O(n):
/// each line's implicit_factor from the last line up, its top's K_0 into its node.
void tree_implicit_factor(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                          TreeImplicitWorkspace& iw);

/// One stage solve of the whole tree (implicit_stage_solve per line, r one
/// StageRhs per line): the right-hand side down from the roots, the bias up
/// from the last line, the increments down; each line's result in its
/// ImplicitWorkspace (a line below a node: iw.a0 is its node's increment).
void tree_stage_solve(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                      const std::vector<StageRhs>& r, TreeImplicitWorkspace& iw);

}  // namespace towsim
