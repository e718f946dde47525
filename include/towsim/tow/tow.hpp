// The tow point O_r: imposed motion (tow force is an output) or imposed force
// (docs/scenario.md "tow", docs/theory.md 6.1-6.2).
//
// A motion is a list of pieces, each a small law type in its own file. Two
// kinds compose:
// - offset laws (Ramp, Heave, Track) give a displacement from the tow start;
//   the displacements add up;
// - manoeuvres (Turn, SpeedChange), listed in time order, steer a vessel
//   course: from the first manoeuvre on, the horizontal motion is the course
//   (speed U(t) along heading psi(t), started from the offsets' horizontal
//   position and velocity then), and the offsets give only the vertical.
// Adding a law: its own header and source, one entry in TowLaw, its parser.
#pragma once

#include <memory>
#include <variant>
#include <vector>

#include "towsim/tow/course.hpp"
#include "towsim/tow/heave.hpp"
#include "towsim/tow/ramp.hpp"
#include "towsim/tow/speed.hpp"
#include "towsim/tow/track.hpp"
#include "towsim/tow/turn.hpp"

namespace towsim {

class Vessel;  // towsim/waves/vessel.hpp

/// One piece of an imposed tow-point motion.
using TowLaw = std::variant<Ramp, Heave, Track, Turn, SpeedChange>;

/// True for a manoeuvre (a piece that steers the course).
bool is_manoeuvre(const TowLaw& law);
/// A manoeuvre's start time [s] (0 for an offset law).
double start_time(const TowLaw& law);

/// The tow point O_r: imposed motion (tow force is an output) or imposed force.
struct Tow {
  enum class Mode { Motion, Force } mode = Tow::Mode::Motion;
  Vec3 start = Vec3::Zero();   // O_r at t = 0 [m, R_g]
  std::vector<TowLaw> pieces;  // Motion: offsets add; manoeuvres (in time order) steer the course
  // Force: F_R(t) tabulated (one row = constant), linear interpolation [s], [N, R_g]
  std::vector<double> force_time;
  std::vector<Vec3> force_value;
  /// Motion mode: a vessel whose wave motion carries the tow point on top of
  /// the pieces (which then move its RAO origin), or none (src/waves/vessel.cpp).
  std::shared_ptr<const Vessel> vessel;
  /// The course worked out from start and pieces by finalize_tow(tow), shared
  /// by copies; none: the course is walked at each call (same numbers).
  std::shared_ptr<const CoursePlan> plan;
  /// The pieces the plan was built from: a cursor checks them against
  /// `pieces` once (a Workspace: once per run); a plan that no longer matches
  /// (the pieces edited after finalize_tow) is not used.
  std::shared_ptr<const std::vector<TowLaw>> plan_pieces;
};

/// Build tow.plan from its start and pieces. Call it again after changing
/// them (compile does; a plan built for other pieces or another start is
/// found out once per cursor and not used: the course is then walked).
void finalize_tow(Tow& tow);

/// Imposed tow-point kinematics at time t (Motion mode): the pieces, then
/// the vessel's wave motion when there is one (src/waves/vessel.cpp).
TowKinematics tow_kinematics(const Tow& tow, double t);
/// The pieces alone (the vessel's RAO origin when there is a vessel).
TowKinematics tow_law_kinematics(const Tow& tow, double t);
/// tow_kinematics and tow_law_kinematics through the tow's course plan and a
/// cursor (same numbers as without).
TowKinematics tow_kinematics(const Tow& tow, double t, CourseCursor& cursor);
TowKinematics tow_law_kinematics(const Tow& tow, double t, CourseCursor& cursor);

/// Imposed tow force at time t (Force mode) [N, R_g].
Vec3 tow_force(const Tow& tow, double t);

/// Times > 0 where the tow law is not smooth (end of a ramp, start of a heave,
/// ends of a track, start and end of each manoeuvre, rows of a force table),
/// sorted. Integrators land on them so that no step straddles a jump in
/// acceleration or velocity.
std::vector<double> tow_breakpoints(const Tow& tow);

/// Where a manoeuvre runs on the course, for checks and reports.
struct ManoeuvreSpan {
  std::size_t piece = 0;  // index in Tow::pieces [-]
  double start = 0;       // [s]
  double end = 0;         // [s], as if no later turn cut it short; CourseState::kNever: never ends
  double speed = 0;       // course speed at its start [m/s]
};
/// The manoeuvres' spans, in list order. Empty when the course cannot start
/// (no horizontal speed at the first manoeuvre: no heading).
std::vector<ManoeuvreSpan> manoeuvre_spans(const Tow& tow);

/// The course after its last event (speed and heading no longer change, unless
/// a turn never ends), or nothing without manoeuvres.
bool final_course(const Tow& tow, CourseState& out);

}  // namespace towsim
