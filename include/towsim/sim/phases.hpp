// The manoeuvre phases of a run: when the tow law and the winch change what
// they impose, and the steady intervals between (docs/scenario.md "Outputs",
// summary.json `phases`). A pure function of the Model.
#pragma once

#include <string>
#include <vector>

#include "towsim/model/model.hpp"

namespace towsim {

/// One phase: a time interval in which one input changes (an activity), or
/// one in which none does (Steady).
struct Phase {
  enum class Kind {
    Steady,       // no input changes: constant tow velocity (or force), the winch (if any) stopped
    Accelerate,   // a `ramp` piece gathers speed from rest
    SpeedChange,  // a `speed` manoeuvre
    Turn,         // a `turn` manoeuvre
    Heave,        // a `heave` piece oscillates (from its start on)
    Track,        // a `track` piece, between its first and last rows
    ForceChange,  // force mode: the tabulated force changes between two rows
    PayOut,       // an imposed winch schedule pays cable out
    HaulIn,       // ... or hauls it in
  } kind = Kind::Steady;
  int piece = -1;         // the Tow::pieces index it comes from (-1: not a piece)
  bool winch = false;     // it comes from the winch's schedule
  double start = 0;       // [s]
  double end = 0;         // [s], > start; a phase that goes on past the run ends at its duration
  double settle_end = 0;  // the end of the interval its response is judged to settle in (phase_settle_end) [s]
};

/// A phase kind's name as summary.json writes it: steady, accelerate,
/// speed_change, turn, heave, track, force_change, pay_out, haul_in.
const char* phase_kind_name(Phase::Kind kind);

/// The phases of a run of `model` over [0, model.sim.duration], sorted by
/// start (then end): the activities of the tow law (ramps with a ramp time,
/// manoeuvres from their start to their end on the course, heaves from their
/// start, tracks between their first and last rows; in force mode, each span
/// of rows over which the force changes) and of the winch (an imposed
/// schedule: its spans of pay-out and of haul-in, a stop of zero speed
/// separating them; a tension-controlled winch has none: its pay-out follows
/// the dynamics), then the Steady intervals where none runs. Activities may
/// overlap (a pay-out during a turn); steady intervals do not. Phases of
/// zero length, or starting at or after the duration, are left out.
/// settle_end: for each phase, the first time at or after its end where
/// another activity starts or is running (its settling window ends where
/// something else changes the inputs), or the duration.
std::vector<Phase> run_phases(const Model& model);

}  // namespace towsim
