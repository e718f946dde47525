// Levenberg-Marquardt on all angles with a dense Jacobian (docs/theory.md §7
// "Check and fallback"): the fallback and polish of small problems.
#include <algorithm>

#include "problem.hpp"
#include "strategies.hpp"

namespace towsim::statics {

/// Levenberg-Marquardt from the iterate, whose residual is r, for at most
/// a.dense_iterations iterations: central-difference Jacobian, damping that
/// handles a body's neutral rotations and shrinks to plain Newton near the
/// solution, each trial step's contact points held at their linear moves.
/// Stops below kTolerance (or at the floor with a.dense_to_floor), when no
/// damping lowers |r|, or on the stop flag (out.interrupted). r: the result's.
void levenberg_marquardt(SteadyProblem& p, const Attempt& a, double floor, const volatile int* stop_flag,
                         Eigen::VectorXd& r, StaticsResult& out) {
  const int N = p.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(N);
  Eigen::MatrixXd J(N, N);
  double mu = -1;  // Levenberg-Marquardt damping, set from J on first use
  for (int it = 0; it < a.dense_iterations; ++it, ++out.iterations) {
    if (p.max_alpha(r) < kTolerance) break;
    if (a.dense_to_floor && good_residual(p, floor, r)) break;  // at the seabed's round-off floor: no further progress
    // Jacobian by central differences (each column one O(n) evaluation pair).
    constexpr double h = 1e-7;
    for (int j = 0; j < N && !out.interrupted; ++j) {
      Eigen::VectorXd x = zero;
      x[j] = h;
      const Eigen::VectorXd rp = p.residual(x);
      x[j] = -h;
      J.col(j) = (rp - p.residual(x)) / (2 * h);
      out.interrupted = stopped(stop_flag);
    }
    if (out.interrupted) break;
    // Levenberg-Marquardt: (J^T J + mu I) dx = -J^T r. Damping handles the
    // neutral rotations of a body (a sphere about its link line) and far
    // starting points; it shrinks to plain Newton near the solution.
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    if (mu < 0) mu = 1e-6 * JtJ.diagonal().maxCoeff();
    bool improved = false;
    for (int tries = 0; tries < 40 && !improved; ++tries) {
      Eigen::MatrixXd A = JtJ;
      A.diagonal().array() += mu;
      Eigen::VectorXd dx = A.ldlt().solve(-g);
      const double max_step = 0.5;  // at most ~30 degrees per element per iteration
      if (dx.cwiseAbs().maxCoeff() > max_step) dx *= max_step / dx.cwiseAbs().maxCoeff();
      dx = on_bottom(p, dx);  // the contact points held at their linear moves
      const Eigen::VectorXd rn = p.residual(dx);
      if (rn.allFinite() && rn.norm() < r.norm()) {
        p.accept(dx);
        r = p.residual(zero);
        mu = std::max(mu / 5, 1e-15 * JtJ.diagonal().maxCoeff());
        improved = true;
      } else {
        mu *= 4;
      }
    }
    if (!improved) break;
  }
}

}  // namespace towsim::statics
