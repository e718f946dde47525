// Elastic elements' stretch on the rigid solution (docs/theory.md §7 "Elastic elements").
#include <algorithm>
#include <cmath>
#include <string>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/dynamics/elastic.hpp"

namespace towsim::statics {

/// Elastic elements (docs/theory.md §5.4, §7): the equilibrium of a chain of
/// inextensible elements of the current lengths l_k, then each elastic
/// element's tension T_k = e_k . (F_k/2 - f_k) (the axial part of its
/// d-equation at rest) gives l_k = L_k (1 + T_k/EA); repeat until the
/// lengths no longer change. The tensions depend on the lengths only through
/// the geometry (depth in a current profile, the body's place), so this
/// converges in a few passes, each a warm-started solve_rigid of the attempt
/// that converged (a).
void stretch(const Model& elastic, SteadyProblem& p, const Attempt& a, const volatile int* stop_flag,
             StaticsResult& out) {
  constexpr int kMaxPasses = 30;
  constexpr double kLengthTolerance = 1e-13;  // relative change of every length [-]: strain to round-off
  const auto& els = elastic.cable.elements;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    forward_dynamics(p.model, p.base, 0.0, p.ws);
    double change = 0;
    for (std::size_t k = 0; k < els.size(); ++k) {
      if (!is_elastic(els[k])) continue;
      const int b = p.ws.body_at[k + 1];
      const Vec3& below = b >= 0 ? p.ws.acc.link_force[static_cast<std::size_t>(b)] : p.ws.acc.joint_force[k + 1];
      const double T = std::max(0.0, p.base.e[k].dot(0.5 * p.ws.F[k] - below));
      const double l = els[k].length * (1 + T / els[k].axial_stiffness);
      change = std::max(change, std::abs(l - p.base.length[k]) / els[k].length);
      p.base.length[k] = l;
      p.model.cable.elements[k].length = l;
    }
    if (change <= kLengthTolerance) return;
    solve_rigid(p, a, stop_flag, out);
    if (!out.converged) return;
  }
  out.converged = false;
  out.message = "statics did not converge: the elastic elements' lengths still change after " +
                std::to_string(kMaxPasses) + " passes";
}

}  // namespace towsim::statics
