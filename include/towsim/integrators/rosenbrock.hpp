// Rosenbrock-W integrator ROS34PW2 (Rang & Angermann 2005): linearly
// implicit, order 3 with an embedded order 2, L-stable, W-method (its order
// holds with any approximation of the Jacobian). Each stage solve is the O(n)
// recursion with modified inertias (System::stage_solve). Error control on
// the state AND on the tow and link forces (docs/theory.md §6.3).
#pragma once

#include <array>

#include "towsim/integrators/system.hpp"

namespace towsim {

class RosenbrockW {
 public:
  /// Where the forces of the force error estimate are compared with those
  /// at y1: at the embedded solution itself (runs: honest on what users
  /// read) or at the filtered one, y1 - (I - hg W)^-1 (y1 - yhat) (a
  /// relaxation, whose path does not matter: fewer steps). docs/theory.md §6.3.
  enum class ForceEstimate { Embedded, Filtered };

  /// The explicit time dependence of f (tow law, waves, winch schedule):
  /// f_t by a forward difference at each step's start, one evaluation, in
  /// the stages' term gamma_i h^2 f_t; or so on every other accepted step
  /// and, between, extrapolated linearly from the last two differences (no
  /// evaluation; runs); or left out (a relaxation at fixed inputs). Any
  /// column keeps the order (it is part of W). docs/theory.md §6.3.
  enum class TimeDerivative { FiniteDifference, Extrapolated, None };

  /// The step size controller: plain, h <- h 0.95 err^(-1/3); or PI
  /// (Gustafsson, Soderlind), after an accepted step h <- h 0.95
  /// err_n^(-0.7/3) err_(n-1)^(0.4/3), which follows an error that varies from
  /// step to step (a sea state) without rejecting a quarter of the steps
  /// (docs/theory.md §6.3 "The controller").
  enum class StepControl { Plain, PI };

  /// tol: relative and absolute tolerance [-]; force_scale: absolute force
  /// floor of the force error norm [N] (the system's apparent weight).
  RosenbrockW(System& sys, double tol, double force_scale, ForceEstimate force_estimate = ForceEstimate::Embedded,
              TimeDerivative time_derivative = TimeDerivative::FiniteDifference);

  /// Try one step of size h from (y, t). Accepted: y, t advanced (y
  /// projected), returns true. Either way h becomes the next proposal [s].
  bool try_step(StateVector& y, double& t, double& h);

  /// The state was changed from outside (a tow velocity jump, a breakpoint):
  /// the cached derivative at the step's start is stale.
  void invalidate() { have_f0_ = false, have_ft_ = false, ft_zero_ = false, ft_held_ = 0, prev_err_ = 0; }

  /// The step size controller (Plain unless set).
  void set_step_control(StepControl control) { control_ = control; }

  /// Dense output: the state at t inside the last accepted step [t0, t1]
  /// (the method's continuous extension, docs/theory.md §6.3), projected.
  /// False when no accepted step is held (none yet, or a step was tried since).
  bool dense_output(double t, StateVector& out);

  double max_error = 0;        // largest accepted local error estimate, relative [-] (state and forces)
  double max_force_error = 0;  // its part from the tow and link forces, relative [-]

 private:
  static constexpr int kStages = 4;

  // try_step's passes, in order (docs/theory.md §6.3); y: the step's start
  // [state units], t its time, h the step and hg = h gamma [s], t1 = t + h [s].
  /// f0_ = f(y, t) and the stage solve's factors at t, unless held (have_f0_).
  void start_derivative(const StateVector& y, double t);
  /// W's time column ft_ [state units / s^2] at the step's start: a forward
  /// difference (one evaluation) or extrapolated from the last two; use_ft_.
  void time_column(const StateVector& y, double t, double h);
  /// The kStages transformed stages u_ [state units], one evaluation and solve each.
  void stages(const StateVector& y, double t, double h, double hg);
  /// y1_ = y + sum m_i u_i, rhs_ = y1 - yhat and, embedded, yi_ = yhat [state units].
  void solutions(const StateVector& y, bool embedded);
  /// yhat_ = y1_ - (I - hg W)^-1 rhs_ [state units], projected at t1.
  void filtered_solution(double hg, double t1);
  /// max_q |y1 - yhat|_q / (tol (1 + max(|y|_q, |y1|_q))) [-]; inf if not finite.
  double state_error(const StateVector& y) const;
  /// max over tow and link forces of |F(y1) - F_hat| / (force_scale + |F(y1)|) [-]
  /// (acc: y1's accelerations, or none: 0); inf if not finite.
  double force_error(const Accelerations* acc) const;
  /// The step size factor for the error err [-] (StepControl), in [0.2, 5].
  double step_factor(double err) const;
  /// Rejected: h [s] shrunk by fac (at most 0.9), an extrapolated column dropped.
  void reject(double& h, double fac);
  /// Accepted: y, t advanced to y1_, t1, f(y1) the next start, dense output
  /// kept, error maxima updated (err, ferr [-]), h [s] grown by fac.
  void accept(StateVector& y, double& t, double& h, double t1, double err, double ferr, double fac);

  System& sys_;
  StepWindow window_;  // the step being tried, [t, t + h]: every evaluation's and the Jacobian's
  double tol_, force_scale_;
  ForceEstimate force_estimate_;
  TimeDerivative time_derivative_;
  std::array<std::array<double, kStages>, kStages> a_{}, c_{};  // transformed coefficients
  std::array<double, kStages> m_{}, mhat_{}, alpha_{};          // weights, stage times
  std::array<double, kStages> gsum_{};                          // gamma_i = sum_{j<=i} gamma_ij (f_t term)
  std::array<std::array<double, kStages>, kStages> gi_{};       // Gamma^-1
  double gamma_ = 0;
  bool have_f0_ = false;
  bool last_rejected_ = false;
  StepControl control_ = StepControl::Plain;
  double prev_err_ = 0;   // the last accepted step's error (floored at 1e-4), 0: none since invalidate() [-]
  bool have_ft_ = false;  // ft_ holds f_t at the step's start (kept over rejections)
  bool use_ft_ = false;   // ... and it is nonzero (a difference was taken)
  bool ft_zero_ = false;  // f_t was exactly zero since the last invalidate(): not evaluated
  StateVector ft_;        // df/dt at fixed y at the step's start [state units / s^2]
  // Extrapolated: the last two differences (ftb_ at t_ftb_ the later) since
  // the last invalidate(), how many are held, and whether ft_ is extrapolated.
  StateVector fta_, ftb_;         // [state units / s^2]
  double t_fta_ = 0, t_ftb_ = 0;  // their step starts [s]
  int ft_held_ = 0;
  bool ft_extrapolated_ = false;
  StateVector f0_, fi_, yi_, rhs_, y1_, yhat_, scratch_;
  StateVector y0d_;          // start of the last accepted step (dense output)
  double t0d_ = 0, hd_ = 0;  // its start and size [s]
  bool dense_ = false;       // y0d_, t0d_, hd_ and u_ describe the last accepted step
  std::array<StateVector, kStages> u_;

  EvaluationForces hat_;  // tow and link forces at the embedded solution [N, R_g] (storage reused)
};

}  // namespace towsim
