// The cable's and the attachments' drag laws (docs/theory.md §3), each
// written once with its slope: element_loads and attachment_loads take the
// forces, the stage solve's local Jacobian (src/dynamics/implicit.cpp) the
// damping -dF/du next to them, so a law and its derivative cannot drift apart.
// u: the velocity relative to the water [m/s, R_g]; e: the element's axis.
#pragma once

#include <cmath>

#include "towsim/hydro/loads.hpp"
#include "towsim/model/model.hpp"

namespace towsim::drag_laws {

/// Normal pressure drag (paper 2.41), F = -k |u_n| u_n on u_n = u - (u.e) e,
/// k = drag_factor [kg/m]: returns k |u_n| u_n [N].
inline Vec3 normal_drag(double k, const Vec3& un) { return k * un.norm() * un; }

/// Its damping -dF/du = k (|u_n| (I - e e^T) + u_n u_n^T / |u_n|) [N s/m].
inline Mat3 normal_drag_damping(double k, const Vec3& e, const Vec3& un) {
  const double unn = un.norm();
  if (unn == 0) return Mat3::Zero();
  return k * (unn * (Mat3::Identity() - e * e.transpose()) + un * un.transpose() / unn);
}

/// Tangential friction along e (paper 2.43), F = -f e with k = friction_factor
/// [kg/m], u_e = u.e and v_s the sign's smoothing speed [m/s]:
/// Pode/Landweber f = k |u|^2 u_e / sqrt(u_e^2 + v_s^2); skin friction f = k |u_e| u_e.
/// Returns f e [N].
inline Vec3 tangential_friction(TangentialLaw law, double k, const Vec3& u, double ue, const Vec3& e, double vs) {
  if (law == TangentialLaw::Pode) return k * u.squaredNorm() * smooth_sign(ue, vs) * e;
  return k * std::abs(ue) * ue * e;
}

/// Its damping along e, df/du_e [N s/m] (the e e^T part of -dF/du; Pode's
/// |u|^2 taken at fixed u_n): Pode k (2 u_e^2 / q + |u|^2 v_s^2 / q^3),
/// q = sqrt(u_e^2 + v_s^2); skin friction 2 k |u_e|.
inline double tangential_friction_damping(TangentialLaw law, double k, const Vec3& u, double ue, double vs) {
  if (law == TangentialLaw::Pode) {
    const double q = std::sqrt(ue * ue + vs * vs);
    return k * (2 * ue * ue / q + u.squaredNorm() * vs * vs / (q * q * q));
  }
  return 2 * k * std::abs(ue);
}

/// Quadratic drag of a point (attachments), F = -k |u| u, k = rho CdA / 2
/// [kg/m]: returns k |u| u [N].
inline Vec3 point_drag(double k, const Vec3& u) { return k * u.norm() * u; }

/// Its damping -dF/du = k (|u| I + u u^T / |u|) [N s/m].
inline Mat3 point_drag_damping(double k, const Vec3& u) {
  const double un = u.norm();
  if (un == 0) return Mat3::Zero();
  return k * (un * Mat3::Identity() + u * u.transpose() / un);
}

}  // namespace towsim::drag_laws
