// Newton-Krylov on all angles, preconditioned by the integrator's stage
// solve (docs/theory.md §7 "Seabed").
#include <algorithm>
#include <cmath>
#include <memory>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/integrators/system.hpp"

namespace towsim::statics {

/// Newton-Krylov on the tangent angles for problems too large for the dense
/// solve (docs/theory.md §7 "Seabed"): each Newton step solves J dx = -r by
/// GMRES, J v by a one-sided difference of the residual (one O(n)
/// evaluation), right-preconditioned by the integrator's O(n) stage solve at
/// the iterate: the linearly implicit step of the dynamics at rest with a
/// large pseudo-step h, dx = h^2 (M + h C + h^2 K)^-1 M alpha, which tends to
/// Newton's step with the stage solve's stiffness K (tension rocking,
/// contact springs, the bodies' load stiffness) and misses only what K
/// leaves out (the loads' dependence on the attitude): GMRES supplies that.
/// Each step backtracked until |r| decreases. Adds its Newton steps to
/// `iterations`; p.base the result. Returns true when the compression guard
/// dropped the result for the start.
bool newton_krylov(SteadyProblem& p, double floor, const volatile int* stop_flag, int& iterations) {
  constexpr int kMaxNewton = 100;        // Newton steps [-]
  constexpr int kKrylov = 80;            // largest Krylov space [-]
  constexpr double kForcing = 1e-4;      // GMRES stops at this fraction of |r| (inexact Newton) [-]
  constexpr double kPseudoStep = 1e3;    // the preconditioner's h [s]: Newton-like, M/h^2 regularises K
  constexpr double kDifference = 1e-7;   // |dx| of the difference quotient [rad]: ~sqrt(eps)
  constexpr double kMaxStep = 0.5;       // largest angle of a Newton step [rad] (as the dense solve)
  constexpr double kCompression = 1e-9;  // an element's compression beyond round-off, of its forces [-]
  Model rm = p.model;
  rm.sim.formulation = Formulation::Default;
  // The bodies' own stiffness only, as in the relaxation (relax): with the
  // pull of the cable below in W, a depressor resting on the bottom rolled
  // over on the way to its steady state (docs/theory.md §6.3).
  rm.sim.line_pull_stiffness = false;
  const double U = p.V.norm();
  rm.tow.pieces.clear();
  if (U > 0) rm.tow.pieces.emplace_back(Ramp{p.V / U, U, 0.0});
  finalize_tow(rm.tow);
  const std::unique_ptr<System> sys = make_system(rm);
  if (!sys->has_stage_solve()) return false;
  const int N = p.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(N);
  StateVector y, dy, rhs, k;
  // x of the preconditioned step for the residual v (P v ~ J^-1 v): only the
  // rates' rows of the flat state are set (the system gives where they are).
  auto precondition = [&](const Eigen::VectorXd& v) {
    std::fill(rhs.begin(), rhs.end(), 0.0);
    for (int i = 0; i < p.n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      const Vec3 a = (v[2 * i] * p.t1[u] + v[2 * i + 1] * p.t2[u]) / p.scale[u];
      const std::size_t o = sys->element_rate_row(u);
      for (std::size_t c = 0; c < 3; ++c) rhs[o + c] = a[static_cast<Eigen::Index>(c)];
    }
    for (int b = 0; b < p.nb; ++b) {
      const auto ub = static_cast<std::size_t>(b);
      const std::size_t o = sys->body_rate_row(ub);
      for (std::size_t c = 0; c < 3; ++c)
        rhs[o + c] = v[2 * p.n + 3 * b + static_cast<int>(c)] / p.scale[static_cast<std::size_t>(p.n) + ub];
    }
    sys->stage_solve(kPseudoStep, rhs, k);
    const double h2 = kPseudoStep * kPseudoStep;
    Eigen::VectorXd x(N);
    for (int i = 0; i < p.n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      const std::size_t o = sys->element_rate_row(u);
      const Vec3 w(k[o], k[o + 1], k[o + 2]);
      const Vec3 de = h2 * w.cross(p.base.e[i]);
      x[2 * i] = -de.dot(p.t1[u]);
      x[2 * i + 1] = -de.dot(p.t2[u]);
    }
    for (int b = 0; b < p.nb; ++b) {
      const std::size_t o = sys->body_rate_row(static_cast<std::size_t>(b));
      x.segment<3>(2 * p.n + 3 * b) = -h2 * Vec3(k[o], k[o + 1], k[o + 2]);
    }
    return x;
  };
  const PhysicalState start = p.base;
  Eigen::VectorXd r = p.residual(zero);
  for (int it = 0; it < kMaxNewton && !stopped(stop_flag); ++it, ++iterations) {
    if (!r.allFinite() || p.max_alpha(r) < kTolerance || good_residual(p, floor, r)) break;
    // The preconditioner's Jacobian at the iterate, at rest.
    PhysicalState s = p.base;
    for (auto& w : s.w) w.setZero();
    for (auto& bs : s.bodies) bs.w.setZero();
    s.r0 = rm.tow.start;
    s.v0 = p.V;
    y = sys->initial(s, 0.0);
    rhs.assign(y.size(), 0.0);
    sys->derivative(y, dy, 0.0);
    sys->prepare_stage_solve(0.0, StepWindow{});
    // GMRES on J P z = -r, dx = P z (one cycle: the preconditioner leaves a
    // few directions to find, 4 to 5 products on the dragged cable).
    const double beta = r.norm();
    Eigen::MatrixXd V(N, kKrylov + 1), Z(N, kKrylov), H = Eigen::MatrixXd::Zero(kKrylov + 1, kKrylov);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(kKrylov + 1), cs(kKrylov), sn(kKrylov);
    V.col(0) = -r / beta;
    g[0] = beta;
    int m = 0;
    while (m < kKrylov) {
      Z.col(m) = precondition(V.col(m));
      const double zn = Z.col(m).norm();
      if (!(zn > 0) || !std::isfinite(zn)) break;
      Eigen::VectorXd w = (p.residual(kDifference / zn * Z.col(m)) - r) * (zn / kDifference);  // J z
      for (int j = 0; j <= m; ++j) {  // Arnoldi, modified Gram-Schmidt
        H(j, m) = V.col(j).dot(w);
        w -= H(j, m) * V.col(j);
      }
      H(m + 1, m) = w.norm();
      if (H(m + 1, m) > 0) V.col(m + 1) = w / H(m + 1, m);
      for (int j = 0; j < m; ++j) {  // the earlier Givens rotations
        const double t = cs[j] * H(j, m) + sn[j] * H(j + 1, m);
        H(j + 1, m) = -sn[j] * H(j, m) + cs[j] * H(j + 1, m);
        H(j, m) = t;
      }
      const double d = std::hypot(H(m, m), H(m + 1, m));
      cs[m] = d > 0 ? H(m, m) / d : 1.0;
      sn[m] = d > 0 ? H(m + 1, m) / d : 0.0;
      H(m, m) = d;
      H(m + 1, m) = 0;
      g[m + 1] = -sn[m] * g[m];
      g[m] *= cs[m];
      ++m;
      if (std::abs(g[m]) <= kForcing * beta || !(d > 0)) break;
    }
    if (m == 0 || !(H(m - 1, m - 1) != 0)) break;
    Eigen::VectorXd dx = Z.leftCols(m) * H.topLeftCorner(m, m).triangularView<Eigen::Upper>().solve(g.head(m));
    if (!dx.allFinite()) break;
    if (dx.cwiseAbs().maxCoeff() > kMaxStep) dx *= kMaxStep / dx.cwiseAbs().maxCoeff();
    bool better = false;
    for (int ls = 0; ls < 30 && !better; ++ls, dx *= 0.5) {
      const Eigen::VectorXd step = on_bottom(p, dx);  // the touchdown held at its linear move
      const Eigen::VectorXd rn = p.residual(step);
      if (rn.allFinite() && rn.norm() < r.norm()) {
        p.accept(step);
        r = p.residual(zero);
        better = true;
      }
    }
    if (!better) break;
  }
  // Newton finds unstable equilibria as well (an inverted chain standing in
  // compression): every element must hang along the pull on it, tension
  // T_k = e_k . (F_k/2 - f_k) >= 0 to round-off (as the sweeps' stable
  // side), else the start is kept.
  p.residual(zero);  // p.ws at the result
  for (int i = 0; i < p.n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const int b = p.ws.body_at[u + 1];
    const Vec3& below = b >= 0 ? p.ws.acc.link_force[static_cast<std::size_t>(b)] : p.ws.acc.joint_force[u + 1];
    const Vec3 pull = 0.5 * p.ws.F[u] - below;
    if (p.base.e[i].dot(pull) < -kCompression * (p.ws.F[u].norm() + below.norm())) {
      p.accept_state(start);
      p.residual(zero);
      return true;
    }
  }
  return false;
}

}  // namespace towsim::statics
