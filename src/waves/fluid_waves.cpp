// The fluid at a point: current plus wave kinematics (MODEL.md 9).
#include "towsim/model/model.hpp"
#include "towsim/waves/waves.hpp"

namespace towsim {

Vec3 Fluid::velocity(const Vec3& x, double t) const {
  return waves ? Vec3(current(x.z()) + waves->velocity(x, t)) : current(x.z());
}

Vec3 Fluid::acceleration(const Vec3& x, double t) const {
  return waves ? waves->acceleration(x, t) : Vec3::Zero();
}

}  // namespace towsim
