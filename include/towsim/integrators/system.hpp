// A formulation as the time integrator sees it: a flat state vector, its time
// derivative, and a projection after each accepted step (docs/theory.md §6).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "towsim/dynamics/state.hpp"
#include "towsim/integrators/step_window.hpp"

namespace towsim {

using StateVector = std::vector<double>;

/// What the force error estimate reads of one evaluation.
struct EvaluationForces {
  Vec3 tow_force = Vec3::Zero();  // force of the chain on the tow point [N, R_g]
  std::vector<Vec3> link_force;   // per body, its link force [N, R_g]
};

/// One formulation's state space. Implementations: the default (unit vectors
/// e_k, angular velocities, body quaternion) and the paper's (angles in charts).
/// What derivative() and evaluate() return depends on their arguments only:
/// the system keeps storage and caches (its workspace), never state; the
/// step's window is an argument, events (tow jumps, winch splits) are the
/// run loop's calls (docs/theory.md §6).
class System {
 public:
  virtual ~System() = default;
  /// Flat state of a physical state at time t.
  virtual StateVector initial(const PhysicalState& s, double t) = 0;
  /// dy/dt at (y, t), the time-dependent inputs taken inside the step's
  /// window. Counted (rhs_evaluations).
  virtual void derivative(const StateVector& y, StateVector& dy, double t, const StepWindow& window) = 0;
  /// derivative() outside any step: the inputs at t itself.
  void derivative(const StateVector& y, StateVector& dy, double t) { derivative(y, dy, t, StepWindow{}); }
  /// derivative() in one step's window with odeint's call signature.
  struct InWindow {
    System* sys;
    StepWindow window;
    void operator()(const StateVector& y, StateVector& dy, double t) const { sys->derivative(y, dy, t, window); }
  };
  InWindow in_window(const StepWindow& window) { return {this, window}; }
  /// After an accepted step: renormalise unit vectors and quaternion, make
  /// angular velocities normal to their element, re-choose charts, and reset
  /// the tow point to its imposed motion. Keeps the physical state.
  virtual void project(StateVector& y, double t) = 0;
  /// At a breakpoint t of an imposed tow motion whose velocity jumps, give
  /// the chain and body the impulsive response (tow_velocity_jump).
  /// Returns the jump's size [m/s] (0: nothing done).
  virtual double apply_tow_jump(StateVector& y, double t) = 0;
  /// derivative(y, dy, t, window) where y's rigid inertias may be those of
  /// the Jacobian point (W's time column): a system may reuse what depends
  /// on y alone when its cache provably holds it. Bit-identical to
  /// derivative(); counted.
  virtual void derivative_time_shift(const StateVector& y, StateVector& dy, double t, const StepWindow& window) {
    derivative(y, dy, t, window);
  }
  /// Physical state of y.
  virtual PhysicalState physical(const StateVector& y) const = 0;
  /// physical(y) into the caller's `out` (no allocation once sized by an
  /// earlier call): for checks and outputs at every step.
  virtual void physical_into(const StateVector& y, PhysicalState& out) const { out = physical(y); }
  /// Full evaluation for output at (y, t), the right limit at a breakpoint
  /// (StepWindow::after: the state is already past it): kinematics, forces,
  /// joint forces. No step's evaluation: not counted.
  virtual const Workspace& evaluate(const StateVector& y, double t) = 0;
  /// What state component i belongs to ("element 3", "body", "tow point").
  virtual std::string describe(std::size_t i) const = 0;
  /// Linearly implicit integrators (docs/theory.md §6.3). True when this
  /// system provides the O(n) stage solve below.
  virtual bool has_stage_solve() const { return false; }
  /// Take the local Jacobian at the state of the last derivative() call (the
  /// start of a step), at t in the step's window: used by every stage_solve
  /// until the next call (the workspace's Jacobian cache).
  virtual void prepare_stage_solve(double /*t*/, const StepWindow& /*window*/) {}
  /// Solve (I - hg J) k = r for the stage increment k, J the local Jacobian
  /// approximation of prepare_stage_solve; hg = h gamma [s]. O(n).
  virtual void stage_solve(double /*hg*/, const StateVector& /*r*/, StateVector& /*k*/) {}
  /// Rows of the flat state holding element k's angular velocity w_k and
  /// body b's angular velocity (3 rows each, [1/s, R_g]): for solvers that set
  /// and read rates through stage_solve (statics). Given by the systems with
  /// a stage solve; kNoRow otherwise.
  static constexpr std::size_t kNoRow = static_cast<std::size_t>(-1);
  virtual std::size_t element_rate_row(std::size_t /*k*/) const { return kNoRow; }
  virtual std::size_t body_rate_row(std::size_t /*b*/) const { return kNoRow; }
  /// Forces of the last derivative() call (tow force, link forces), or null.
  virtual const Accelerations* last_accelerations() const { return nullptr; }
  /// Two evaluations in one window, two counted: f(y_side, t_side) for its forces only
  /// (into `side`, when last_accelerations() gives forces), and f(y, t) into
  /// dy as derivative(y, dy, t), the last one on this system's workspace
  /// (last_accelerations(), prepare_stage_solve read it). Here one after the
  /// other, the side one first; a system with a worker thread
  /// (simulation.threads) runs the side one on it, on a workspace of its own,
  /// at the same time: the same numbers (tests/unit/test_concurrent_evaluations.cpp).
  /// start_side_forces() then finish_side_forces().
  void derivative_with_side_forces(const StateVector& y, StateVector& dy, double t, const StateVector& y_side,
                                   double t_side, const StepWindow& window, EvaluationForces& side) {
    start_side_forces(y_side, t_side, window, side);
    finish_side_forces(y, dy, t, window);
  }
  /// derivative_with_side_forces() in two calls, for a side evaluation
  /// handed over before it is known to be needed (speculative: the step's
  /// error is not known yet). y_side and side stay untouched until the
  /// matching finish_side_forces() or cancel_side_forces(). Here it is only
  /// recorded; a system with a worker thread starts it on the worker.
  virtual void start_side_forces(const StateVector& y_side, double t_side, const StepWindow& window,
                                 EvaluationForces& side) {
    pending_ = {&y_side, t_side, window, &side};
  }
  /// The started side evaluation's end, then f(y, t) into dy: as
  /// derivative_with_side_forces(y, dy, t, y_side, t_side, window, side),
  /// the same evaluations in the same order, counted, exceptions the same
  /// (the side one's first).
  virtual void finish_side_forces(const StateVector& y, StateVector& dy, double t, const StepWindow& window) {
    derivative(*pending_.y, side_dy_, pending_.t, pending_.window);
    if (const Accelerations* acc = last_accelerations())
      pending_.out->tow_force = acc->tow_force, pending_.out->link_force = acc->link_force;
    derivative(y, dy, t, window);
  }
  /// Drop the started side evaluation: as if never started (not counted,
  /// nothing thrown: what it threw is dropped; `side` may have been written).
  /// Waits for a worker running it. Serially (here) nothing was evaluated.
  virtual void cancel_side_forces() noexcept {}
  /// A side evaluation (start_side_forces) comes soon (a hint: a worker
  /// thread gets ready for it; nothing else changes).
  virtual void expect_side_evaluation() {}
  /// Threads this system evaluates on (1, or 2 with a worker thread) [-].
  virtual int threads() const { return 1; }

