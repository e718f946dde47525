// The vessel's course once manoeuvres steer it: speed U(t) along a heading
// psi(t) in the horizontal plane (docs/theory.md 6.2).
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "towsim/tow/kinematics.hpp"

namespace towsim {

/// The course at a time t0 where a segment starts. Within a segment the speed
/// changes at a constant rate `a` and the path has constant curvature (a
/// straight line, R = 0, or an arc of radius R), so position, velocity and
/// acceleration are closed forms of the distance run s(t) = U tau + a tau^2 / 2
/// (tau = t - t0): exact to round-off.
struct CourseState {
  static constexpr double kNever = std::numeric_limits<double>::infinity();
  double t0 = 0;              // start of the segment [s]
  Vec3 p = Vec3::Zero();      // horizontal position at t0 [m, R_g] (z = 0)
  Vec3 h = Vec3::UnitX();     // unit heading at t0 [-, R_g] (horizontal)
  double U = 0;               // speed along the heading at t0 [m/s]
  double a = 0;               // dU/dt while a speed change runs [m/s^2]
  double a_end = kNever;      // time the speed change ends [s]
  double U_end = 0;           // speed then [m/s]
  double R = 0;               // turn radius [m]; 0 = straight
  Vec3 n = Vec3::Zero();      // unit normal towards the turn's centre [-, R_g]
  double turn_left = kNever;  // heading change left before the turn ends [rad]
};

/// The course's segments worked out once from a tow's start and pieces
/// (finalize_tow, towsim/tow/tow.hpp): tow_law_kinematics through it gives the same numbers (the same
/// segment states) without walking the events from the first manoeuvre at
/// every call. Immutable once built.
struct CoursePlan {
  struct Segment {
    double end = 0;     // the segment lasts up to this time [s] (kNever: for ever)
    CourseState state;  // the course at its start
  };
  bool course = false;                   // a course runs after t_first
  double t_first = CourseState::kNever;  // the first manoeuvre's start [s]
  std::vector<Segment> segments;         // in time order
  std::size_t pieces = 0;                // the tow's piece count it was built for [-]
  Vec3 start = Vec3::Zero();             // the tow's start it was built for [m, R_g]
};

/// Per-evaluation state of the tow law (in the Workspace): the last result,
/// for the plan it came from.
struct CourseCursor {
  const CoursePlan* checked = nullptr;     // the plan last checked against the tow's pieces and start
  bool usable = false;                     // ... and it matched them
  std::shared_ptr<const CoursePlan> plan;  // the plan `last` was computed with (none: no last result)
  double last_t = 0;                       // [s]
  TowKinematics last{};                    // tow_law_kinematics at last_t
  // The vessel's last tow point (an evaluation asks for it more than once):
  // for this vessel (held, so that its address is not reused), time and law.
  std::shared_ptr<const void> vessel;
  double vessel_t = 0;           // [s]
  TowKinematics vessel_law{};    // the tow law's kinematics it was computed for
  TowKinematics vessel_point{};  // the tow point then
};

/// Horizontal position, velocity and acceleration at t >= c.t0 in c's segment.
TowKinematics course_at(const CourseState& c, double t);
/// The time the running turn ends if the segment lasts (kNever if it does not end).
double turn_end_time(const CourseState& c);
/// Start a new segment at te >= c.t0. `turn_ends`: te is the running turn's
/// end, where the heading has turned by exactly turn_left; the path is
/// straight after it.
void advance(CourseState& c, double te, bool turn_ends);

}  // namespace towsim
