// Starts on the seabed (docs/theory.md §7 "Seabed"): the chain laid down
// where it would cross the bottom, and the dragged-cable start.
#include <algorithm>
#include <cmath>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim::statics {

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
/// the pull. True when it turned such a body (the sweeps, contact left out,
/// would lift it off: relax first).
bool lay_on_seabed(SteadyProblem& p) {
  const Model& m = p.model;
  if (!m.seabed) return false;
  bool turned = false;
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
        turned = true;
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
  return turned;
}

/// With a seabed and a moving tow (no body, no attachment), the start of a
/// cable dragged along the bottom: its last m elements lie along the bottom
/// behind the tow (against V), each carried by the bottom's normal force,
/// with the friction mu s N against V (s = U / sqrt(U^2 + v_s^2), the law's
/// smoothing); the suspended part hangs above as the start's fixed-point
/// sweep aligns it (start.cpp). m is the fewest lying elements whose
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

}  // namespace towsim::statics
