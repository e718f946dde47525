// An independent planar chain for the free-end flutter test: n equal rigid
// elements in the x-z plane in absolute angles, the tow point at constant
// velocity (V, 0), still water, apparent weight, normal drag only (Pode f = 0)
// and Morison added mass. Lagrange's equations in Kane's form (MODEL §8),
// written here from MODEL §2-3 without any towsim code. docs/validation.md §6.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

namespace towsim::validation {

struct PlanarChain {
  int n = 20;      // elements [-]
  double l = 0.1;  // element length [m]
  double m = 0;    // element mass in air [kg]
  double ma = 0;   // element normal added mass [kg]
  double w = 0;    // element apparent weight [N]
  double kd = 0;   // 1/2 rho Cd D [kg/m^2]
  double V = 2.0;  // tow speed along +x [m/s]

  /// Angular accelerations theta'' of the angles theta_k of e_k = (cos, sin) (x, z) [rad/s^2].
  Eigen::VectorXd accel(const Eigen::VectorXd& th, const Eigen::VectorXd& thd) const {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd S = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, n);  // d v(G_k) / d theta'
    Eigen::Vector2d vP(V, 0), cP(0, 0);               // top joint's velocity, its centripetal acceleration
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d e(std::cos(th[i]), std::sin(th[i])), ep(-std::sin(th[i]), std::cos(th[i]));
      J.col(i) = 0.5 * l * ep;
      const Eigen::Vector2d vG = vP + 0.5 * l * thd[i] * ep;
      const Eigen::Vector2d cG = cP - 0.5 * l * thd[i] * thd[i] * e;
      const Eigen::Matrix2d Mt = m * Eigen::Matrix2d::Identity() +
                                 ma * (Eigen::Matrix2d::Identity() - e * e.transpose());
      const Eigen::Vector2d un = vG - vG.dot(e) * e;
      const Eigen::Vector2d F = Eigen::Vector2d(0, -w) - kd * l * un.norm() * un;
      M += J.transpose() * Mt * J;
      M(i, i) += (m + ma) * l * l / 12;
      S += J.transpose() * (F - Mt * cG);
      J.col(i) = l * ep;  // for the elements below
      vP += l * thd[i] * ep;
      cP -= l * thd[i] * thd[i] * e;
    }
    return M.ldlt().solve(S);
  }

  /// The critical angle phi_c below the horizontal: R sin^2 = w' cos, R = kd V^2 [rad].
  double critical_angle() const {
    double lo = 0, hi = std::numbers::pi / 2;
    for (int it = 0; it < 200; ++it) {
      const double p = 0.5 * (lo + hi);
      (kd * V * V * std::sin(p) * std::sin(p) * l - w * std::cos(p) > 0 ? hi : lo) = p;
    }
    return 0.5 * (lo + hi);
  }

  /// Eigenvalues of the linearisation about the straight steady tow at phi_c
  /// (central differences of accel, step h) [1/s].
  Eigen::VectorXcd eigenvalues(double h = 1e-6) const {
    const Eigen::VectorXd th = Eigen::VectorXd::Constant(n, std::numbers::pi + critical_angle());
    const Eigen::VectorXd thd = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    for (int j = 0; j < n; ++j) A(j, n + j) = 1;
    for (int j = 0; j < 2 * n; ++j) {
      Eigen::VectorXd tp = th, tm = th, dp = thd, dm = thd;
      if (j < n)
        tp[j] += h, tm[j] -= h;
      else
        dp[j - n] += h, dm[j - n] -= h;
      A.block(n, j, n, 1) = (accel(tp, dp) - accel(tm, dm)) / (2 * h);
    }
    return Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
  }
};

}  // namespace towsim::validation
