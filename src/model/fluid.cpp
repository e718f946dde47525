// The water (include/towsim/model/fluid.hpp): a steady current U(z) given by
// depth, linear between the table's rows.
#include <algorithm>

#include "towsim/model/fluid.hpp"
#include "towsim/model/table.hpp"
#include "towsim/waves/waves.hpp"

namespace towsim {

namespace {
/// Index of the table interval containing x (clamped), for linear interpolation.
std::size_t interval(const std::vector<double>& xs, double x) {
  auto it = std::upper_bound(xs.begin(), xs.end(), x);
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - xs.begin(), 1)) - 1;
  return std::min(i, xs.size() - 2);
}
}  // namespace

Vec3 Fluid::velocity(const Vec3& x, double t) const {
  return waves ? Vec3(current(x.z()) + waves->velocity(x, t)) : current(x.z());
}

Vec3 Fluid::rate_seen(const Vec3& x, const Vec3& v, double t) const {
  // Current: steady and a function of z only: du/dt = 0 and (v . grad) u = U'(z) v_z.
  // Waves: their local du/dt (linear theory; docs/theory.md 8 "Wave loads").
  const Vec3 r = current_gradient(x.z()) * v.z();
  return waves ? Vec3(r + waves->acceleration(x, t)) : r;
}

Vec3 Fluid::acceleration(const Vec3& x, double t) const {
  // Waves: the local du/dt, equal to Du/Dt to first order in the steepness.
  if (waves) return waves->acceleration(x, t) + current_gradient(x.z()) * current(x.z()).z();
  // Du/Dt = du/dt + (u . grad) u = 0 + U'(z) U_z(z). The current is steady
  // and varies only with depth, so a water particle keeps its velocity unless
  // it moves vertically through the shear: for a horizontal current (U_z = 0
  // in every row, the usual case) the material acceleration is exactly zero.
  if (uniform()) return Vec3::Zero();
  return current_gradient(x.z()) * current(x.z()).z();
}

void Fluid::flow(const Vec3& x, const Vec3& v, double t, Vec3& velocity, Vec3& rate_seen, Vec3& acceleration) const {
  // As velocity(), rate_seen() and acceleration() (with waves), one wave sum.
  Vec3 uw = Vec3::Zero(), aw = Vec3::Zero();
  if (waves) waves->kinematics(x, t, &uw, &aw);
  const Vec3 U = current(x.z()), G = current_gradient(x.z());
  velocity = U + uw;
  rate_seen = G * v.z() + aw;
  acceleration = aw + G * U.z();
}

Vec3 Fluid::current(double z) const {
  if (current_velocity.empty()) return Vec3::Zero();
  return interpolate(current_depth, current_velocity, -z);
}

Vec3 Fluid::current_gradient(double z) const {
  if (current_velocity.size() < 2) return Vec3::Zero();
  const double d = -z;
  if (d <= current_depth.front() || d >= current_depth.back()) return Vec3::Zero();
  const std::size_t i = interval(current_depth, d);
  // dU/dz = -dU/d(depth)
  return -(current_velocity[i + 1] - current_velocity[i]) / (current_depth[i + 1] - current_depth[i]);
}

}  // namespace towsim
