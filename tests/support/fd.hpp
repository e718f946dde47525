// Finite-difference derivatives with error bounds, for tests that check
// analytic derivatives (tow laws, added-mass forces, Kirchhoff's equations).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <utility>

namespace towsim::testing {

inline constexpr double kFdEps = std::numeric_limits<double>::epsilon();

/// Central difference of f at t with step h, and a bound on its error:
/// 2 (h^2/6 |f'''|) + 8 eps (|f(t+h)| + |f(t-h)|) / h, with |f'''| from a
/// five-point stencil of step H = 1e-2 (accurate to O(H^2), enough for a bound).
template <class F>
std::pair<Eigen::VectorXd, double> fd_with_bound(F f, double t, double h) {
  const Eigen::VectorXd fp = f(t + h), fm = f(t - h);
  const double H = 1e-2;
  const Eigen::VectorXd third = (f(t + 2 * H) - 2 * f(t + H) + 2 * f(t - H) - f(t - 2 * H)) / (2 * H * H * H);
  const double bound = 2 * (h * h / 6 * third.norm()) + 8 * kFdEps * (fp.norm() + fm.norm()) / h;
  return {(fp - fm) / (2 * h), bound};
}

/// Richardson extrapolation of the central differences at h and h/2:
/// (4 D_{h/2} - D_h) / 3 = f' - h^4/480 f^(5) + O(h^6). With h = 1e-3 the
/// truncation is ~2e-15 |f^(5)|; for the trigonometric trajectories used here
/// (frequencies <= 2.6 rad/s, |f^(5)| < 1e3 |f|) that is < 1e-12 |f|. Round-off:
/// each evaluation of f carries ~c eps S, S the size of the terms f is
/// computed from (|f| itself, or `scale` when f is a difference of larger
/// terms, e.g. P = ma (u - (e.u) e)), c <= 10 for these few-operation
/// expressions; the combination amplifies it by (4 * 2 + 1) / 3 / h = 3 / h.
/// Bound: 30 eps S / h + 1e-12 S.
template <class F>
std::pair<Eigen::VectorXd, double> fd_richardson(F f, double t, double h, double scale = 0) {
  const Eigen::VectorXd fp = f(t + h), fm = f(t - h);
  const Eigen::VectorXd d1 = (fp - fm) / (2 * h);
  const Eigen::VectorXd d2 = (f(t + h / 2) - f(t - h / 2)) / h;
  const double fmag = std::max({fp.norm(), fm.norm(), scale});
  return {(4 * d2 - d1) / 3, 30 * kFdEps * fmag / h + 1e-12 * fmag};
}

}  // namespace towsim::testing
