// Steady-tow statics (docs/theory.md §7): zero accelerations of the dynamics' own equations.
#include "towsim/sim/statics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "statics_internal.hpp"
#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"

namespace towsim {

namespace {

constexpr double kTolerance = 1e-12;  // converged when every |alpha| < this [rad/s^2]
constexpr double kFloor = 1e-9;       // ... or below this when round-off stops further progress
constexpr int kMaxIterations = 60;
constexpr int kMaxDenseOnlyIterations =
    1000;  // ... when the dense solve works alone (a moving tow on the bottom:
           // the contact springs make it ill-conditioned; 100 to 400 on 30 to 60 elements)
constexpr double kRelativeFloor =
    1e-12;                         // ... or every element's moment left below this of its scale (round-off: ~1e-15)
constexpr int kMaxSweeps = 200;    // sweeps of the O(n) solver before it gives up
constexpr int kDenseLimit = 1200;  // largest dense (Levenberg-Marquardt) problem [unknowns]: J is N^2 doubles,
                                   // each iteration 2N evaluations of O(n): ~1 s at this size
constexpr int kPolishLimit = 200;  // ... and polishing a result converged to the floor only [unknowns]
constexpr double kLocalTolerance = 1e-14;  // a part's own balance: |moment| below this times its scale

/// True when the caller asked to stop.
bool stopped(const volatile int* stop_flag) { return stop_flag != nullptr && *stop_flag != 0; }

/// The residual's round-off floor [rad/s^2]: kFloor, or with a seabed the
/// noise its springs make of the positions' round-off. A joint at distance R
/// from the origin carries R eps of position error, k l R eps of force, and
/// an element of length L, mass per metre mu (with added mass) turns that into
/// an angular acceleration of about 3 k R eps / (mu L) (the force at its end,
/// over its inertia about the other end); ten times that is the floor.
double residual_floor(const Model& m) {
  if (!m.seabed) return kFloor;
  const double eps = std::numeric_limits<double>::epsilon();
  double R = m.tow.start.norm() + m.cable.total_length();  // largest joint distance [m]
  for (double d : m.seabed->depth) R = std::max(R, d + m.cable.total_length());
  double floor = kFloor;
  for (const Element& el : m.cable.elements) {
    const double mu = (el.mass + el.added_mass) / el.length;  // [kg/m]
    floor = std::max(floor, 30 * m.seabed->stiffness * R * eps / (mu * el.length));
  }
  return floor;
}

/// Two unit vectors completing e to an orthonormal frame (state.hpp's basis).
void tangent_basis(const Vec3& e, Vec3& t1, Vec3& t2) {
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
  bool sweeps = true;  // solve by O(n) sweeps first (false: straight to the dense solve)
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

/// How far the body's lowest point in contact lies below its link Q [m, R_g]
/// along the bottom's normal n, at attitude R: its hull's contact points
/// (hull_points, the contact's own rule) and an in-line body's lower link Q2
/// [m, >= 0].
double body_drop(const Seabed& sb, const Body& body, const Mat3& R, const Vec3& Q, const Vec3& n) {
  double drop = 0;
  const Vec3 O = Q - R * body.link_point;  // the body origin [m, R_g]
  hull_points(sb, body, O, R, [&](const Vec3& p, double) { drop = std::max(drop, -n.dot(p - Q)); });
  if (body.inline_body) drop = std::max(drop, -n.dot(R * (body.lower_link_point - body.link_point)));
  return drop;
}

/// The step x with the contact points held at their linear moves along the
/// bottom's normal (docs/theory.md §7 "Seabed"): a step in the tangent
/// angles moves each joint by sum L_i (x_i . t_i) to first order and by
/// -sum L_i |x_i|^2 / 2 e_i at second (a body's turn likewise moves its
/// lower link); below steep suspended elements that shifts the first point
/// in contact (and the whole lying part with it) along the normal, where the
/// contact springs (k l ~ 1e5 N/m per m) turn it into moments far above the
/// linear model's (the full Newton step on 1000 dragged elements raised |r|
/// 200-fold). Walking down, each element ending at a joint in contact or at
/// a body touching the bottom is turned in its plane towards the normal by
/// the angle that cancels the second-order shift accumulated down to its
/// end; the correction's own error is of fourth order. x unchanged without
/// a seabed.
Eigen::VectorXd on_bottom(SteadyProblem& p, const Eigen::VectorXd& x) {
  const Model& m = p.model;
  if (!m.seabed) return x;
  const Seabed& sb = *m.seabed;
  compute_kinematics(m, p.base, p.ws);  // the iterate's joints and links
  Eigen::VectorXd y = x;
  Vec3 shift = Vec3::Zero();  // exact less linear move of the current joint [m]
  // Element i's exact less linear move of its end under the step y.
  auto second = [&](int i) {
    const auto u = static_cast<std::size_t>(i);
    const Vec3 dt = y[2 * i] * p.t1[u] + y[2 * i + 1] * p.t2[u];
    return Vec3(m.cable.elements[u].length * ((p.base.e[i] + dt).normalized() - p.base.e[i] - dt));
  };
  for (int i = 0; i < p.n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double L = m.cable.elements[u].length;
    const Vec3 end = p.ws.P[u] + L * p.base.e[i];  // the element's lower end (a body's Q) [m]
    Vec3 d = second(i);
    const int bi = p.ws.body_at[u + 1];
    bool touches = sb.gap(end) < 0;
    if (bi >= 0) {
      const auto ub = static_cast<std::size_t>(bi);
      touches = sb.gap(end) <
                body_drop(sb, m.bodies[ub], p.base.bodies[ub].q.toRotationMatrix(), end, sb.normal(end.x()));
    }
    if (touches) {
      const Vec3 nb = sb.normal(end.x());
      const double a = nb.dot(p.t1[u]), b = nb.dot(p.t2[u]);
      const double reach = L * (a * a + b * b);  // [m/rad]: the element's turn towards the normal
      if (reach > 1e-3 * L) {                    // (an element along the normal cannot correct it)
        const double err = nb.dot(shift + d);    // [m]
        y[2 * i] -= err * a / reach;
        y[2 * i + 1] -= err * b / reach;
        d = second(i) - L * (err / reach) * (a * p.t1[u] + b * p.t2[u]);  // the turn's own move is linear
      }
    }
    shift += d;
    if (bi >= 0 && m.bodies[static_cast<std::size_t>(bi)].inline_body) {
      // Through an in-line body: its turn's exact less linear move of Q2 - Q.
      const auto ub = static_cast<std::size_t>(bi);
      const Body& body = m.bodies[ub];
      const Vec3 r = y.segment<3>(2 * p.n + 3 * bi);
      const Vec3 link = p.base.bodies[ub].q.toRotationMatrix() * (body.lower_link_point - body.link_point);
      if (r.norm() > 0) shift += Eigen::AngleAxisd(r.norm(), r.normalized()) * link - link - r.cross(link);
    }
  }
  return y;
}

/// With a seabed, the starting chain does not pass below it: walking down
/// from the tow point, the element that would cross the bottom is turned in
/// its vertical plane (towards where the chain heads horizontally, else
/// against the tow velocity, else +x) so that its end rests on the bottom, and
/// every element after it lies along the bottom in that heading. An element
/// ending at a body's link Q ends high enough for the body (at its attitude)
/// to rest on its lowest point (body_drop), rising from the bottom if needed;
/// the cable below an in-line body then starts from its lower link.
/// Dragged, an in-line body touching the bottom is first turned (least
/// rotation) to lie along the element above it, its lower link Q2 behind
/// its upper link Q: upright, the pull at Q, the friction at its lowest
/// point and the cable behind at Q2 all turn it the same way, and the
/// solve followed it over backwards onto its upper link, a kink of the
/// contact where it stalled (2.1 rad/s^2 left on the dragged depressor of
/// test_seabed.cpp); along the cable it converges to the body leaning into
/// the pull.
void lay_on_seabed(SteadyProblem& p) {
  const Model& m = p.model;
  if (!m.seabed) return;
  const Seabed& sb = *m.seabed;
  PhysicalState& s = p.base;
  Vec3 h = Vec3::UnitX();  // horizontal heading along the bottom [-]
  if (std::hypot(p.V.x(), p.V.y()) > 0) h = -Vec3(p.V.x(), p.V.y(), 0).normalized();
  for (std::size_t k = 0; k < s.e.size(); ++k) {
    compute_kinematics(m, s, p.ws);  // the top of element k+1 after the changes above
    if (const int bi = k > 0 ? p.ws.body_at[k] : -1; bi >= 0 && p.V.norm() > 0) {
      const auto ub = static_cast<std::size_t>(bi);
      const Body& body = m.bodies[ub];
      Quat& q = s.bodies[ub].q;
      const Vec3 axis = q.toRotationMatrix() * (body.link_point - body.lower_link_point);  // Q2 -> Q [m]
      const Vec3 Q = p.ws.body[ub].Q;
      if (body.inline_body && axis.norm() > 0 &&
          sb.gap(Q) < body_drop(sb, body, q.toRotationMatrix(), Q, sb.normal(Q.x()))) {
        q = (Quat::FromTwoVectors(axis, -s.e[k - 1]) * q).normalized();
        compute_kinematics(m, s, p.ws);  // the cable below from the turned body's Q2
        p.sweeps = false;                // (the sweeps, contact left out, lift it off: relax first)
      }
    }
    const Vec3 top = p.ws.P[k];
    const double L = m.cable.elements[k].length;
    Vec3& e = s.e[k];
    if (std::hypot(e.x(), e.y()) > 1e-6) h = Vec3(e.x(), e.y(), 0).normalized();
    // The gap its end needs: a body hanging there rests on its lowest point.
    // Only at rest: dragged, a start that puts the body above the bottom
    // leads the solve to a spurious inverted column (the in-line sphere
    // dragged at 0.5 m/s in test_seabed.cpp); unlifted it stays unsolved.
    double need = 0;  // [m]
    if (const int bi = p.ws.body_at[k + 1]; bi >= 0 && !(p.V.norm() > 0)) {
      const auto ub = static_cast<std::size_t>(bi);
      need = body_drop(sb, m.bodies[ub], s.bodies[ub].q.toRotationMatrix(), top + L * e, sb.normal((top + L * e).x()));
    }
    if (sb.gap(top + L * e) >= need) continue;
    // Along the bottom at the top joint, in the heading h.
    const Vec3 n = sb.normal(top.x());
    const Vec3 along = (h - h.dot(n) * n).normalized();
    auto dir = [&](double th) { return Vec3(std::sin(th) * h - std::cos(th) * Vec3::UnitZ()); };
    const double highest = need > 0 ? M_PI : 0.5 * M_PI;  // rising to a body, else at most along the bottom [rad]
    if (need <= 0 && (sb.gap(top) <= 0 || sb.gap(top + L * dir(highest)) < 0)) {
      e = along;
      continue;
    }
    // Bisection on the angle from the vertical: the end at the gap it needs.
    double lo = 0, hi = highest;  // gap(lo) < need <= gap(hi)
    if (sb.gap(top + L * dir(lo)) >= need || sb.gap(top + L * dir(hi)) < need) lo = hi;
    for (int it = 0; it < 60 && lo < hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (sb.gap(top + L * dir(mid)) < need ? lo : hi) = mid;
    }
    e = dir(hi).normalized();
  }
}

/// With a seabed and a moving tow (no body, no attachment), the start of a
/// cable dragged along the bottom: its last m elements lie along the bottom
/// behind the tow (against V), each carried by the bottom's normal force,
/// with the friction mu s N against V (s = U / sqrt(U^2 + v_s^2), the law's
/// smoothing); the suspended part hangs above as the fixed-point sweep of
/// sweep_from_bottom aligns it. m is the fewest lying elements whose
/// suspended part reaches down to the bottom (bisection: more lying cable
/// pulls harder, flattening the suspended part). The bottom's normal is taken
/// at the previous trial's joints. False when not applicable (lay_on_seabed
/// lays the cable then).
bool lay_along_bottom(SteadyProblem& p) {
  const Model& m = p.model;
  const double U = p.V.norm();
  if (!m.seabed || !m.bodies.empty() || !m.cable.attachments.empty()) return false;
  const Seabed& sb = *m.seabed;
  Vec3 h = Vec3::UnitX();  // the lying part's heading [-]
  if (U > 0) {
    if (std::hypot(p.V.x(), p.V.y()) < 1e-9 * U) return false;
    h = -Vec3(p.V.x(), p.V.y(), 0).normalized();
  } else {
    // At rest on a sloped bottom (a flat one: lay_on_seabed): downslope
    // from the tow point, the only side the cable can lie on with tension.
    if (sb.depth.size() < 2) return false;
    const Vec3 n0 = sb.normal(m.tow.start.x());
    if (std::abs(n0.x()) > 1e-12) h = Vec3(n0.x() > 0 ? 1.0 : -1.0, 0, 0);
  }
  const double slip = U > 0 ? U / std::hypot(U, sb.slip_speed) : 0.0;  // the friction's smoothing at V [-]
  const Vec3 Vhat = U > 0 ? Vec3(p.V / U) : Vec3::Zero();
  PhysicalState& s = p.base;
  compute_kinematics(m, s, p.ws);
  // Gap of the touchdown joint above the bottom with `lying` elements on it
  // (s.e set accordingly) [m].
  auto shoot = [&](int lying) {
    Vec3 f = Vec3::Zero();  // force of the part above on the lying part [N]
    for (int k = p.n - 1; k >= p.n - lying; --k) {
      const auto uk = static_cast<std::size_t>(k);
      const Vec3 n = sb.normal(p.ws.G[uk].x());
      const Vec3 e = (h - h.dot(n) * n).normalized();
      Vec3 F, M;
      element_loads(m, m.cable.elements[uk], e, Vec3::Zero(), p.V, p.ws.G[uk], 0.0, F, M);
      const double N = std::max(0.0, -F.dot(n));
      f -= F + N * n - sb.friction * slip * N * Vhat;
      s.e[uk] = e;
    }
    for (int k = p.n - lying - 1; k >= 0; --k) {
      const auto uk = static_cast<std::size_t>(k);
      const Element& el = m.cable.elements[uk];
      Vec3 e = s.e[uk], F, M;
      for (int it = 0; it < 30; ++it) {
        element_loads(m, el, e, Vec3::Zero(), p.V, p.ws.G[uk], 0.0, F, M);
        const Vec3 d = 0.5 * F - f;
        if (d.norm() < 1e-300) break;
        e = d.normalized();
      }
      s.e[uk] = e;
      f -= F;
    }
    compute_kinematics(m, s, p.ws);
    return sb.gap(p.ws.P[static_cast<std::size_t>(p.n - lying)]);
  };
  int lo = 0, hi = p.n;              // gap(lo) < 0 <= gap(hi) once bracketed
  if (shoot(lo) >= 0) return false;  // the hanging cable clears the bottom: nothing lies on it
  if (shoot(hi) < 0) return false;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (shoot(mid) < 0 ? lo : hi) = mid;
  }
  shoot(hi);
  shoot(hi);  // the normals at this trial's own joints
  return true;
}

/// Starting point: from the bottom up, each element aligned with the force it
/// carries (moment balance about its top joint, its own load at mid-length);
/// a body passes on the force balancing its own loads, an attachment its load.
void sweep_from_bottom(SteadyProblem& p) {
  const Model& m = p.model;
  PhysicalState& s = p.base;
  s = PhysicalState::hanging(m);
  s.r0 = m.tow.start;
  s.v0 = p.V;
  // Bodies start facing the tow's heading: their initial attitude is taken
  // relative to it (a fish towed along +y starts yawed 90 deg), so that any
  // heading converges to the body flying nose first.
  if (std::hypot(p.V.x(), p.V.y()) > 0) {
    const Quat heading(Eigen::AngleAxisd(std::atan2(p.V.y(), p.V.x()), Vec3::UnitZ()));
    for (auto& b : s.bodies) b.q = (heading * b.q).normalized();
  }
  compute_kinematics(m, s, p.ws);  // depths of the hanging guess (for a current profile)
  for (auto& v : p.ws.vP) v = p.V;
  attachment_loads(m, 0.0, p.ws);
  Vec3 f = -p.ws.Fa.back();  // force through the joint below the element
  for (int k = p.n - 1; k >= 0; --k) {
    const int bi = p.ws.body_at[static_cast<std::size_t>(k + 1)];
    if (bi >= 0) {
      BodyWork& bw = p.ws.body[static_cast<std::size_t>(bi)];
      bw.vO = p.V;
      bw.w.setZero();
      body_loads(m.fluid, m.bodies[static_cast<std::size_t>(bi)], 0.0, bw);
      f -= bw.Fb;  // link force balancing the body's loads and the cable below
    }
    const Element& el = m.cable.elements[static_cast<std::size_t>(k)];
    Vec3 e = s.e[static_cast<std::size_t>(k)], F, M;
    for (int it = 0; it < 30; ++it) {
      element_loads(m, el, e, Vec3::Zero(), p.V, p.ws.G[static_cast<std::size_t>(k)], 0.0, F, M);
      const Vec3 d = 0.5 * F - f;
      if (d.norm() < 1e-300) break;
      e = d.normalized();
    }
    s.e[static_cast<std::size_t>(k)] = e;
    f -= F + p.ws.Fa[static_cast<std::size_t>(k)];
  }
  // Laid along the bottom: the sweeps (which leave the contact out) would
  // lift it off; relaxation and the dense solve take over (solve_statics).
  if (lay_along_bottom(p))
    p.sweeps = false;
  else
    lay_on_seabed(p);
  p.accept(Eigen::VectorXd::Zero(p.size()));
}

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

/// A body's steady kinematics and loads at attitude q hanging from Q, all
/// moving at V without rotating (as compute_kinematics and compute_loads).
void steady_body(const Model& m, const Body& body, const Quat& q, const Vec3& Q, const Vec3& V, BodyWork& bw) {
  bw.R = q.toRotationMatrix();
  bw.w.setZero();
  bw.Q = Q;
  bw.vQ = V;
  bw.rQ = bw.R * body.link_point;
  bw.O = Q - bw.rQ;
  bw.vO = V;
  bw.rQ2 = bw.R * body.lower_link_point;
  body_inertia(m.fluid, body, bw, 0.0);
  body_loads(m.fluid, body, 0.0, bw);
}

/// The body's moment balance about its link Q with the cable below pulling
/// f2 at Q2 (in-line bodies): the recursion's rhs at zero acceleration [N m].
Vec3 body_moment(const Body& body, const BodyWork& bw, const Vec3& f2) {
  const Vec3 hl = bw.hw.head<3>(), ha = bw.hw.tail<3>();
  Vec3 r = bw.Mb - bw.rQ.cross(bw.Fb) - ha + bw.rQ.cross(hl);
  if (body.inline_body) r += bw.rQ.cross(f2) - bw.rQ2.cross(f2);
  return r;
}

/// The size of the moments in the body's balance at bw: of each load's moment about Q [N m].
double body_moment_scale(const BodyWork& bw, const Vec3& f2) {
  return bw.Mb.norm() + bw.rQ.norm() * (bw.Fb.norm() + bw.hw.head<3>().norm() + f2.norm()) + bw.hw.tail<3>().norm() +
         bw.rQ2.norm() * f2.norm() + 1e-300;
}

/// Body attitude balancing its moments about Q, from q: Newton with
/// minimum-norm steps (a sphere's rotation about its link line is neutral).
/// On return bw holds the body at q; false when no balance was found.
bool newton_body(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2, Quat& q,
                 BodyWork& bw) {
  BodyWork tmp = bw;
  auto rotated = [&q](const Vec3& x) {
    return x.norm() > 0 ? Quat((Quat(Eigen::AngleAxisd(x.norm(), x.normalized())) * q).normalized()) : q;
  };
  for (int it = 0; it < 100; ++it) {
    steady_body(m, body, q, Q, V, bw);
    const Vec3 g = body_moment(body, bw, f2);
    const double scale = body_moment_scale(bw, f2);
    if (g.norm() <= kLocalTolerance * scale) return true;
    constexpr double h = 1e-7;  // [rad]
    Mat3 J;
    for (int j = 0; j < 3; ++j) {
      steady_body(m, body, rotated(h * Vec3::Unit(j)), Q, V, tmp);
      const Vec3 gp = body_moment(body, tmp, f2);
      steady_body(m, body, rotated(-h * Vec3::Unit(j)), Q, V, tmp);
      J.col(j) = (gp - body_moment(body, tmp, f2)) / (2 * h);
    }
    // Damped least squares: a neutral rotation (J's null space) takes no step.
    Mat3 A = J.transpose() * J;
    A.diagonal().array() += 1e-10 * A.diagonal().maxCoeff() + 1e-300;
    Vec3 dx = A.ldlt().solve(-J.transpose() * g);
    if (!dx.allFinite()) return false;
    if (dx.norm() > 0.3) dx *= 0.3 / dx.norm();
    bool better = false;
    for (int ls = 0; ls < 30 && !better; ++ls, dx *= 0.5) {
      steady_body(m, body, rotated(dx), Q, V, tmp);
      if (body_moment(body, tmp, f2).norm() < g.norm()) q = rotated(dx), better = true;
    }
    if (!better) {
      steady_body(m, body, q, Q, V, bw);
      return g.norm() <= 1e3 * kLocalTolerance * scale;
    }
  }
  steady_body(m, body, q, Q, V, bw);  // bw at the best attitude found
  return false;
}

constexpr double kStiffnessStep = 1e-5;  // [rad] central differences of the moment about Q: truncation
                                         // ~1e-10, round-off ~1e-11 of its scale
constexpr double kNeutral = 1e-6;        // an eigenvalue of K's symmetric part below -kNeutral times the
                                         // moment scale (per radian) is unstable; above, zero to round-off

/// The body's balance at q classified: its restoring stiffness K = -dM/dtheta
/// (rotations theta in R_g, central differences), the diagonal of K in body
/// axes and the smallest eigenvalue of K's symmetric part; stable when that
/// eigenvalue is not below -kNeutral of the moment scale. bw: a copy of the
/// body's work (its control surfaces' state). `neutral` (may be null): the
/// rotation axes (R_g) of eigenvalues within that band.
BodyEquilibrium classify_balance(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2,
                                 const Quat& q, BodyWork bw, std::vector<Vec3>* neutral = nullptr) {
  steady_body(m, body, q, Q, V, bw);
  const double scale = body_moment_scale(bw, f2);
  Mat3 K;
  for (int j = 0; j < 3; ++j) {
    steady_body(m, body, Quat(Eigen::AngleAxisd(kStiffnessStep, Vec3::Unit(j)) * q).normalized(), Q, V, bw);
    const Vec3 gp = body_moment(body, bw, f2);
    steady_body(m, body, Quat(Eigen::AngleAxisd(-kStiffnessStep, Vec3::Unit(j)) * q).normalized(), Q, V, bw);
    K.col(j) = -(gp - body_moment(body, bw, f2)) / (2 * kStiffnessStep);
  }
  const Mat3 R = q.toRotationMatrix();
  const Mat3 Kb = R.transpose() * K * R;  // in body axes
  const Eigen::SelfAdjointEigenSolver<Mat3> sym(0.5 * (K + K.transpose()));
  BodyEquilibrium e;
  e.q = q;
  e.rpy_deg = roll_pitch_yaw(q) * (180.0 / M_PI);
  e.stiffness = Kb.diagonal();
  e.min_stiffness = sym.eigenvalues()[0];
  e.stable = e.min_stiffness >= -kNeutral * scale;
  if (neutral != nullptr)
    for (int i = 0; i < 3; ++i)
      if (std::abs(sym.eigenvalues()[i]) < kNeutral * scale) neutral->push_back(sym.eigenvectors().col(i));
  return e;
}

/// The trims newton_body restarts from: pitched -75..75 deg in steps of 15 deg, level in the tow's heading.
std::vector<Quat> trim_starts(const Vec3& V) {
  const Quat heading(Eigen::AngleAxisd(std::hypot(V.x(), V.y()) > 0 ? std::atan2(V.y(), V.x()) : 0.0, Vec3::UnitZ()));
  std::vector<Quat> out;
  for (int deg = -75; deg <= 75; deg += 15)
    out.push_back((heading * Quat(Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitY()))).normalized());
  return out;
}

/// newton_body from q, else from several trims (trim_starts). Newton from
/// the attitude a body held may not reach a balance far from it
/// (two-part-tow's depressor flies nose up below about 560 kg, 24 deg at
/// 500 kg, from a level start), or may reach a statically unstable one: a
/// stable balance from q is kept; otherwise the stable balance from the
/// trims nearest q, or when none is stable, the (unstable) balance from q,
/// or when Newton from q found none, the balance from the trims nearest q.
bool solve_body(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2, Quat& q, BodyWork& bw) {
  const Quat start = q;
  const bool held = newton_body(m, body, Q, V, f2, q, bw);
  if (held && classify_balance(m, body, Q, V, f2, q, bw).stable) return true;
  const Quat from_start = q;
  const BodyWork at_start = bw;  // the best attitude from q, kept when no start balances
  bool found = held, found_stable = false;
  double nearest = held ? q.angularDistance(start) : 0.0;  // angle from q to the balance kept [rad]
  BodyWork trial = bw;
  for (Quat t : trim_starts(V)) {
    if (!newton_body(m, body, Q, V, f2, t, trial)) continue;
    const bool stable = classify_balance(m, body, Q, V, f2, t, trial).stable;
    const double angle = t.angularDistance(start);
    // A stable balance beats an unstable one; then the nearer.
    if (!found || (stable && !found_stable) || (stable == found_stable && angle < nearest)) {
      found = true;
      found_stable = stable;
      nearest = angle;
      q = t;
      bw = trial;
    }
  }
  if (!found || (held && !found_stable)) {
    q = from_start;
    bw = at_start;
  }
  return found;
}

/// The balances of each body at the equilibrium `state` of `m` (waves off,
/// the steady tow), its links' places in ws (forward_dynamics at state) and
/// the in-line bodies' forces on the cable below `below` (StaticsResult's
/// equilibria).
std::vector<BodyEquilibria> find_equilibria(const Model& m, const PhysicalState& state, const Workspace& ws,
                                            const Vec3& V, const std::vector<Vec3>& below) {
  std::vector<BodyEquilibria> out(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    const Vec3 Q = ws.body[b].Q;
    const Vec3 f2 = body.inline_body ? below[b] : Vec3::Zero();
    const Quat solved = state.bodies[b].q;
    if (m.seabed &&
        m.seabed->gap(Q) < body_drop(*m.seabed, body, solved.toRotationMatrix(), Q, m.seabed->normal(Q.x())))
      continue;  // on the bottom: the contact is not part of steady_body's balance
    BodyEquilibria& eq = out[b];
    eq.analysed = true;
    std::vector<std::vector<Vec3>> neutral;  // each balance's neutral rotation axes
    auto add = [&](const Quat& q) {
      for (std::size_t i = 0; i < eq.balances.size(); ++i) {
        Eigen::AngleAxisd d(q * eq.balances[i].q.conjugate());
        Vec3 r = d.angle() * d.axis();
        if (d.angle() > M_PI) r = (d.angle() - 2 * M_PI) * d.axis();
        for (const Vec3& a : neutral[i]) r -= a.dot(r) * a;  // rotations along a neutral axis: the same balance
        if (r.norm() <= kDistinctBalance) return;
      }
      neutral.emplace_back();
      eq.balances.push_back(classify_balance(m, body, Q, V, f2, q, ws.body[b], &neutral.back()));
    };
    add(solved);  // the balance of the equilibrium solved: index 0 until sorted
    BodyWork bw = ws.body[b];
    for (Quat t : trim_starts(V))
      if (newton_body(m, body, Q, V, f2, t, bw)) add(t);
    std::vector<std::size_t> order(eq.balances.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
      return eq.balances[i].rpy_deg.y() > eq.balances[j].rpy_deg.y();
    });
    std::vector<BodyEquilibrium> sorted;
    for (std::size_t i = 0; i < order.size(); ++i) {
      sorted.push_back(eq.balances[order[i]]);
      if (order[i] == 0) eq.chosen = static_cast<int>(i);
    }
    eq.balances = std::move(sorted);
  }
  return out;
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

}  // namespace

