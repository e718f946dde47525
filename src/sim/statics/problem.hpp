// The steady problem the statics strategies share (docs/theory.md §7
// "Statics"): internal to src/sim/statics.cpp and src/sim/statics/.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim::statics {

inline constexpr double kTolerance = 1e-12;  // converged when every |alpha| < this [rad/s^2]
inline constexpr double kFloor = 1e-9;       // ... or below this when round-off stops further progress
inline constexpr int kMaxIterations = 60;
inline constexpr int kMaxDenseOnlyIterations =
    1000;  // ... when the dense solve works alone (a moving tow on the bottom:
           // the contact springs make it ill-conditioned; 100 to 400 on 30 to 60 elements)
inline constexpr double kRelativeFloor =
    1e-12;  // ... or every element's moment left below this of its scale (round-off: ~1e-15)
inline constexpr int kMaxSweeps = 200;            // sweeps of the O(n) solver before it gives up
inline constexpr int kDenseLimit = 1200;          // largest dense (Levenberg-Marquardt) problem [unknowns]: J is N^2
                                                  // doubles, each iteration 2N evaluations of O(n): ~1 s at this size
inline constexpr int kPolishLimit = 200;          // ... and polishing a result converged to the floor only [unknowns]
inline constexpr double kLocalTolerance = 1e-14;  // a part's own balance: |moment| below this times its scale

/// True when the caller asked to stop.
inline bool stopped(const volatile int* stop_flag) { return stop_flag != nullptr && *stop_flag != 0; }

/// The residual's round-off floor [rad/s^2]: kFloor, or with a seabed the
/// noise its springs make of the positions' round-off (problem.cpp).
double residual_floor(const Model& m);

/// Two unit vectors completing e to an orthonormal frame (state.hpp's basis).
inline void tangent_basis(const Vec3& e, Vec3& t1, Vec3& t2) {
  const Eigen::Matrix<double, 3, 2> T = towsim::tangent_basis(e);
  t1 = T.col(0);
  t2 = T.col(1);
}

/// The steady problem: a copy of the model whose tow point moves at V with no acceleration.
struct SteadyProblem {
  Model model;
  Vec3 V;
  Workspace ws;
  PhysicalState base;        // current iterate
  std::vector<Vec3> t1, t2;  // tangent bases of the iterate's elements
  int n;
  int nb;
  int size() const { return 2 * n + 3 * nb; }

  SteadyProblem(const Model& m, const Vec3& v)
      : model(m), V(v), ws(m), n(m.cable.n()), nb(static_cast<int>(m.bodies.size())) {
    model.tow.mode = Tow::Mode::Motion;
    model.tow.pieces.clear();  // a0 = 0; the velocity is set in the state
    finalize_tow(model.tow);
    model.tow.vessel.reset();  // calm water: no ship motion, no waves
    model.fluid.waves.reset();
    t1.assign(static_cast<std::size_t>(n), Vec3::Zero());
    t2.assign(static_cast<std::size_t>(n), Vec3::Zero());
    for (const Element& el : m.cable.elements)
      scale.push_back(element_rot_inertia(el) + 0.25 * (el.mass + el.added_mass) * el.length * el.length);
    for (const Body& b : m.bodies) {
      const Mat6 M = b.rigid_mass + b.fluid_mass;
      scale.push_back(M.bottomRightCorner<3, 3>().trace() / 3 + M(0, 0) * b.link_point.squaredNorm());
    }
  }

  /// The state displaced by x from the iterate (tangent perturbations).
  PhysicalState displaced(const Eigen::VectorXd& x) const {
    PhysicalState s = base;
    for (int k = 0; k < n; ++k) s.e[k] = (base.e[k] + x[2 * k] * t1[k] + x[2 * k + 1] * t2[k]).normalized();
    for (int b = 0; b < nb; ++b) {
      const Vec3 r = x.segment<3>(2 * n + 3 * b);
      const Quat& q0 = base.bodies[static_cast<std::size_t>(b)].q;
      if (r.norm() > 0)
        s.bodies[static_cast<std::size_t>(b)].q = (Quat(Eigen::AngleAxisd(r.norm(), r.normalized())) * q0).normalized();
    }
    return s;
  }

