// Manoeuvre `turn` (include/towsim/tow/turn.hpp).
#include "towsim/tow/turn.hpp"

namespace towsim {

void Turn::begin(CourseState& c) const {
  c.R = radius;
  // Towards the centre: the heading's left normal to port, right to starboard (z up).
  c.n = port ? Vec3(-c.h.y(), c.h.x(), 0) : Vec3(c.h.y(), -c.h.x(), 0);
  c.turn_left = angle;
}

}  // namespace towsim
