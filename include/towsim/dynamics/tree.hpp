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
//
// Loops (TreeModel::loops, docs/theory.md §5.7 "Loops"): each closing ball
// joint's force, one multiplier vector per loop, from a small dense solve
// per evaluation (and per stage factorisation) of the loop points' relative
// accelerations, which are affine in the multipliers.
#pragma once

#include <Eigen/LU>
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
  // Loops (empty without): the multipliers and their solve's work.
  std::vector<int> loop_slot;    // per loop closing on a body's point: its index in that body's children, else -1
  std::vector<Vec3> loop_force;  // per loop: the force of its node on the line's cable end [N, R_g] (the leg's
                                 // pull is -loop_force on the node)
  std::vector<char> loop_path;   // per line: on a path from a root to a loop's point (its passes see the loop forces)
  Eigen::MatrixXd loop_G;        // the loop points' relative accelerations per unit loop force (3L x 3L) [1/kg]
  Eigen::VectorXd loop_gap;      // the free sweep's relative accelerations (3L) [m/s^2]
  Eigen::VectorXd loop_lambda;   // the loop forces stacked (3L) [N]
  Eigen::PartialPivLU<Eigen::MatrixXd> loop_lu;
  /// True when this workspace was sized for `tree`.
  bool fits(const TreeModel& tree) const;
};

/// Accelerations of every line of the tree at (s, t): each line's ws.acc as
/// forward_dynamics gives a chain's (acc.tow_force: the force on the line at
/// its top, from the vessel or its node). With loops, their forces in
/// ws.loop_force (the state must satisfy the loops' position and velocity
/// constraints: tree_close_loops). Throws std::logic_error when the
/// workspace or state does not fit the tree.
void tree_forward_dynamics(const TreeModel& tree, const TreeState& s, double t, TreeWorkspace& ws);

/// Each line's stage-solve workspace, with the nodes' children sized.
struct TreeImplicitWorkspace {
  TreeImplicitWorkspace(const TreeModel& tree, const TreeWorkspace& ws);
  std::vector<ImplicitWorkspace> lines;
  // Loops (empty without): the stage's multipliers (impulses) and their solve, as TreeWorkspace's.
  std::vector<Vec3> loop_impulse;  // per loop: the impulse of its node on the line's cable end [N s, R_g]
  std::vector<StageRhs> zero_rhs;  // per line: a zero right-hand side (the unit responses' loads)
  Eigen::MatrixXd loop_G;          // relative increments per unit impulse (3L x 3L) [1/kg]
  Eigen::VectorXd loop_gap;        // [m/s]
  Eigen::VectorXd loop_mu;         // the impulses stacked (3L) [N s]
  Eigen::PartialPivLU<Eigen::MatrixXd> loop_lu;
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
/// With loops, z keeps them closed to first order (the gap of the loop
/// points' increments is zero), their impulses in iw.loop_impulse.
void tree_stage_solve(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, double hg,
                      const std::vector<StageRhs>& r, TreeImplicitWorkspace& iw);

/// The tree's impulsive response to a jump dv[i] of each root line's tow
/// velocity (dv of a line below a node unused) [m/s, R_g]: the sweep at
/// zero velocity with zero finite loads, the loops closed by impulses, so
/// each line's ws.lines[i].acc holds velocity jumps (alpha: the elements'
/// angular velocity jumps [rad/s], alpha_b the bodies', length_acc the
/// elastic lengths' rates). As tow_velocity_jump for a chain.
void tree_tow_velocity_jump(const TreeModel& tree, const TreeState& s, const std::vector<Vec3>& dv, TreeWorkspace& ws);

/// Put a state that nearly closes its loops onto them: the positions by
/// Gauss-Newton steps on the element directions and the bodies' attitudes
/// (least norm in the parts' rotational inertias; lengths and roots held),
/// to 1e-12 m; then the velocities (the elements' and bodies' angular
/// velocities) projected onto the loops' velocity constraint the same way.
/// Returns the largest position gap left [m]. No loops: nothing changes.
double tree_close_loops(const TreeModel& tree, TreeState& s);

}  // namespace towsim
