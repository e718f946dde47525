// Manoeuvre `speed`: the course changes speed along its heading.
#pragma once

#include "towsim/tow/course.hpp"

namespace towsim {

/// From start_time the course's speed changes linearly from its value then to
/// `speed` over ramp_time (> 0), along the current heading (which turns keep
/// changing); then it holds `speed`.
struct SpeedChange {
  double speed = 0;       // new speed [m/s], >= 0
  double start_time = 0;  // [s]
  double ramp_time = 1;   // [s], > 0

  bool operator==(const SpeedChange&) const = default;

  /// Start the change: the rate and its end.
  void begin(CourseState& c) const;
};

}  // namespace towsim
