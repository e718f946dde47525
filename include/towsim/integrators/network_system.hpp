// A network of lines as the time integrator sees it (docs/theory.md §6):
// one flat state, each line's rows of the default formulation
// (StateLayout::default_of its Model) one after the other, the tree's one
// sweep for the derivative and the stage solves.
#pragma once

#include <memory>

#include "towsim/dynamics/tree.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/model/network.hpp"

namespace towsim {

class ChainRows;

/// The tree of a network as a System. A line below a node keeps rows for
/// its top joint (r0, v0) like every line, but they are not its state: the
/// dynamics take its node's motion, their rates and stage increments are
/// zero (they hold their start and stay out of the step's error estimate),
/// and evaluations report the node's (evaluated_state).
class NetworkSystem final : public System {
 public:
  explicit NetworkSystem(const Network& net);
  ~NetworkSystem() override;
  NetworkSystem(const NetworkSystem&) = delete;
  NetworkSystem& operator=(const NetworkSystem&) = delete;

  /// Flat state of the tree's state s.
  StateVector initial_tree(const TreeState& s) const;
  /// The tree's state of y into `out` (resized unless it has this network's
  /// shape, e.g. storage from before a winch event): each line's top joint
  /// as its rows hold it.
  void tree_state_into(const StateVector& y, TreeState& out) const;
  /// Full evaluation for output at (y, t) (the right limit at a
  /// breakpoint), every line's top joint its node's; not counted.
  const TreeWorkspace& evaluate_tree(const StateVector& y, double t);
  /// The tree's state of the last evaluation (derivative, evaluate_tree):
  /// a line's top joint is its node's.
  const TreeState& evaluated_state() const { return s_; }
  /// First row of line i's block.
  std::size_t offset(std::size_t line) const { return offset_[line]; }
  const Network& network() const { return net_; }

  /// A jump of the tow velocity at most this is round-off of its difference
  /// quotient at a change of acceleration (a ramp's end) [m/s].
  static constexpr double kRoundOffJump = 1e-6;
  /// Largest jump of a root line's imposed tow velocity at t [m/s].
  double tow_jump(double t) const;
  /// True when a line hangs below a junction or body (not only from the vessel).
  bool has_nodes() const;

  /// Not a chain: throws std::logic_error (initial_tree is the network's).
  StateVector initial(const PhysicalState& s, double t) override;
  void derivative(const StateVector& y, StateVector& dy, double t, const StepWindow& window) override;
  /// Every root line's tow rows to its imposed motion, unit vectors and
  /// quaternions renormalised, each winch on its law (a tension winch's
  /// stop an impulse), the loops closed (tree_close_loops).
  void project(StateVector& y, double t) override;
  /// The tow velocity's jump at t (with each winch's sheave's) as the tree's impulsive response: each
  /// line's own (jumped) when the lines meet only at the vessel, else the
  /// tree's (tree_tow_velocity_jump, loops closed by impulses), where a jump
  /// of at most kRoundOffJump is left out.
  double apply_tow_jump(StateVector& y, double t) override;
  /// The tree's impulsive response to a jump dv[i] of each root line's
  /// material at its sheave (zero: none) added to s, the loops closed by
  /// impulses (tree_tow_velocity_jump); the winches' own rates are the caller's.
  void sheave_jumps(TreeState& s, const std::vector<Vec3>& dv);
  /// Line 0's physical state (physical_into likewise).
  PhysicalState physical(const StateVector& y) const override;
  /// evaluate_tree's workspace of line 0.
  const Workspace& evaluate(const StateVector& y, double t) override;
  std::string describe(std::size_t i) const override;
  bool has_stage_solve() const override { return true; }
  void prepare_stage_solve(double t, const StepWindow& window) override;
  void stage_solve(double hg, const StateVector& r, StateVector& k) override;
  /// The tree's forces of the last derivative(): tow_force = line 0's top
  /// force; link_force = the other lines' top forces, then every line's
  /// bodies' link forces (the force error estimate reads them all).
  const Accelerations* last_accelerations() const override { return &forces_; }

 private:
  void rates(const StateVector& y, StateVector& dy, double t, const StepWindow& window);
  void gather_forces();
  /// The tension winches that stop (stop_rate_, set by project): the
  /// impulse of their pay-out speeds dropping to zero.
  void stop_winches(StateVector& y);

  const Network& net_;
  const TreeModel& tree_;
  std::vector<std::unique_ptr<ChainRows>> rows_;  // per line
  std::vector<std::size_t> offset_;               // per line: its block's first row
  std::size_t size_ = 0;                          // rows in all
  TreeState s_, js_;                              // the last evaluation's state; the Jacobian point's
  TreeWorkspace ws_, jws_;                        // their evaluations
  TreeImplicitWorkspace iw_;                      // the stage solves' local Jacobians and work arrays
  std::vector<StageRhs> rhs_;                     // per line: one stage's right-hand side
  std::vector<CourseCursor> course_;              // per line: the tow law's cursor for project()
  Accelerations forces_;                          // gather_forces()
  TreeState js_close_;                            // project()'s and the jumps' scratch state (storage)
  std::vector<double> stop_rate_;                 // per line: project()'s tension winch speed at its stop [m/s]
};

/// Initial state of a network's tree (hanging, or along a direction: every
/// line from its top, at rest; elastic lines at their own static stretch;
/// loops closed by tree_close_loops, std::invalid_argument when they cannot be).
/// Throws std::invalid_argument for `initial: steady` (network_steady_state
/// computes that start).
TreeState network_initial_state(const Network& net);

}  // namespace towsim
