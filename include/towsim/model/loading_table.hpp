// A faired cable's loading function: a force coefficient tabulated over the
// angle between the cable and the flow (docs/theory.md §3 "Faired cable").
#pragma once

#include <vector>

#include "towsim/model/types.hpp"

namespace towsim {

/// f(phi) over phi, the acute angle between an element's axis and the flow
/// relative to it, in [0, pi/2]: linear between rows, held at the ends.
/// The loads are f(phi) times R = 1/2 rho Cd D L |u|^2 (Cd the section's
/// normal drag coefficient): the normal force along -u_n, the tangential one
/// along -sgn(u.e) e. An empty table means "the default law" (cross-flow
/// normal drag, Pode or skin friction).
struct LoadingTable {
  std::vector<double> phi;  // strictly increasing, within [0, pi/2] [rad]
  std::vector<double> f;    // loading function at phi, >= 0 [-]

  bool empty() const { return f.empty(); }
  /// f at the flow angle `angle` [rad].
  double at(double angle) const;
  /// Normal load of a table law on an element: -k |u|^2 f(phi) u_n/|u_n|, the
  /// direction smoothed as u_n / sqrt(|u_n|^2 + v_s^2) (continuous at u_n = 0).
  /// k = 1/2 rho Cd D L [kg/m], un, ue: the relative velocity across and along the axis [m/s], v_s [m/s].
  Vec3 normal_force(double k, const Vec3& un, double ue, double v_s) const;
  /// Tangential load of a table law: -k |u|^2 f(phi) sgn_s(u.e) e [N].
  Vec3 tangential_force(double k, const Vec3& un, double ue, const Vec3& e, double v_s) const;
};

}  // namespace towsim
