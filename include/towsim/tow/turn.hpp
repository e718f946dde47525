// Manoeuvre `turn`: the course leaves its line on a circle.
#pragma once

#include "towsim/tow/course.hpp"

namespace towsim {

/// From start_time the horizontal path turns on a circle of `radius`, tangent
/// to the course, at the course's speed; after a change of heading `angle` it
/// goes straight on at the new heading (angle = kNever: it turns for ever).
/// `port` turns left (towards +y when heading +x, z up), else starboard.
struct Turn {
  double radius = 1;                   // [m]
  double start_time = 0;               // [s]
  bool port = true;                    // true = to port (left), false = starboard
  double angle = CourseState::kNever;  // change of heading at which it ends [rad]

  bool operator==(const Turn&) const = default;

  /// Start turning: set the curvature and the heading change left.
  void begin(CourseState& c) const;
};

}  // namespace towsim
