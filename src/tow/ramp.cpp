// Tow law `ramp` (include/towsim/tow/ramp.hpp).
#include "towsim/tow/ramp.hpp"

namespace towsim {

TowKinematics Ramp::at(double t) const {
  const Vec3 d = direction.normalized();
  const double T = ramp_time;
  TowKinematics k{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (t < 0) return k;
  if (T <= 0) {  // no ramp: at speed from the start
    k.vel = speed * d;
    k.pos = speed * t * d;
    return k;
  }
  if (t < T) {  // constant acceleration
    k.acc = speed / T * d;
    k.vel = speed * t / T * d;
    k.pos = speed * t * t / (2 * T) * d;
  } else {  // at speed, having lost T/2 of distance to the ramp
    k.vel = speed * d;
    k.pos = speed * (t - T / 2) * d;
  }
  return k;
}

void Ramp::breakpoints(std::vector<double>& out) const {
  if (ramp_time > 0) out.push_back(ramp_time);
}

}  // namespace towsim
