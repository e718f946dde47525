// The steady problem's round-off floor (docs/theory.md §7 "Check and fallback").
#include <algorithm>
#include <limits>

#include "problem.hpp"

namespace towsim::statics {

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

}  // namespace towsim::statics