Vec3 final_tow_velocity(const Tow& tow) {
  Vec3 v = Vec3::Zero();
  for (const auto& piece : tow.pieces) {
    if (const auto* ramp = std::get_if<Ramp>(&piece)) v += ramp->speed * ramp->direction.normalized();
    if (const auto* track = std::get_if<Track>(&piece); track != nullptr && track->time.size() > 1)
      v += track->at(track->time.back()).vel;
  }
  // Manoeuvres: the course's last speed and heading replace the horizontal part.
  CourseState c;
  if (final_course(tow, c)) {
    v = Vec3(c.U * c.h.x(), c.U * c.h.y(), v.z());
  }
  return v;
}

namespace {

/// Converged: every angular acceleration in res below `floor`, or (many short
/// elements: their accelerations carry the round-off of tensions far larger
/// than their own loads) every element's moment left below kRelativeFloor of
/// its scale and the bodies' accelerations below `floor`. Reads p.ws of the
/// evaluation that gave res.
bool good_residual(const SteadyProblem& p, double floor, const Eigen::VectorXd& res) {
  return res.allFinite() &&
         (p.max_alpha(res) < floor || (p.relative_moment(res) < kRelativeFloor && p.max_body_alpha(res) < floor));
}

bool newton_krylov(SteadyProblem& p, double floor, const volatile int* stop_flag, int& iterations);

/// The equilibrium of the problem's (inextensible) elements from its current
/// iterate: the O(n) sweeps, then for small problems Levenberg-Marquardt;
/// sets out.iterations, residual, converged, interrupted, message.
void solve_rigid(SteadyProblem& p, const volatile int* stop_flag, StaticsResult& out) {
  const PhysicalState start = p.base;
  // The O(n) sweeps first (not with a moving tow on the bottom: see relax).
  std::string why;
  out.iterations = p.sweeps ? solve_by_sweeps(p, stop_flag, why) : 0;
  out.interrupted = why == "interrupted";
  const int N = p.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(N);
  Eigen::VectorXd r = p.residual(zero);
  // Fallback: Levenberg-Marquardt on all angles with a dense Jacobian, for
  // problems the sweeps left unconverged (up to kDenseLimit unknowns), or
  // converged only to the floor (up to kPolishLimit: a cheap polish), from
  // the better of their result and their start.
  // Converged: every angular acceleration below kFloor, or (many short
  // elements: their accelerations carry the round-off of tensions far larger
  // than their own loads) every element's moment left below kRelativeFloor of
  // its scale and the bodies' accelerations below kFloor. Reads p.ws of the
  // evaluation that gave r.
  const double floor = residual_floor(p.model);  // kFloor, or the seabed springs' round-off
  const auto good = [&p, floor](const Eigen::VectorXd& res) { return good_residual(p, floor, res); };
  // Newton-Krylov first (O(n) per product) with cable on the bottom: above
  // the dense solve's limit, and from the relaxation above kPolishLimit.
  // Bending springs likewise: the sweeps balance each element without them.
  const bool coupled = p.model.seabed.has_value() || has_bending(p.model);
  if (!out.interrupted && coupled && !good(r) && (N > kDenseLimit || (!p.sweeps && N > kPolishLimit))) {
    newton_krylov(p, floor, stop_flag, out.iterations);
    r = p.residual(zero);
  }
  const bool dense = !out.interrupted && !(p.max_alpha(r) < kTolerance) &&
                     (N <= kPolishLimit || (!good(r) && N <= kDenseLimit));
  if (dense) {
    const PhysicalState swept = p.base;
    p.accept_state(start);
    const Eigen::VectorXd r0 = p.residual(zero);
    if (r.allFinite() && r.norm() < r0.norm())
      p.accept_state(swept);
    else
      r = r0;
  }
  Eigen::MatrixXd J(dense ? N : 0, dense ? N : 0);
  double mu = -1;  // Levenberg-Marquardt damping, set from J on first use
  const int max_iterations = p.sweeps ? kMaxIterations : kMaxDenseOnlyIterations;
  for (int it = 0; dense && it < max_iterations; ++it, ++out.iterations) {
    if (p.max_alpha(r) < kTolerance) break;
    if (!p.sweeps && good(r)) break;  // at the seabed's round-off floor: no further progress to make
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
  r = p.residual(Eigen::VectorXd::Zero(N));  // p.ws at the result, for good() and the message
  out.residual = r.allFinite() ? p.max_alpha(r) : std::numeric_limits<double>::quiet_NaN();  // max drops NaNs
  const double rel = p.relative_moment(r);
  out.converged = !out.interrupted && good(r);
  if (out.interrupted) {
    out.message = "statics interrupted by a signal after " + std::to_string(out.iterations) + " iterations";
  } else if (!out.converged) {
    std::ostringstream os;
    os << "statics did not converge: largest angular acceleration left " << out.residual << " rad/s^2 (moment " << rel
       << " of its scale) after " << out.iterations << " iterations";
    if (!why.empty()) os << " (" << why << ")";
    if (N > kDenseLimit)
      os << "; above " << kDenseLimit / 2 << " elements Newton-Krylov (O(n)) stands in for the dense fallback solver";
    os << ". Try: a body.initial_attitude_deg near its flying attitude (yaw relative to the tow heading), fewer "
          "elements, or a weaker current shear; a body without a stable attitude in this flow has no steady tow";
    out.message = os.str();
  }
}

/// Dynamic relaxation towards the steady tow (docs/theory.md §7 "Seabed"):
/// the dynamics themselves from the iterate, the tow point moving at V,
/// integrated by Rosenbrock-W (the contact springs do not bound its step),
/// with kinetic damping: whenever the chain's rotational kinetic energy
/// (relative to the steady motion) passes a peak, every element and body
/// rotation rate is set to zero, which leaves every point moving at V again.
/// The water's drag and the bottom's friction damp as well. Stops when the
/// angular accelerations of the state at rest fall below `target`, after
/// kMaxRelaxSteps steps, or on the stop flag. p.base: the result (tow
/// point back at its start: a flat bottom is the same everywhere).
void relax(SteadyProblem& p, double target, const volatile int* stop_flag) {
  constexpr int kMaxRelaxSteps = 20000;     // accepted steps [-]
  constexpr int kCheckEvery = 20;           // steps between residual checks [-]
  constexpr double kRelaxTolerance = 1e-5;  // local error target of the steps [-]
  constexpr double kSharpSlip = 0.1;        // the relaxation's v_s' / U, at most [-]
  constexpr int kStallChecks = 50;          // checks (1000 steps) without the residual halving: stalled [-]
  Model rm = p.model;
  const double U = p.V.norm();
  // At rest the friction vanishes at the equilibrium; left in, its viscous
  // slope mu N / v_s makes the lying cable only creep: relax without it.
  if (!(U > 0) && rm.seabed) rm.seabed->friction = 0;
  // Moving near the smoothing speed v_s the same slope makes the lying
  // length creep as well: relax with a sharper law, v_s' = U / 10, scaled
  // to the same friction at the steady slip U (so the same equilibrium).
  if (U > 0 && rm.seabed && rm.seabed->slip_speed > kSharpSlip * U) {
    Seabed& sb = *rm.seabed;
    const double sharp = kSharpSlip * U;
    sb.friction *= std::hypot(U, sharp) / std::hypot(U, sb.slip_speed);
    sb.slip_speed = sharp;
  }
  rm.tow.pieces.clear();
  if (U > 0) rm.tow.pieces.emplace_back(Ramp{p.V / U, U, 0.0});
  finalize_tow(rm.tow);
  const std::unique_ptr<System> sys = make_system(rm);
  if (!sys->has_stage_solve()) return;
  double weight = 1.0;  // force scale of the error norm: the chain's apparent weight [N]
  for (const Element& el : rm.cable.elements) weight += std::abs(el.weight);
  // No rotation rates: every point moving at V.
  auto stop_rotations = [](PhysicalState& st) {
    for (auto& w : st.w) w.setZero();
    for (auto& b : st.bodies) b.w.setZero();
  };
  // The iterate handed back: at rest, the tow point at its start.
  auto accept = [&](PhysicalState st) {
    stop_rotations(st);
    st.r0 = rm.tow.start;
    st.v0 = p.V;
    p.accept_state(st);
  };
  PhysicalState s = p.base;
  s.r0 = rm.tow.start;
  s.v0 = p.V;
  stop_rotations(s);
  StateVector y = sys->initial(s, 0.0);
  RosenbrockW ros(*sys, kRelaxTolerance, weight, RosenbrockW::ForceEstimate::Filtered,
                  RosenbrockW::TimeDerivative::None);  // the path does not matter: no f_t evaluations
  double t = 0, h = 1e-3, previous = 0;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p.size());
  double best = std::numeric_limits<double>::infinity(), anchor = best;  // residuals at the checks [rad/s^2]
  PhysicalState best_state = p.base;
  int since = 0;  // checks since the residual last halved
  for (int step = 0; step < kMaxRelaxSteps && !stopped(stop_flag);) {
    if (!ros.try_step(y, t, h)) {
      if (!(h > 1e-12)) break;
      continue;
    }
    ++step;
    s = sys->physical(y);
    double ke = 0;  // rotational kinetic energy about each part's joint [J]
    for (int k = 0; k < p.n; ++k) ke += p.scale[static_cast<std::size_t>(k)] * s.w[k].squaredNorm();
    for (int b = 0; b < p.nb; ++b)
      ke += p.scale[static_cast<std::size_t>(p.n + b)] * s.bodies[static_cast<std::size_t>(b)].w.squaredNorm();
    const bool peak = ke < previous;
    previous = peak ? 0.0 : ke;
    if (peak) {
      stop_rotations(s);
      y = sys->initial(s, t);
      ros.invalidate();
    }
    if (step % kCheckEvery == 0) {
      accept(s);
      const double res = p.max_alpha(p.residual(zero));
      if (res < target) return;
      // At rest, stalled: the residual has not halved in kStallChecks checks
      // (the in-line depressors of test_seabed.cpp stop near 1e-4 rad/s^2):
      // hand the best iterate to the dense solve instead of using up
      // kMaxRelaxSteps. Not when moving: the dragged in-line clump wanders
      // near 0.3 rad/s^2 for 20000 steps, and the dense solve converges
      // from where that leaves it, not from its best iterate after 1000.
      if (res < best) best = res, best_state = p.base;
      if (best < 0.5 * anchor) {
        anchor = best;
        since = 0;
      } else if (!(U > 0) && ++since >= kStallChecks) {
        p.accept_state(best_state);
        return;
      }
    }
  }
  accept(sys->physical(y));
}

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

/// Elastic elements (docs/theory.md §5.4, §7): the equilibrium of a chain of
/// inextensible elements of the current lengths l_k, then each elastic
/// element's tension T_k = e_k . (F_k/2 - f_k) (the axial part of its
/// d-equation at rest) gives l_k = L_k (1 + T_k/EA); repeat until the
/// lengths no longer change. The tensions depend on the lengths only through
/// the geometry (depth in a current profile, the body's place), so this
/// converges in a few passes, each a warm-started Newton solve.
void stretch(const Model& elastic, SteadyProblem& p, const volatile int* stop_flag, StaticsResult& out) {
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
    solve_rigid(p, stop_flag, out);
    if (!out.converged) return;
  }
  out.converged = false;
  out.message = "statics did not converge: the elastic elements' lengths still change after " +
                std::to_string(kMaxPasses) + " passes";
}

}  // namespace

