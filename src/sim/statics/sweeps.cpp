// The O(n) sweeps (docs/theory.md §7 "Sweeps"): each part balanced from the
// bottom up given the force from below.
#include <algorithm>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim::statics {

// ---------------------------------------------------------------------------
// O(n) steady solve (docs/theory.md §7.2): with every point moving at V and
// no acceleration, each part's balance involves only its own loads and the
// force from the part below it. A sweep from the bottom up solves each part
// for its attitude (an element: 2 angles, a body: 3) given that force, then
// passes on the force through its top joint. Loads depend on positions only
// through the water's velocity at a depth (a current profile); positions come
// from the previous sweep, so sweeps repeat until the joints stop moving (in
// a uniform current the first sweep is the answer).
// ---------------------------------------------------------------------------

/// Moment about element k's top joint P of everything on it, in the plane
/// normal to e: its loads (at G = P + L/2 e) and the force f it exerts
/// on the part below through its bottom joint [N m, R_g]. F: its loads [N].
Vec3 element_moment(const Model& m, const Element& el, const Vec3& e, const Vec3& P, const Vec3& V, const Vec3& f,
                    Vec3& F) {
  Vec3 M;
  const double L = el.length;
  element_loads(m, el, e, Vec3::Zero(), V, P + 0.5 * L * e, 0.0, F, M);
  return e.cross(0.5 * L * F - L * f) + M - e.dot(M) * e;
}

/// Element k's axis balancing its loads and the force f through its bottom
/// joint, from the start e0 (kept on the stable side: the element hangs along
/// the pull 0.5 F - f on it). Newton in the tangent plane, steps limited and
/// backtracked. Returns false when no balance was found.
bool solve_element(const Model& m, const Element& el, const Vec3& P, const Vec3& V, const Vec3& f, Vec3& e, Vec3& F) {
  const double L = el.length;
  for (int it = 0; it < 60; ++it) {
    Vec3 t1, t2;
    tangent_basis(e, t1, t2);
    const Vec3 r = element_moment(m, el, e, P, V, f, F);
    const double scale = L * (0.5 * F.norm() + f.norm()) + 1e-300;
    const Eigen::Vector2d g(r.dot(t1), r.dot(t2));
    if (g.norm() <= kLocalTolerance * scale) return e.dot(0.5 * F - f) >= 0;
    // Jacobian by central differences in the tangent plane.
    constexpr double h = 1e-7;  // [rad]
    Eigen::Matrix2d J;
    Vec3 Fh;
    for (int j = 0; j < 2; ++j) {
      const Vec3& t = j == 0 ? t1 : t2;
      const Vec3 rp = element_moment(m, el, (e + h * t).normalized(), P, V, f, Fh);
      const Vec3 rm = element_moment(m, el, (e - h * t).normalized(), P, V, f, Fh);
      J.col(j) = Eigen::Vector2d((rp - rm).dot(t1), (rp - rm).dot(t2)) / (2 * h);
    }
    Eigen::Vector2d dx = J.fullPivLu().solve(-g);
    if (!dx.allFinite()) return false;
    if (dx.norm() > 0.3) dx *= 0.3 / dx.norm();  // at most ~17 degrees a step
    // Backtrack until the moment shrinks.
    bool better = false;
    for (int ls = 0; ls < 30 && !better; ++ls, dx *= 0.5) {
      const Vec3 en = (e + dx[0] * t1 + dx[1] * t2).normalized();
      const Vec3 rn = element_moment(m, el, en, P, V, f, Fh);
      if (Eigen::Vector2d(rn.dot(t1), rn.dot(t2)).norm() < g.norm()) e = en, better = true;
    }
    if (!better) return g.norm() <= 1e3 * kLocalTolerance * scale && e.dot(0.5 * F - f) >= 0;
  }
  element_moment(m, el, e, P, V, f, F);  // F of the best axis found
  return false;
}

/// One sweep from the bottom up at the positions of p.base (in p.ws): every
/// part balanced given the force from below. A part without balance keeps
/// the best attitude found and the sweep goes on (the next sweep may find it
/// once the positions have moved). Returns an empty string, "interrupted", or
/// which part had no balance (the lowest).
std::string sweep_once(SteadyProblem& p, PhysicalState& s, const volatile int* stop_flag) {
  const Model& m = p.model;
  Workspace& ws = p.ws;
  compute_kinematics(m, s, ws);  // positions of the previous sweep
  for (auto& v : ws.vP) v = p.V;
  attachment_loads(m, 0.0, ws);
  Vec3 f = -ws.Fa.back();  // force through the joint below the element
  Vec3 F;
  std::string failed;
  for (int k = p.n - 1; k >= 0; --k) {
    const auto uk = static_cast<std::size_t>(k);
    if ((k & 4095) == 0 && stopped(stop_flag)) return "interrupted";
    const int bi = ws.body_at[uk + 1];
    if (bi >= 0) {
      const auto ub = static_cast<std::size_t>(bi);
      const Body& body = m.bodies[ub];
      BodyWork& bw = ws.body[ub];
      const Vec3 Q = ws.P[uk] + m.cable.elements[uk].length * s.e[uk];  // upper link at the previous sweep
      if (!solve_body(m, body, Q, p.V, f, s.bodies[ub].q, bw) && failed.empty())
        failed = "no balance of " + (body.inline_body ? "body " + body.name : std::string("the body"));
      f = bw.hw.head<3>() - bw.Fb + (body.inline_body ? f : Vec3::Zero());  // link force F_L
    }
    if (!solve_element(m, m.cable.elements[uk], ws.P[uk], p.V, f, s.e[uk], F) && failed.empty())
      failed = "no balance of element " + std::to_string(k + 1);
    if (!s.e[uk].allFinite()) return failed;
    f -= F + ws.Fa[uk];
  }
  return failed;
}

/// The O(n) solve: sweeps until the joints stop moving, then the dynamics'
/// own angular accelerations as the residual. Returns the number of sweeps;
/// p.base holds the result; `why` is empty or why it stopped early.
int solve_by_sweeps(SteadyProblem& p, const volatile int* stop_flag, std::string& why) {
  PhysicalState s = p.base;
  const double length = p.model.cable.total_length();
  std::vector<Vec3> P0 = p.ws.P;
  int sweeps = 0;
  while (sweeps < kMaxSweeps) {
    if (stopped(stop_flag)) {
      why = "interrupted";
      break;
    }
    why = sweep_once(p, s, stop_flag);
    ++sweeps;
    if (why == "interrupted" || !s.e.front().allFinite()) break;
    // Converged when the positions the loads saw no longer change.
    P0 = p.ws.P;
    compute_kinematics(p.model, s, p.ws);
    double moved = 0;
    for (std::size_t k = 0; k < P0.size(); ++k) moved = std::max(moved, (p.ws.P[k] - P0[k]).norm());
    if (moved <= 1e-13 * (length + 1)) break;
  }
  p.accept_state(s);
  return sweeps;
}

}  // namespace towsim::statics
