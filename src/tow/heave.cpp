// Tow law `heave` (include/towsim/tow/heave.hpp).
#include "towsim/tow/heave.hpp"

#include <cmath>
#include <numbers>

namespace towsim {

TowKinematics Heave::at(double t) const {
  TowKinematics k{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (t <= start_time) return k;
  const double w = 2 * std::numbers::pi / period;  // [rad/s]
  const double ph = w * (t - start_time);          // phase [rad]
  k.pos.z() = amplitude * std::sin(ph);
  k.vel.z() = amplitude * w * std::cos(ph);
  k.acc.z() = -amplitude * w * w * std::sin(ph);
  return k;
}

void Heave::breakpoints(std::vector<double>& out) const { out.push_back(start_time); }

}  // namespace towsim