StaticsResult solve_statics(const Model& model, const Vec3& V, const volatile int* stop_flag) {
  // A steady tow holds the winch: the configuration at the current length.
  if (model.winch.active()) {
    Model held = model;
    held.winch = Winch{};
    StaticsResult r = solve_statics(held, V, stop_flag);
    if (elastic_winch(model)) r.state.top_unstretched = model.cable.elements.front().length;  // L_1
    return r;
  }
  SteadyProblem p(model, V);
  const Model elastic = p.model;  // with the steady tow, before its elements are made rigid
  const bool stretches = lengths_in_state(model);
  for (Element& el : p.model.cable.elements) el.axial_stiffness = 0;  // the Newton problem: rigid elements
  sweep_from_bottom(p);
  StaticsResult out;
  // Cable laid along the bottom: relax first (at rest, frictionless there,
  // relaxation is cheap and leaves the dense solve less to do).
  if (!p.sweeps) relax(p, V.norm() > 0 ? 1e-3 : 1e-6, stop_flag);
  solve_rigid(p, stop_flag, out);
  if (!out.converged && !out.interrupted && model.seabed && p.sweeps) {
    // The sweeps and the dense polish failed with cable on the bottom (a
    // moving or a stationary tow with a body or attachments: not laid by
    // lay_along_bottom; the sweeps leave the contact out): relax from the
    // better iterate (at rest to 1e-6, as on a slope), then the dense solve
    // alone.
    const int before = out.iterations;
    p.sweeps = false;
    relax(p, V.norm() > 0 ? 1e-3 : 1e-6, stop_flag);
    out.message.clear();  // the failed attempt's
    solve_rigid(p, stop_flag, out);
    out.iterations += before;
  }
  if (stretches && out.converged) stretch(elastic, p, stop_flag, out);
  // Forces at the equilibrium (the elastic model's own evaluation).
  out.state = p.base;
  out.state.length_rate.assign(out.state.length.size(), 0.0);
  out.tow_velocity = V;
  forward_dynamics(elastic, p.base, 0.0, p.ws);
  out.tow_force = p.ws.acc.tow_force;
  out.link_force = p.ws.acc.link_force;
  out.body_force = p.ws.acc.lower_link_force;
  out.joint_force = p.ws.acc.joint_force;
  out.sample = make_sample(elastic, p.base, p.ws, 0.0);
  if (out.converged) out.equilibria = find_equilibria(elastic, p.base, p.ws, V, out.body_force);
  // Angles balanced but forces overflowed (e.g. mass_per_length 1e200): no equilibrium to report.
  // (components near 1e200 are finite, their norm, the tension, is not).
  bool finite = std::isfinite(out.tow_force.norm());
  for (const std::vector<Vec3>* forces : {&out.link_force, &out.body_force, &out.joint_force})
    for (const Vec3& f : *forces) finite = finite && std::isfinite(f.norm());
  if (out.converged && !finite) {
    out.converged = false;
    out.message =
        "no finite equilibrium: the forces overflow double precision (check the scenario's masses, sizes "
        "and speeds)";
  }
  return out;
}

