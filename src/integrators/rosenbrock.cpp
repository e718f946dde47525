// Rosenbrock-W ROS34PW2 with error control on state and forces (docs/theory.md §6.3).
#include "towsim/integrators/rosenbrock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace towsim {

namespace {

inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

// ROS34PW2 (Rang & Angermann, BIT 45 (2005) 761-787), in the form
// (I - h gamma J) k_i = h f(y + sum_j alpha_ij k_j) + h J sum_j gamma_ij k_j,
// y1 = y + sum_i b_i k_i; bhat: the embedded order-2 solution.
constexpr double kGamma = 4.3586652150845900e-01;
constexpr double kSafety = 0.95;  // step size controller's safety factor [-]
// f_t's forward difference over kTimeDifference h: far above the 1e-12 |t|
// by which law times are moved inside a step's window (StepWindow::law_time),
// far below the inputs' time scales. Measured on paper-3d-turn: 1e-3 and
// 1e-5 give the same steps (1836, 1837) and errors; any f_t keeps the order
// (it is W's time column).
constexpr double kTimeDifference = 1e-3;  // [-]
constexpr double kAlpha[4][4] = {{0, 0, 0, 0},
                                 {8.7173304301691801e-01, 0, 0, 0},
                                 {8.4457060015369423e-01, -1.1299064236484185e-01, 0, 0},
                                 {0, 0, 1, 0}};
constexpr double kGam[4][4] = {{kGamma, 0, 0, 0},
                               {-8.7173304301691801e-01, kGamma, 0, 0},
                               {-9.0338057013044082e-01, 5.4180672388095326e-02, kGamma, 0},
                               {2.4212380706095346e-01, -1.2232505839045147e+00, 5.4526025533510214e-01, kGamma}};
constexpr double kB[4] = {2.4212380706095346e-01, -1.2232505839045147e+00, 1.5452602553351020e+00, kGamma};
constexpr double kBhat[4] = {3.7810903145819369e-01, -9.6042292212423178e-02, 0.5, 2.1793326075422950e-01};
// Continuous extension: y(t + theta h) = y + sum_i b_i(theta) k_i with
// b_i(theta) = sum_j kBtheta[i][j] theta^(j+1); b_i(1) = b_i (PETSc's
// TSROSWRA34PW2 interpolation table). Measured on a test ODE: local error
// O(h^4) with the exact Jacobian, O(h^3) with an arbitrary W (docs/theory.md §6.3).
constexpr double kBtheta[4][3] = {{1.0564298455794094, -1.3864882699759573, 0.5721822314575016},
                                  {2.296429974281067, -8.262611700275677, 4.742931142090097},
                                  {-1.307599564525376, 7.250979895056055, -4.398120075195578},
                                  {-1.045260255335102, 2.398120075195581, -0.9169932983520199}};

/// Up to kMaxTerms weighted vectors w_l u_l of a combination (below).
constexpr int kMaxTerms = 4;  // a stage's 3 earlier stages and f_t [-]
struct Terms {
  std::array<const double*, kMaxTerms> u{};
  std::array<double, kMaxTerms> w{};
  int n = 0;
  void add(const double* v, double weight) { u[idx(n)] = v, w[idx(n++)] = weight; }
};

/// out[q] = x[q] (times *s when s is given) + w_0 u_0[q] + w_1 u_1[q] + ...,
/// added in that order: NL terms unrolled, so that the compiler vectorises
/// the pass (a loop over a run-time count of terms it does not).
template <int NL>
void combine_n(std::size_t n, double* __restrict out, const double* __restrict x, const double* s, const Terms& t) {
  std::array<const double*, NL + 1> u{};
  std::array<double, NL + 1> w{};
  for (std::size_t l = 0; l < NL; ++l) u[l] = t.u[l], w[l] = t.w[l];
  if (s) {
    const double sc = *s;
    for (std::size_t q = 0; q < n; ++q) {
      double v = sc * x[q];
      for (std::size_t l = 0; l < NL; ++l) v += w[l] * u[l][q];
      out[q] = v;
    }
  } else {
    for (std::size_t q = 0; q < n; ++q) {
      double v = x[q];
      for (std::size_t l = 0; l < NL; ++l) v += w[l] * u[l][q];
      out[q] = v;
    }
  }
}

/// combine_n for t's count of terms.
void combine(std::size_t n, double* out, const double* x, const double* s, const Terms& t) {
  switch (t.n) {
    case 0:
      return combine_n<0>(n, out, x, s, t);
    case 1:
      return combine_n<1>(n, out, x, s, t);
    case 2:
      return combine_n<2>(n, out, x, s, t);
    case 3:
      return combine_n<3>(n, out, x, s, t);
    default:  // kMaxTerms
      return combine_n<kMaxTerms>(n, out, x, s, t);
  }
}

/// The step's solutions from its start y and its kStages stages u_i with
/// weights m_i and m_i - mhat_i, one pass.
struct Solutions {
  const double *y, *u0, *u1, *u2, *u3;
  std::array<double, 4> m, dm;
  /// y1 = y + sum m_i u_i, d = y1 - yhat = sum dm_i u_i (each added in the
  /// order i = 0, 1, ...) and, WithEmbedded, yhat = y1 - d.
  template <bool WithEmbedded>
  void pass(std::size_t n, double* y1, double* d, double* yhat) const {
    run<WithEmbedded>(n, y, u0, u1, u2, u3, y1, d, yhat);
  }
  // Restrict-qualified parameters: the compiler vectorises without run-time
  // overlap checks (the vectors are distinct).
  template <bool WithEmbedded>
  void run(std::size_t n, const double* __restrict y0, const double* __restrict v0, const double* __restrict v1,
           const double* __restrict v2, const double* __restrict v3, double* __restrict y1, double* __restrict d,
           double* __restrict yhat) const {
    for (std::size_t q = 0; q < n; ++q) {
      double v = y0[q], e = 0.0;
      v += m[0] * v0[q], e += dm[0] * v0[q];
      v += m[1] * v1[q], e += dm[1] * v1[q];
      v += m[2] * v2[q], e += dm[2] * v2[q];
      v += m[3] * v3[q], e += dm[3] * v3[q];
      y1[q] = v, d[q] = e;
      if constexpr (WithEmbedded) yhat[q] = v - e;
    }
  }
};

/// The step-end side evaluation started and not yet finished: cancelled
/// (waited for, dropped) if the step leaves early by an exception, so that no
/// worker reads the integrator's vectors after try_step.
class SideForces {
 public:
  explicit SideForces(System& sys) : sys_(sys) {}
  ~SideForces() { cancel(); }
  SideForces(const SideForces&) = delete;
  SideForces& operator=(const SideForces&) = delete;
  void start(const StateVector& y_side, double t_side, const StepWindow& window, EvaluationForces& out) {
    sys_.start_side_forces(y_side, t_side, window, out);
    started_ = true;
  }
  void finish(const StateVector& y, StateVector& dy, double t, const StepWindow& window) {
    started_ = false;  // finish_side_forces ends it, even by an exception
    sys_.finish_side_forces(y, dy, t, window);
  }
  void cancel() noexcept {
    if (started_) sys_.cancel_side_forces();
    started_ = false;
  }

