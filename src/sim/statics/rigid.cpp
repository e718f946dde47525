// One attempt at the rigid elements' equilibrium: the plan's sweeps,
// Newton-Krylov and Levenberg-Marquardt in turn, and the verdict on the
// result (docs/theory.md §7 "Check and fallback").
#include <limits>
#include <sstream>
#include <string>

#include "problem.hpp"
#include "strategies.hpp"

namespace towsim::statics {

namespace {

/// The verdict at the iterate: out.residual, converged and, when not, the
/// message (why: the sweeps' reason to stop early, or empty).
void judge(SteadyProblem& p, double floor, const std::string& why, StaticsResult& out) {
  const int N = p.size();
  const Eigen::VectorXd r = p.residual(Eigen::VectorXd::Zero(N));  // p.ws at the result, for the verdict
  out.residual = r.allFinite() ? p.max_alpha(r) : std::numeric_limits<double>::quiet_NaN();  // max drops NaNs
  const double rel = p.relative_moment(r);
  out.converged = !out.interrupted && good_residual(p, floor, r);
  if (out.interrupted) {
    out.message = "statics interrupted by a signal after " + std::to_string(out.iterations) + " iterations";
  } else if (!out.converged) {
    std::ostringstream os;
    os << "statics did not converge: largest angular acceleration left " << out.residual << " rad/s^2 (moment " << rel
       << " of its scale) after " << out.iterations << " iterations";
    if (!why.empty()) os << " (" << why << ")";
    if (N > kDenseLimit)
      os << "; above " << kDenseLimit / 2 << " elements Newton-Krylov (O(n)) stands in for the dense fallback solver";
    os << ". Try: a body.initial_attitude_deg near its flying attitude (yaw relative to the tow heading), fewer "
          "elements, or a weaker current shear; a body without a stable attitude in this flow has no steady tow";
    out.message = os.str();
  }
}

}  // namespace

void solve_rigid(SteadyProblem& p, const Attempt& a, const volatile int* stop_flag, StaticsResult& out) {
  const PhysicalState start = p.base;
  // The O(n) sweeps, when planned (not from a start on the bottom: they leave the contact out).
  std::string why;
  out.iterations = a.sweeps ? solve_by_sweeps(p, stop_flag, why) : 0;
  out.interrupted = why == "interrupted";
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p.size());
  Eigen::VectorXd r = p.residual(zero);
  const double floor = residual_floor(p.model);  // kFloor, or the seabed springs' round-off
  // Newton-Krylov (O(n) per product), when planned, on an unconverged iterate.
  if (!out.interrupted && a.newton_krylov && !good_residual(p, floor, r)) {
    newton_krylov(p, floor, stop_flag, out.iterations);
    r = p.residual(zero);
  }
  // Levenberg-Marquardt, when planned, on an unconverged iterate (or to
  // polish one converged only to the floor), from the better of the
  // iterate and the attempt's start.
  if (!out.interrupted && !(p.max_alpha(r) < kTolerance) && a.dense && (a.polish || !good_residual(p, floor, r))) {
    const PhysicalState swept = p.base;
    p.accept_state(start);
    const Eigen::VectorXd r0 = p.residual(zero);
    if (r.allFinite() && r.norm() < r0.norm())
      p.accept_state(swept);
    else
      r = r0;
    levenberg_marquardt(p, a, floor, stop_flag, r, out);
  }
  // The verdict.
  judge(p, floor, why, out);
}

}  // namespace towsim::statics
