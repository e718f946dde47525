// Steady-tow statics: the equilibrium of cable and body for a steady tow
// (docs/theory.md §7 "Statics").
#pragma once

#include <string>
#include <vector>

#include "towsim/dynamics/state.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim {

/// Angle beyond which two balances of a body count as distinct [rad]: 0.1 deg
/// (Newton leaves the same balance reached from two starts within ~1e-9 rad).
inline constexpr double kDistinctBalance = 0.1 * 3.14159265358979323846 / 180;

/// The starts of BodyEquilibria's search: the attitude solved and 11 trims.
inline constexpr int kBodyStarts = 12;

/// One balance of a body's moments about its link Q, the flow there and the
/// force of the cable below held as in the equilibrium solved (docs/theory.md
/// §7 "Equilibria of a body").
struct BodyEquilibrium {
  Quat q = Quat::Identity();      // attitude [-, body to R_g]
  Vec3 rpy_deg = Vec3::Zero();    // roll, pitch, yaw as the outputs give them [deg]
  Vec3 stiffness = Vec3::Zero();  // restoring stiffness about the body's x, y, z axes (roll, pitch,
                                  // yaw): -dM/dtheta, the diagonal of K in body axes [N m/rad]
  double min_stiffness = 0;       // smallest eigenvalue of K's symmetric part [N m/rad]
  bool stable = false;            // see BodyEquilibria
};

/// The balances of one body at a converged equilibrium: Newton on its
/// attitude from the attitude solved and from trims pitched -75..75 deg in
/// 15 deg steps (level in the tow's heading); balances farther apart than
/// kDistinctBalance (a rotation about a neutral axis, e.g. a sphere's about
/// its link line, left out) are distinct. Each is classified from its
/// restoring stiffness K = -dM/dtheta (central differences of the moment
/// about Q, 1e-5 rad): stable when K's symmetric part has no eigenvalue below
/// -1e-6 of the body's moment scale per radian (a zero one, a neutral
/// rotation, is not unstable). A body whose lowest point reaches the seabed
/// is not analysed (the contact is not part of its own balance).
struct BodyEquilibria {
  bool analysed = false;
  std::vector<BodyEquilibrium> balances;  // distinct balances, highest pitch first
  int chosen = -1;                        // index of the one in the equilibrium solved
};

/// Result of a statics solve.
struct StaticsResult {
  PhysicalState state;            // configuration; every point moves at tow_velocity
  Vec3 tow_velocity;              // steady velocity of the tow point [m/s, R_g]
  Vec3 tow_force;                 // F_R [N, R_g]
  std::vector<Vec3> link_force;   // F_L on each body at Q [N, R_g]
  std::vector<Vec3> body_force;   // each in-line body's force on the cable below at Q2 [N, R_g]
  std::vector<Vec3> joint_force;  // f_k through joint k, k = 0..n [N, R_g]
  Sample sample;                  // the equilibrium as an output sample (t = 0)
  double residual = 0;            // largest angular acceleration left [rad/s^2]
  int iterations = 0;             // Newton iterations
  bool converged = false;
  bool interrupted = false;                // the stop flag was set: the state is the last iterate
  std::string message;                     // why it did not converge
  std::vector<BodyEquilibria> equilibria;  // per body, when converged
};

/// The tow velocity a steady tow settles to: the sum of the ramps' final
/// velocities and a track's final velocity (heave left out); with turns or
/// speed changes, horizontally the course's final speed along its heading
/// after the last manoeuvre (a turn that never ends: the heading at its start) [m/s].
Vec3 final_tow_velocity(const Tow& tow);

/// Equilibrium of the model's cable and body when the tow point moves at the
/// constant velocity V (in the model's current): zero accelerations in the
/// same equations the dynamics use. A short driver: a model with an active
/// winch is solved without it, the Newton problem's elements are rigid, and
/// the start decides the plan of strategies (docs/theory.md §7 "Strategies
/// and the driver"): the O(n) sweeps from the body up, then Newton on all
/// angles (Levenberg-Marquardt for small problems, Newton-Krylov for large
/// coupled ones); with cable on the seabed dynamic relaxation first (laid
/// along the bottom) or when the sweeps fail; elastic elements stretched
/// on the rigid solution. The tow point sits at tow.start. `stop_flag`, when non-null and set, ends the solve early
/// (result.interrupted, not converged).
StaticsResult solve_statics(const Model& model, const Vec3& V, const volatile int* stop_flag = nullptr);

/// `model` with a deployed length L: the top section's elements (their
/// number kept) stretched or shortened together, per-length properties kept,
/// everything below unchanged. L must exceed the length below the top section.
Model with_deployed_length(const Model& model, double L);

/// Deployed length for a target depth (`towsim statics --target-depth`).
struct TargetDepthResult {
  double length = 0;  // deployed length found [m]
  double depth = 0;   // depth of the end body's origin (or the cable end) there [m]
  bool found = false;
  std::string message;    // why not
  StaticsResult statics;  // the steady configuration at that length
};

/// The deployed length that puts the end body (or the cable end) at `depth`
/// when the tow point moves steadily at V: bracketing then bisection-secant
/// (Illinois) on the steady depth, to 1e-6 m of depth. `stop_flag`, when
/// non-null and set, ends the search (statics.interrupted, not found).
TargetDepthResult length_for_depth(const Model& model, const Vec3& V, double depth,
                                   const volatile int* stop_flag = nullptr);

/// The link point for a body's trim (`towsim statics --trim`).
struct TrimResult {
  double link_x = 0;     // the body's link_point x found [m, body axes]
  double pitch_deg = 0;  // its pitch there [deg]
  bool found = false;
  std::string message;    // why not
  StaticsResult statics;  // the steady configuration with that link point
};

/// Largest |pitch - target| the trim search leaves [deg].
inline constexpr double kTrimTolerance = 1e-4;

/// The x of body `body`'s link_point (y, z kept) that gives it `pitch_deg`
/// of pitch when the tow point moves steadily at V: from the scenario's x,
/// steps of 0.02, 0.04, ... 5.12 m forward and aft, alternately, until the
/// pitch passes the target (a failed solve is skipped), then
/// bisection-secant (Illinois) to kTrimTolerance. `stop_flag`, when
/// non-null and set, ends the search (statics.interrupted, not found).
TrimResult link_point_for_pitch(const Model& model, const Vec3& V, std::size_t body, double pitch_deg,
                                const volatile int* stop_flag = nullptr);

/// Equilibrium at the tow's velocity at t = 0 (what `initial: steady` starts
/// from); throws std::runtime_error with the message when it does not converge.
StaticsResult steady_state(const Model& model);

/// The same without throwing: the result says whether it converged or was interrupted.
StaticsResult steady_state(const Model& model, const volatile int* stop_flag);

}  // namespace towsim
