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