 private:
  System& sys_;
  bool started_ = false;
};

}  // namespace

RosenbrockW::RosenbrockW(System& sys, double tol, double force_scale, ForceEstimate force_estimate,
                         TimeDerivative time_derivative)
    : sys_(sys),
      tol_(tol),
      force_scale_(force_scale),
      force_estimate_(force_estimate),
      time_derivative_(time_derivative),
      gamma_(kGamma) {
  // Transformed variables u_i = sum_j gamma_ij k_j (Hairer & Wanner IV.7):
  // (I - h gamma J) u_i = h gamma f(y + sum_j a_ij u_j) + gamma sum_j c_ij u_j,
  // a = alpha Gamma^-1, c = diag(1/gamma) - Gamma^-1, m = b^T Gamma^-1.
  double Gi[4][4] = {};  // Gamma^-1 (lower triangular), by forward substitution
  for (int j = 0; j < kStages; ++j) {
    Gi[j][j] = 1 / kGam[j][j];
    for (int i = j + 1; i < kStages; ++i) {
      double s = 0;
      for (int l = j; l < i; ++l) s += kGam[i][l] * Gi[l][j];
      Gi[i][j] = -s / kGam[i][i];
    }
  }
  for (int i = 0; i < kStages; ++i)
    for (int j = 0; j < kStages; ++j) gi_[i][j] = Gi[i][j];
  for (int i = 0; i < kStages; ++i) {
    alpha_[i] = 0;
    for (int j = 0; j < kStages; ++j) {
      alpha_[i] += kAlpha[i][j];
      double s = 0;
      for (int l = 0; l < kStages; ++l) s += kAlpha[i][l] * Gi[l][j];
      a_[i][j] = s;
      c_[i][j] = (i == j ? 1 / kGamma : 0) - Gi[i][j];
      m_[j] += kB[i] * Gi[i][j];
      mhat_[j] += kBhat[i] * Gi[i][j];
      if (j <= i) gsum_[i] += kGam[i][j];
    }
  }
}

