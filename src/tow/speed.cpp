// Manoeuvre `speed` (include/towsim/tow/speed.hpp).
#include "towsim/tow/speed.hpp"

namespace towsim {

void SpeedChange::begin(CourseState& c) const {
  c.a = (speed - c.U) / ramp_time;  // constant rate [m/s^2]
  c.a_end = c.t0 + ramp_time;
  c.U_end = speed;
}

}  // namespace towsim
