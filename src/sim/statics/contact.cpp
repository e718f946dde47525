// The seabed contact's geometry in the statics: a body's lowest point, and
// Newton steps that keep the contact points where the linear model put them
// (docs/theory.md §7 "Seabed").
#include <algorithm>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim::statics {

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

}  // namespace towsim::statics
