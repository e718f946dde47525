// Tow-law pieces for the benchmarks, by named fields (the others keep their
// defaults), so that a new TowPiece field needs no change here.
#pragma once

#include "towsim/model/model.hpp"

namespace towsim::bench {

/// Ramp to `speed` [m/s] along `direction` [-, R_g] in `ramp_time` [s].
inline TowPiece ramp(const Vec3& direction, double speed, double ramp_time) {
  TowPiece p{};
  p.type = TowPiece::Type::Ramp;
  p.direction = direction;
  p.speed = speed;
  p.ramp_time = ramp_time;
  return p;
}

/// Vertical sine of `amplitude` [m] and `period` [s] from `start_time` [s].
inline TowPiece heave(double amplitude, double period, double start_time) {
  TowPiece p{};
  p.type = TowPiece::Type::Heave;
  p.amplitude = amplitude;
  p.period = period;
  p.start_time = start_time;
  return p;
}

/// An empty track (rows to be appended to track_time, track_pos).
inline TowPiece track() {
  TowPiece p{};
  p.type = TowPiece::Type::Track;
  return p;
}

}  // namespace towsim::bench