  /// Residual: angular accelerations of elements (in their tangent bases) and
  /// body, each times a scalar inertia about its joint, so that all rows are
  /// moments [N m] of comparable size (a light body's rows would otherwise
  /// dominate the line search).
  Eigen::VectorXd residual(const Eigen::VectorXd& x) {
    const PhysicalState s = displaced(x);
    forward_dynamics(model, s, 0.0, ws);
    Eigen::VectorXd r(size());
    for (int k = 0; k < n; ++k) {
      r[2 * k] = scale[k] * ws.acc.alpha[k].dot(t1[k]);
      r[2 * k + 1] = scale[k] * ws.acc.alpha[k].dot(t2[k]);
    }
    for (int b = 0; b < nb; ++b)
      r.segment<3>(2 * n + 3 * b) = scale[static_cast<std::size_t>(n + b)] *
                                    ws.acc.alpha_b[static_cast<std::size_t>(b)];
    return r;
  }

  /// Largest unscaled angular acceleration of a residual [rad/s^2].
  double max_alpha(const Eigen::VectorXd& r) const {
    double m = 0;
    for (int i = 0; i < 2 * n; ++i) m = std::max(m, std::abs(r[i]) / scale[static_cast<std::size_t>(i / 2)]);
    for (int i = 2 * n; i < r.size(); ++i)
      m = std::max(m, std::abs(r[i]) / scale[static_cast<std::size_t>(n + (i - 2 * n) / 3)]);
    return m;
  }

  std::vector<double> scale;  // inertia about the top joint (elements), about Q (bodies) [kg m^2]

  /// Largest element moment left in r over its moment scale L_k (|f_k-1| + |f_k| + |F_k|),
  /// from the workspace of the evaluation that gave r [-].
  double relative_moment(const Eigen::VectorXd& r) const {
    double m = 0;
    for (int k = 0; k < n; ++k) {
      const auto u = static_cast<std::size_t>(k);
      const double s = model.cable.elements[u].length *
                       (ws.acc.joint_force[u].norm() + ws.acc.joint_force[u + 1].norm() + ws.F[u].norm());
      m = std::max(m, std::hypot(r[2 * k], r[2 * k + 1]) / (s + 1e-300));
    }
    return m;
  }

  /// Largest body angular acceleration in r [rad/s^2].
  double max_body_alpha(const Eigen::VectorXd& r) const {
    double m = 0;
    for (int i = 2 * n; i < r.size(); ++i)
      m = std::max(m, std::abs(r[i]) / scale[static_cast<std::size_t>(n + (i - 2 * n) / 3)]);
    return m;
  }

  /// Make s the iterate and rebuild the tangent bases.
  void accept_state(const PhysicalState& s) {
    base = s;
    for (int k = 0; k < n; ++k) tangent_basis(base.e[k], t1[k], t2[k]);
  }

  /// Move the iterate by x and rebuild the tangent bases.
  void accept(const Eigen::VectorXd& x) {
    base = displaced(x);
    for (int k = 0; k < n; ++k) tangent_basis(base.e[k], t1[k], t2[k]);
  }
};

/// Converged: every angular acceleration in res below `floor`, or (many short
/// elements: their accelerations carry the round-off of tensions far larger
/// than their own loads) every element's moment left below kRelativeFloor of
/// its scale and the bodies' accelerations below `floor`. Reads p.ws of the
/// evaluation that gave res.
inline bool good_residual(const SteadyProblem& p, double floor, const Eigen::VectorXd& res) {
  return res.allFinite() &&
         (p.max_alpha(res) < floor || (p.relative_moment(res) < kRelativeFloor && p.max_body_alpha(res) < floor));
}

}  // namespace towsim::statics