  /// Statistics: the derivative() evaluations so far (evaluate()'s are none) [-].
  long rhs_evaluations = 0;

 protected:
  StateVector side_dy_;  // the serial side evaluation's discarded rates (storage)

 private:
  /// The side evaluation started last (start_side_forces), serially.
  struct PendingSide {
    const StateVector* y = nullptr;
    double t = 0;  // [s]
    StepWindow window;
    EvaluationForces* out = nullptr;
  };
  PendingSide pending_;
};

/// The system of the model's formulation (model.sim.formulation), on
/// evaluation_threads(model) threads.
std::unique_ptr<System> make_system(const Model& model);

/// Cable elements from which simulation.threads: auto uses a worker thread
/// (docs/performance.md "Concurrent step-end evaluations", "Loads
/// on two threads": with the loads split, 2 threads won 13 % at
/// 300 elements and tied at 200).
constexpr int kAutoThreadsElements = 300;  // [-]
/// Stalled waits for the worker (Worker::stalls) after which a system runs
/// on without it [-] (docs/performance.md "Next to a busy process").
constexpr int kMaxWorkerStalls = 8;

/// Threads a run of the model evaluates its dynamics on: 2 (the step-end
/// evaluations of the rosenbrock integrator at the same time) or 1.
/// model.sim.threads >= 2, or auto (0) with >= kAutoThreadsElements elements
/// and >= 2 hardware threads: 2 with the rosenbrock integrator and the
/// default formulation; 1 otherwise.
int evaluation_threads(const Model& model);

/// Initial physical state of a model (hanging, along a direction; steady via statics).
PhysicalState initial_state(const Model& model);

/// The run's start over a bottom (docs/theory.md §3.2): a cable with a free
/// end whose elements start exactly vertical (hanging from a sheave at rest)
/// has them leaned by 1e-4 rad towards +x_g (4 mm over 40 m). An upright
/// column landing on the bottom is an unstable equilibrium, but an exact one
/// that a symmetric run would keep for ever, the rigid column driven into the
/// bottom by the winch; the lean is the imperfection a real cable always has,
/// as a buckling analysis seeds one. The dynamics carry no push. Nothing is
/// changed without a seabed or with an end body.
void lean_upright(const Model& model, PhysicalState& s);

}  // namespace towsim