bool RosenbrockW::try_step(StateVector& y, double& t, double& h) {
  const double t1 = t + h, hg = h * gamma_;
  dense_ = false;  // u_ is about to change
  window_ = {t, t1};
  // f0 = f(y, t) and the stage solve's factors, unless held from the last step.
  start_derivative(y, t);
  // W's time column f_t at the step's start: a difference, extrapolated, or none.
  if (time_derivative_ != TimeDerivative::None && !have_ft_ && !ft_zero_) time_column(y, t, h);
  // Stages u_i: one evaluation and one O(n) solve each.
  stages(y, t, h, hg);
  // y1, y1 - yhat and (embedded force estimate) the embedded solution, one pass.
  const bool embedded = force_estimate_ == ForceEstimate::Embedded;
  solutions(y, embedded);
  // The solution whose forces are compared with y1's, projected: the embedded
  // one needs no filter solve, so its evaluation starts now, on the worker
  // thread when the system has one (simulation.threads), during the filter
  // solve and the state error, and is dropped if the step is rejected
  // (speculative, docs/performance.md "Speculative step-end evaluation").
  // Serially it only runs with f(y1), below.
  SideForces side(sys_);
  if (embedded) {
    sys_.project(yi_, t1);
    side.start(yi_, t1, window_, hat_);
  }
  // Filtered error estimate: yhat = y1 - (I - hg J)^-1 (y1 - yhat), projected;
  // with the filtered force estimate, the solution whose forces are compared.
  filtered_solution(hg, t1);
  if (!embedded) side.start(yhat_, t1, window_, hat_);
  sys_.project(y1_, t1);
  // State error: |y1 - yhat| against tol (1 + |y|), max norm.
  double err = state_error(y);
  // Force error (only if the state error passes): the side evaluation's
  // forces and f(y1), the next step's start (last on the system's
  // workspace), then y1's tow and link forces against the side's.
  double ferr = 0;
  if (err <= 1) {
    const Accelerations* acc = sys_.last_accelerations();
    side.finish(y1_, fi_, t1, window_);
    ferr = force_error(acc);
    err = std::max(err, ferr / tol_);
  } else {
    side.cancel();  // rejected: as serially, never evaluated (what it threw dropped)
  }
  // Step size control: rejected, a smaller h; accepted, the step's end.
  const double fac = step_factor(err);
  if (!(err <= 1)) {
    reject(h, fac);
    return false;
  }
  accept(y, t, h, t1, err, ferr, fac);
  return true;
}

void RosenbrockW::start_derivative(const StateVector& y, double t) {
  if (have_f0_) return;
  sys_.derivative(y, f0_, t, window_);
  sys_.prepare_stage_solve(t, window_);
  have_f0_ = true;
}

