// The winch at the tow point: pay-out and haul-in during a run
// (docs/theory.md "Winch", docs/scenario.md "winch").
//
// The top element's length l is a prismatic coordinate at the sheave: its
// material is fixed to its bottom joint P_1 = P_0 + l e_1 and leaves the
// sheave at v_0 + l' e_1. Length control imposes the deployed length L(t)
// (a piecewise quadratic schedule: a rate table integrated exactly, or a
// length table); tension control makes l a force-driven coordinate with the
// drum's inertia. The top element splits when it grows past `split_at`
// nominal lengths and is removed when it shrinks below `remove_at`.
#pragma once

#include <limits>
#include <vector>

namespace towsim {

/// One piece of an imposed deployed-length schedule, valid from t0 to the
/// next piece's t0: L(t) = L0 + rate (t - t0) + acc (t - t0)^2 / 2.
struct WinchPiece {
  double t0 = 0;    // start [s]
  double L0 = 0;    // deployed length at t0 [m]
  double rate = 0;  // pay-out speed at t0 [m/s] (< 0 hauls in)
  double acc = 0;   // constant pay-out acceleration on the piece [m/s^2]
};

/// Deployed length, pay-out speed and acceleration at one time.
struct WinchKinematics {
  double length = 0;  // deployed length L [m]
  double rate = 0;    // L' [m/s]
  double acc = 0;     // L'' [m/s^2]
};

/// The winch (immutable, part of the Model).
struct Winch {
  enum class Mode {
    None,     // no winch: fixed deployed length
    Imposed,  // length control: L(t) from `schedule` (rate or length table)
    Tension,  // constant-tension control: M_d l'' = T_top - T_set - c l'
  } mode = Mode::None;
  std::vector<WinchPiece> schedule;  // Imposed: sorted by t0, the first at t0 = 0; the last runs forever
  double tension = 0;                // Tension: set tension T_set [N]
  double drum_inertia = 0;           // Tension: drum inertia as a mass at the rim M_d [kg]
  double damping = 0;                // Tension: c, drum damping [N s/m]
  double max_speed = std::numeric_limits<double>::infinity();         // |L'| limit [m/s]
  double max_acceleration = std::numeric_limits<double>::infinity();  // |L''| limit (tension mode) [m/s^2]
  double min_length = 0;  // the winch stops hauling in at this deployed length [m]
  double max_length = std::numeric_limits<double>::infinity();  // drum capacity: stops paying out [m]
  double rating = 0;          // winch rating (line pull) for the tow tension ratio [N]; 0 = not given
  double nominal_length = 0;  // L_e, the top section's element length [m]
  double split_at = 1.5;      // the top element splits above split_at * L_e [-]
  double remove_at = 0.1;     // and is removed below remove_at * L_e [-]
  double length_offset = 0;   // cable drawn in by removals (straightened kinks) [m]

  bool active() const { return mode != Mode::None; }
};

/// Imposed deployed length, speed and acceleration at t (Mode::Imposed).
/// At a breakpoint, the piece starting there.
WinchKinematics winch_kinematics(const Winch& w, double t);

/// The same as the limit from the left at t: the piece before a breakpoint
/// (at t = 0, the first piece). Steps ending on a breakpoint end on it.
WinchKinematics winch_kinematics_before(const Winch& w, double t);

/// Times > 0 where the schedule's speed or acceleration jumps (piece starts), sorted.
std::vector<double> winch_breakpoints(const Winch& w);

/// Schedule from a pay-out speed table {t, rate} (linear between rows, held
/// beyond them; one row = constant) starting at length L0 at t = 0, stopped
/// (speed set to 0) while it would take L out of [min_length, max_length].
std::vector<WinchPiece> schedule_from_rate(const std::vector<double>& t, const std::vector<double>& rate, double L0,
                                           double min_length, double max_length);

/// Schedule from a length table {t, L} (linear between rows, held beyond
/// them); the speed jumps at each row.
std::vector<WinchPiece> schedule_from_length(const std::vector<double>& t, const std::vector<double>& L);

}  // namespace towsim
