// Helpers for tests of the Rosenbrock-W integrator and its O(n) stage solve
// (docs/theory.md §6.3): fixed steps, and the stage solve's matrix W.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstddef>

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
  sys.set_window(t, t + h);
  sys.derivative(y, w.k1, t);
  w.yt = y;
  axpy(w.k1, h / 2);
  sys.derivative(w.yt, w.k2, t + h / 2);
  axpy(w.k2, h / 2);
  sys.derivative(w.yt, w.k3, t + h / 2);
  axpy(w.k3, h);
  sys.derivative(w.yt, w.k4, t + h);
  for (std::size_t i = 0; i < N; ++i) y[i] += h / 6 * (w.k1[i] + 2 * w.k2[i] + 2 * w.k3[i] + w.k4[i]);
  sys.project(y, t + h);
}

/// W of the stage solve at hg = h gamma [s]: the solve is S = (I - hg W)^-1,
/// so W = (I - S^-1) / hg, S's columns the solves of unit right-hand sides
/// (N the flat state's size). Uses the Jacobian point of the last
/// sys.prepare_stage_solve().
inline Eigen::MatrixXd stage_W(System& sys, std::size_t N, double hg) {
  Eigen::MatrixXd S(N, N);
  StateVector r(N), k(N);
  for (std::size_t j = 0; j < N; ++j) {
    std::fill(r.begin(), r.end(), 0.0);
    r[j] = 1;
    sys.stage_solve(hg, r, k);
    for (std::size_t i = 0; i < N; ++i) S(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = k[i];
  }
  return (Eigen::MatrixXd::Identity(S.rows(), S.cols()) - S.inverse()) / hg;
}

}  // namespace towsim::testing