// The explicit time dependence (tow law, waves, winch schedule): time as a
// state whose column in W is f_t, here (f(y, t + dt) - f0) / dt at the
// step's start (ROW form, Hairer & Wanner IV.7: the stages get
// gamma_i h^2 f_t). W's time column may be anything without losing the
// order (it is part of W); left out (zero, as before), paper-3d-turn took
// 4367 steps at tol 1e-5 instead of 1836, its tow force 3.5x less
// accurate (docs/performance.md "W's time column").
// Exactly zero (a steady tow: the inputs do not change on this piece of
// the tow law) it is not evaluated again before the next invalidate(), the
// law's next breakpoint; were the inputs to change meanwhile, W's time
// column would be zero, as without it: the order holds either way.
// Extrapolated: on every other accepted step (the one after a difference,
// two differences held since the last invalidate(), the tow law's last
// breakpoint) the column is f_t extrapolated linearly in time from the
// last two differences, without an evaluation: O(h^2) from f_t along the
// solution where a stale column is O(h) off. Measured (docs/performance.md
// "W's time column extrapolated"): a column one step stale multiplied
// the rejected tries 6-14x; extrapolated, 6-8 % fewer evaluations at the
// same accuracy. A rejected try's difference is kept for the retry, an
// extrapolated column is not (reject()).
void RosenbrockW::time_column(const StateVector& y, double t, double h) {
  const std::size_t N = y.size();
  const bool extrapolated = time_derivative_ == TimeDerivative::Extrapolated;
  if (extrapolated && ft_held_ == 2 && !ft_extrapolated_ && use_ft_) {
    // Linear in time through the last two differences.
    const double s = (t - t_ftb_) / (t_ftb_ - t_fta_);  // [-]
    for (std::size_t q = 0; q < N; ++q) ft_[q] = ftb_[q] + s * (ftb_[q] - fta_[q]);
    ft_extrapolated_ = true;
  } else {
    // The forward difference over kTimeDifference h, one evaluation.
    const double dt = kTimeDifference * h;
    use_ft_ = dt > 1e-9 * std::max(1.0, std::abs(t));  // else law_time's shift would dominate: no column
    if (use_ft_) {
      sys_.derivative_time_shift(y, scratch_, t + dt, window_);  // y's inertias kept (y alone sets them)
      ft_.resize(N);
      for (std::size_t q = 0; q < N; ++q) ft_[q] = (scratch_[q] - f0_[q]) / dt;
      ft_zero_ = std::all_of(ft_.begin(), ft_.end(), [](double v) { return v == 0; });
      use_ft_ = !ft_zero_;
    }
    // The last two differences, in order; none here (no column): the
    // extrapolation spans consecutive differences only.
    if (extrapolated && use_ft_) {
      fta_.swap(ftb_);
      ftb_ = ft_;
      t_fta_ = t_ftb_, t_ftb_ = t;
      ft_held_ = std::min(ft_held_ + 1, 2);
    } else {
      ft_held_ = 0;
    }
    ft_extrapolated_ = false;
  }
  have_ft_ = true;
}

// Stage 1 reuses f0. Each combination is one pass over the state, its terms
// added in the order j = 0, 1, ... (the same round-off as a pass per term).
void RosenbrockW::stages(const StateVector& y, double t, double h, double hg) {
  const std::size_t N = y.size();
  for (int i = 0; i < kStages; ++i) {
    const StateVector* f = &f0_;
    Terms terms;
    if (i > 0) {
      // f(y + sum_j a_ij u_j, t + alpha_i h).
      for (int j = 0; j < i; ++j)
        if (a_[i][j] != 0) terms.add(u_[idx(j)].data(), a_[i][j]);
      // The step's last evaluations, on a worker thread's side (threads 2),
      // come one evaluation and two stage solves after this one's start.
      if (i == 1) sys_.expect_side_evaluation();
      yi_.resize(N);
      combine(N, yi_.data(), y.data(), nullptr, terms);
      sys_.derivative(yi_, fi_, t + alpha_[i] * h, window_);
      f = &fi_;
    }
    // (I - hg W) u_i = hg f_i + sum_j gamma c_ij u_j + hg gamma_i h f_t.
    terms = Terms{};
    for (int j = 0; j < i; ++j) terms.add(u_[idx(j)].data(), gamma_ * c_[i][j]);
    if (use_ft_ && gsum_[i] != 0) terms.add(ft_.data(), hg * gsum_[i] * h);  // last, as before
    rhs_.resize(N);
    combine(N, rhs_.data(), f->data(), &hg, terms);
    sys_.stage_solve(hg, rhs_, u_[i]);
  }
}

void RosenbrockW::solutions(const StateVector& y, bool embedded) {
  const std::size_t N = y.size();
  std::array<double, kStages> dm{};
  for (int i = 0; i < kStages; ++i) dm[idx(i)] = m_[i] - mhat_[i];
  y1_.resize(N);
  rhs_.resize(N);
  yi_.resize(N);
  static_assert(kStages == 4, "Solutions is written for four stages");
  const Solutions sol{y.data(), u_[0].data(), u_[1].data(), u_[2].data(), u_[3].data(), m_, dm};
  if (embedded)
    sol.pass<true>(N, y1_.data(), rhs_.data(), yi_.data());
  else
    sol.pass<false>(N, y1_.data(), rhs_.data(), nullptr);
}

// Filtered (Shampine): the embedded solution is not L-stable (|R(inf)| =
// 0.48); unfiltered, the damped stiff modes (element rocking) would
// dominate the state error estimate.
void RosenbrockW::filtered_solution(double hg, double t1) {
  const std::size_t N = y1_.size();
  sys_.stage_solve(hg, rhs_, scratch_);
  yhat_.resize(N);
  for (std::size_t q = 0; q < N; ++q) yhat_[q] = y1_[q] - scratch_[q];
  sys_.project(yhat_, t1);
}