BodyEquilibrium classify_body_balance(const Model& model, std::size_t body, const Vec3& Q, const Vec3& V,
                                      const Vec3& f2, const Quat& q) {
  Workspace ws(model);
  return classify_balance(model, model.bodies[body], Q, V, f2, q, ws.body[body]);
}

StaticsResult newton_krylov_statics(const Model& model, const Vec3& V, const PhysicalState& start) {
  SteadyProblem p(model, V);
  for (Element& el : p.model.cable.elements) el.axial_stiffness = 0;  // rigid elements, as solve_statics
  PhysicalState s = start;
  s.r0 = p.model.tow.start;
  s.v0 = V;
  p.accept_state(s);
  StaticsResult out;
  const double floor = residual_floor(p.model);
  const bool rejected = newton_krylov(p, floor, nullptr, out.iterations);
  const Eigen::VectorXd r = p.residual(Eigen::VectorXd::Zero(p.size()));  // p.ws at the result
  out.residual = p.max_alpha(r);
  out.converged = !rejected && good_residual(p, floor, r);
  if (rejected) out.message = "compression";
  out.state = p.base;
  out.tow_velocity = V;
  out.tow_force = p.ws.acc.tow_force;
  out.joint_force = p.ws.acc.joint_force;
  return out;
}

StaticsResult steady_state(const Model& model) {
  StaticsResult res = steady_state(model, nullptr);
  if (!res.converged) throw std::runtime_error(res.message);
  return res;
}

StaticsResult steady_state(const Model& model, const volatile int* stop_flag) {
  if (model.tow.mode != Tow::Mode::Motion)
    throw std::runtime_error("initial: steady needs tow.mode: motion (the steady velocity comes from the tow law)");
  const TowKinematics k = tow_kinematics(model.tow, 0.0);
  StaticsResult res = solve_statics(model, tow_law_kinematics(model.tow, 0.0).vel, stop_flag);  // mean tow velocity
  if (!res.converged && !res.interrupted && model.seabed && res.tow_velocity.norm() > 0)
    res.message += " (a tow moving with cable on the seabed is solved by relaxation, then the dense solve up to " +
                   std::to_string(kDenseLimit / 2) +
                   " elements and Newton-Krylov above: fewer elements, or start at rest or from a direction "
                   "above the bottom)";
  res.state.r0 = k.pos;
  res.state.v0 = k.vel;
  return res;
}

}  // namespace towsim
