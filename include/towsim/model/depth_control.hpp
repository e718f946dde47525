// A depth-keeping controller on a lifting surface (docs/theory.md §4 "Depth
// control"): PID on the body's depth error, its output the surface's
// deflection through a rate-limited servo, with back-calculation anti-windup.
// Its state (ControlState) is part of the physical state and integrated with
// the rest; these functions hold none.
#pragma once

namespace towsim {

/// The controller's settings (the model: immutable during a run).
struct DepthControl {
  double target_depth = 0;           // depth to hold, of the body origin O_t, positive down [m]
  double kp = 0;                     // proportional gain [rad/m]
  double ki = 0;                     // integral gain [rad/(m s)]
  double kd = 0;                     // derivative gain [rad s/m]
  double max_deflection = 0;         // |delta| and |command| limit [rad]
  double max_rate = 0;               // |d delta/dt| limit [rad/s]
  double servo_time_constant = 0.1;  // tau: d delta/dt = (u_s - delta) / tau within the rate limit [s]
  double tracking_time = 1;          // T_t of the back-calculation anti-windup [s]
  double initial_deflection = 0;     // delta at t = 0 [rad]
  double settling_band = 0;          // |e| band of the settling time in summary.json [m]; 0 = 1 % of the first |e|
};

/// The controller's state (one per controlled surface).
struct ControlState {
  double integral = 0;    // I = integral of the depth error over time [m s]
  double deflection = 0;  // delta, the servo's position [rad]
};

/// What the controller computes at one instant.
struct ControlRates {
  double error = 0;        // e = depth - target_depth [m] (> 0: too deep)
  double command = 0;      // u_s = clamp(kp e + ki I + kd de/dt, +-max_deflection) [rad]
  double dintegral = 0;    // dI/dt = e + (u_s - u) / (ki T_t) [m]
  double ddeflection = 0;  // d delta/dt = clamp((u_s - delta) / tau, +-max_rate) [rad/s]
};

/// The PID law with its limits at depth [m] (-z of O_t) changing at depth_rate [m/s].
ControlRates depth_control_rates(const DepthControl& c, const ControlState& s, double depth, double depth_rate);

/// The deflection the surface takes: the servo's, within +-max_deflection [rad].
double applied_deflection(const DepthControl& c, const ControlState& s);

}  // namespace towsim
