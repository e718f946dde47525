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

/// Jump of the imposed pay-out speed at t from the state's (the left limit,
/// or at rest at t = 0) to the schedule's right limit L'(t+) [m/s] (zero
/// unless length control).
double winch_jump(const Model& m, const PhysicalState& s, double t);
/// Velocity jump of the material at the sheave for a pay-out speed jump dL:
/// dL e_1, or (l_1/L_1) dL e_1 over an elastic top element [m/s, R_g].
Vec3 sheave_jump(const Model& m, const PhysicalState& s, double dL);
/// After the impulsive response to a tow jump with the sheave's jump
/// `dsheave` at t: a length-controlled winch's own rates on its schedule's
/// right limit (over an elastic top element l_1' also takes the sheave's jump).
void winch_rates_after_jump(const Model& m, double t, const Vec3& dsheave, PhysicalState& s);
/// After the impulsive response to a tension-controlled winch's stop
/// (the sheave's jump dv = -sheave_jump(rate)): the pay-out speed is zero;
/// over an elastic top element l_1' takes the sheave's jump besides.
void winch_rates_after_stop(const Model& m, const Vec3& dv, PhysicalState& s);
/// Physical state after a tension-controlled winch stops from pay-out speed
/// `rate` [m/s]: the impulsive response to the sheave's jump -sheave_jump(rate)
/// (tow_velocity_jump; ws: its storage), then winch_rates_after_stop.
PhysicalState stopped(const Model& m, PhysicalState s, double rate, Workspace& ws);

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
  /// After a step ending at t, the winch's rows on its law: length control
  /// on its schedule's piece before t (a jump, if any, comes next); tension
  /// control at most max_speed, and held at min_length or max_length, where
  /// it returns the pay-out speed that stops there (an impulse the caller
  /// applies: -sheave_jump of it), else 0 [m/s].
  double project_winch(double t, double* y) const;
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
