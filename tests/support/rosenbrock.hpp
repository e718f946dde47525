// Helpers for tests of the Rosenbrock-W integrator and its O(n) stage solve
// (docs/theory.md §6.3): fixed steps, and the stage solve's matrix W.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <complex>
#include <cstddef>
#include <numeric>
#include <vector>

#include "towsim/integrators/system.hpp"
#include "towsim/model/model.hpp"

namespace towsim::testing {

/// m integrated by Rosenbrock-W at fixed steps h [s] (error control off).
inline Model fixed_rosenbrock(Model m, double h) {
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e10;
  m.sim.time_step = h;
  m.sim.max_step = h;
  return m;
}

/// Scratch states of rk4_step (sized on first use).
struct Rk4Scratch {
  StateVector k1, k2, k3, k4, yt;
};

/// One classical RK4 step of h [s] from (y, t) on sys, then the projection:
/// the reference integrator of the Rosenbrock tests (far below its limit).
inline void rk4_step(System& sys, StateVector& y, double t, double h, Rk4Scratch& w) {
  const std::size_t N = y.size();
  auto axpy = [&](const StateVector& k, double a) {
    for (std::size_t i = 0; i < N; ++i) w.yt[i] = y[i] + a * k[i];
  };
  const StepWindow window{t, t + h};
  sys.derivative(y, w.k1, t, window);
  w.yt = y;
  axpy(w.k1, h / 2);
  sys.derivative(w.yt, w.k2, t + h / 2, window);
  axpy(w.k2, h / 2);
  sys.derivative(w.yt, w.k3, t + h / 2, window);
  axpy(w.k3, h);
  sys.derivative(w.yt, w.k4, t + h, window);
  for (std::size_t i = 0; i < N; ++i) y[i] += h / 6 * (w.k1[i] + 2 * w.k2[i] + 2 * w.k3[i] + w.k4[i]);
  sys.project(y, t + h);
}

/// W of the stage solve at hg = h gamma [s]: the solve is S = (I - hg W)^-1,
/// so W = (I - S^-1) / hg, S's columns the solves of unit right-hand sides
/// (N the flat state's size). Uses the Jacobian point of the last
/// sys.prepare_stage_solve().
/// `held`: rows the solve never moves (a network line's top rows below a
/// node: zero in every solve), left out of S; their rows and columns of W
/// are zero.
inline Eigen::MatrixXd stage_W(System& sys, std::size_t N, double hg, const std::vector<std::size_t>& held = {}) {
  std::vector<std::size_t> free;
  for (std::size_t i = 0; i < N; ++i)
    if (std::find(held.begin(), held.end(), i) == held.end()) free.push_back(i);
  const auto M = static_cast<Eigen::Index>(free.size());
  const auto at = [&free](Eigen::Index i) { return free[static_cast<std::size_t>(i)]; };
  Eigen::MatrixXd S(M, M);
  StateVector r(N), k(N);
  for (Eigen::Index j = 0; j < M; ++j) {
    std::fill(r.begin(), r.end(), 0.0);
    r[at(j)] = 1;
    sys.stage_solve(hg, r, k);
    for (Eigen::Index i = 0; i < M; ++i) S(i, j) = k[at(i)];
  }
  const Eigen::MatrixXd Wf = (Eigen::MatrixXd::Identity(M, M) - S.inverse()) / hg;
  if (held.empty()) return Wf;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  for (Eigen::Index i = 0; i < M; ++i)
    for (Eigen::Index j = 0; j < M; ++j)
      W(static_cast<Eigen::Index>(at(i)), static_cast<Eigen::Index>(at(j))) = Wf(i, j);
  return W;
}

/// The elements' tangent coordinates of a flat state y (n elements; the
/// state layout's e block at 6 and omega block at 6 + 3n): per element two
/// angles (de = t_a, omega kept normal to the turned e) in columns 2k + a and
/// two rates in columns 2n + 2k + a of P (flat perturbation per coordinate),
/// and Q's matching rows (projections of flat rates on t_a).
inline void element_tangent_maps(const StateVector& y, int n, Eigen::MatrixXd& P, Eigen::MatrixXd& Q) {
  for (int k = 0; k < n; ++k) {
    const Eigen::Index ie = 6 + 3 * k, iw = 6 + 3 * n + 3 * k;
    const Vec3 e(y[ie], y[ie + 1], y[ie + 2]), w(y[iw], y[iw + 1], y[iw + 2]);
    const auto T = tangent_basis(e);
    for (int a = 0; a < 2; ++a) {
      const Vec3 ta = T.col(a);
      for (int d = 0; d < 3; ++d) {
        P(ie + d, 2 * k + a) = ta[d];
        P(iw + d, 2 * k + a) = -w.dot(ta) * e[d];  // omega stays normal to the turned e
        P(iw + d, 2 * n + 2 * k + a) = ta[d];
        Q(2 * k + a, ie + d) = ta[d];
        Q(2 * n + 2 * k + a, iw + d) = ta[d];
      }
    }
  }
}

/// The dynamics' Jacobian in the reduced coordinates of P and Q (Q df/dy P)
/// at (y, t) in the step's window, by central differences of step eps along P's columns.
inline Eigen::MatrixXd reduced_jacobian(System& sys, const StateVector& y, double t, const StepWindow& window,
                                        const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q, double eps) {
  const std::size_t N = y.size();
  Eigen::MatrixXd J(Q.rows(), P.cols());
  for (Eigen::Index j = 0; j < P.cols(); ++j) {
    StateVector yp = y, ym = y, fp, fm;
    for (std::size_t i = 0; i < N; ++i) {
      yp[i] += eps * P(static_cast<Eigen::Index>(i), j);
      ym[i] -= eps * P(static_cast<Eigen::Index>(i), j);
    }
    sys.derivative(yp, fp, t, window);
    sys.derivative(ym, fm, t, window);
    Eigen::VectorXd d(static_cast<Eigen::Index>(N));
    for (std::size_t i = 0; i < N; ++i) d[static_cast<Eigen::Index>(i)] = (fp[i] - fm[i]) / (2 * eps);
    J.col(j) = Q * d;
  }
  return J;
}

/// How well W captures J's stiffest modes: max |(W - J) v| / |J v| over the
/// `count` eigenvectors v of J with the largest |lambda|; J's largest |lambda|
/// and W's in lmax and wmax [1/s].
inline double stiff_mode_mismatch(const Eigen::MatrixXd& J, const Eigen::MatrixXd& W, int count, double& lmax,
                                  double& wmax) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(J);
  const Eigen::VectorXcd& lam = es.eigenvalues();
  std::vector<int> order(static_cast<std::size_t>(J.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(lam[a]) > std::abs(lam[b]); });
  const Eigen::MatrixXcd Jc = J.cast<std::complex<double>>(), Wc = W.cast<std::complex<double>>();
  double worst = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::VectorXcd v = es.eigenvectors().col(order[static_cast<std::size_t>(i)]);
    worst = std::max(worst, (Wc * v - Jc * v).norm() / (Jc * v).norm());
  }
  lmax = std::abs(lam[order[0]]);
  wmax = Eigen::EigenSolver<Eigen::MatrixXd>(W, false).eigenvalues().cwiseAbs().maxCoeff();
  return worst;
}

}  // namespace towsim::testing