double RosenbrockW::state_error(const StateVector& y) const {
  const std::size_t N = y.size();
  double err = 0;
  for (std::size_t q = 0; q < N; ++q) {
    const double sc = tol_ * (1 + std::max(std::abs(y[q]), std::abs(y1_[q])));
    err = std::max(err, std::abs(y1_[q] - yhat_[q]) / sc);
  }
  if (!std::isfinite(err)) err = std::numeric_limits<double>::infinity();
  return err;
}

// Against the embedded solution UNFILTERED (runs), against tol (scale +
// |F|). The forces read the stiff components directly (a rocking element's
// tension): filtered, their error is divided by ~hg|lambda| and the
// estimate is optimistic at large steps (2.5e-3 of the peak force on
// km-turn-100 at tol 1e-4 against 4.4e-4 unfiltered, docs/performance.md
// "Force error estimate").
double RosenbrockW::force_error(const Accelerations* acc) const {
  double ferr = 0;
  if (acc) {
    auto rel = [&](const Vec3& a, const Vec3& b) { return (a - b).norm() / (force_scale_ + a.norm()); };
    ferr = rel(acc->tow_force, hat_.tow_force);
    for (std::size_t b = 0; b < hat_.link_force.size(); ++b)
      ferr = std::max(ferr, rel(acc->link_force[b], hat_.link_force[b]));
  }
  if (!std::isfinite(ferr)) ferr = std::numeric_limits<double>::infinity();
  return ferr;
}

// Order 2 estimate -> exponent 1/3, safety 0.95, factor in [0.2, 5].
// Measured against a PI (Gustafsson) controller and safeties 0.8..1
// (docs/performance.md): this plain controller took the fewest
// evaluations; 1.0 rejects a third.
double RosenbrockW::step_factor(double err) const {
  // PI after an accepted step with a predecessor: the last error's memory damps the
  // controller's overshoot. Measured on sea-state-tow (docs/performance.md "Sea states"):
  // 4.6 % of the steps rejected instead of 28 %, 3.6 % fewer evaluations.
  if (control_ == StepControl::PI && prev_err_ > 0 && err > 0 && err <= 1)
    return std::clamp(kSafety * std::pow(err, -0.7 / 3.0) * std::pow(prev_err_, 0.4 / 3.0), 0.2, 5.0);
  return err == 0 ? 5.0 : std::clamp(kSafety * std::pow(err, -1.0 / 3.0), 0.2, 5.0);
}

void RosenbrockW::reject(double& h, double fac) {
  h *= std::min(fac, 0.9);
  last_rejected_ = true;
  // An extrapolated column (O(h^2) off f_t) is not kept: the retry takes
  // the difference (paper-3d-turn: 123 rejected tries against 147 kept).
  if (ft_extrapolated_) have_ft_ = false;
}

void RosenbrockW::accept(StateVector& y, double& t, double& h, double t1, double err, double ferr, double fac) {
  // No growth right after a rejection.
  if (last_rejected_) fac = std::min(fac, 1.0);
  prev_err_ = std::max(err, 1e-4);
  last_rejected_ = false;
  // y1 and f(y1) become the next step's start; y the dense output's.
  y.swap(y1_);
  y0d_.swap(y1_);
  t0d_ = t, hd_ = h, dense_ = true;
  t = t1;
  f0_.swap(fi_);
  have_ft_ = false;
  sys_.prepare_stage_solve(t1, window_);  // the Jacobian at y1, in the step's window
  max_error = std::max(max_error, err * tol_);
  max_force_error = std::max(max_force_error, ferr);
  h *= fac;
}

bool RosenbrockW::dense_output(double t, StateVector& out) {
  if (!dense_ || hd_ <= 0) return false;
  const double th = std::clamp((t - t0d_) / hd_, 0.0, 1.0);
  // Weights on the transformed stages u_j: w_j = sum_i b_i(theta) (Gamma^-1)_ij.
  std::array<double, kStages> w{};
  for (int i = 0; i < kStages; ++i) {
    const double bi = th * (kBtheta[i][0] + th * (kBtheta[i][1] + th * kBtheta[i][2]));
    for (int j = 0; j < kStages; ++j) w[j] += bi * gi_[i][j];
  }
  out = y0d_;
  for (int j = 0; j < kStages; ++j)
    for (std::size_t q = 0; q < out.size(); ++q) out[q] += w[j] * u_[j][q];
  sys_.project(out, t);
  return true;
}

}  // namespace towsim
