// One chain's rows of a flat state in the default formulation
// (StateLayout::default_of): packing and unpacking its physical state, its
// rates from an evaluation, the projection's renormalisation, and its stage
// solve's right-hand side and result. The default system is one chain's
// rows; a network's system is one per line, side by side.
#pragma once

#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/state.hpp"
#include "towsim/integrators/state_layout.hpp"

namespace towsim {

/// Jump of the chain's imposed tow velocity at t: v(t+) - v(t-) [m/s] (zero in Force mode).
Vec3 tow_jump(const Model& m, double t);
/// Add an impulsive response `jump` (its accelerations are velocity jumps:
/// tow_velocity_jump, tree_tow_velocity_jump) to s; with `tow_law`, the
/// tow point to its motion's right limit at t.
void add_jump(const Model& m, const Accelerations& jump, double t, bool tow_law, PhysicalState& s);
/// Physical state after the impulsive response to the tow velocity jump dv
/// at t (tow_velocity_jump; ws: its storage), the tow point at its motion's right limit.
PhysicalState jumped(const Model& m, PhysicalState s, const Vec3& dv, double t, Workspace& ws);

/// A chain's rows, at a pointer to the first row of its block.
class ChainRows {
 public:
  explicit ChainRows(const Model& m);

  const Model& model() const { return model_; }
  const StateLayout& layout() const { return layout_; }
  /// The chain's shape: sizes, and the model's lengths of the elements without a length in the state.
  const PhysicalState& shape() const { return shape_; }
  std::size_t size() const { return layout_.size; }
  bool winch() const { return winch_; }
  bool elastic_top() const { return elastic_top_; }
  bool lengths() const { return lengths_; }
  double fixed_length() const { return fixed_length_; }

  /// The rows of physical state s.
  void pack(const PhysicalState& s, double* y) const;
  /// s (of the chain's shape) from the rows.
  void unpack(const double* y, PhysicalState& s) const;
  /// Length control: the top element's length and rate at t from the schedule.
  void impose_winch(double t, PhysicalState& s) const;
  /// dy/dt's rows from the evaluation ws of s (forward dynamics done).
  void rates(const PhysicalState& s, const Workspace& ws, double* dy) const;
  /// After a step: unit directions, angular velocities normal to them, unit quaternions.
  void normalise(double* y) const;
  /// The stage right-hand side r's rows as the recursion's StageRhs, at the Jacobian point js.
  void stage_rhs(const double* r, const PhysicalState& js, StageRhs& rhs) const;
  /// The stage increment k's rows from the solve's result iw (r, rhs as
  /// given to it): position rows k_x = r_x + hg B k_v; rows without local terms k = r.
  void stage_result(const double* r, const PhysicalState& js, const StageRhs& rhs, const ImplicitWorkspace& iw,
                    double hg, double* k) const;

 private:
  const Model& model_;
  StateLayout layout_;
  PhysicalState shape_;
  int n_ = 0;
  bool lengths_ = false;      // the state carries element lengths and rates
  bool winch_ = false;        // the state carries the winch's l_1, l_1'
  bool elastic_top_ = false;  // ... as L_1, L_1' of an elastic top element (l_1, l_1' among the lengths)
  double fixed_length_ = 0;   // deployed length but l_1 [m]
};

}  // namespace towsim
