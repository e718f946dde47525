// Faired cable loading functions (docs/theory.md §3 "Faired cable").
#include "towsim/model/loading_table.hpp"

#include <cmath>

#include "towsim/hydro/loads.hpp"
#include "towsim/model/table.hpp"

namespace towsim {

namespace {
/// Angle between the axis and the relative flow, folded into [0, pi/2] [rad].
double flow_angle(const Vec3& un, double ue) { return std::atan2(un.norm(), std::abs(ue)); }
}  // namespace

double LoadingTable::at(double angle) const { return interpolate(phi, f, angle); }

Vec3 LoadingTable::normal_force(double k, const Vec3& un, double ue, double v_s) const {
  const double un2 = un.squaredNorm();
  return -k * (un2 + ue * ue) * at(flow_angle(un, ue)) / std::sqrt(un2 + v_s * v_s) * un;
}

Vec3 LoadingTable::tangential_force(double k, const Vec3& un, double ue, const Vec3& e, double v_s) const {
  return -k * (un.squaredNorm() + ue * ue) * at(flow_angle(un, ue)) * smooth_sign(ue, v_s) * e;
}

}  // namespace towsim
