// The depth-keeping controller's law (docs/theory.md §4 "Depth control").
#include "towsim/model/depth_control.hpp"

#include <algorithm>

namespace towsim {

ControlRates depth_control_rates(const DepthControl& c, const ControlState& s, double depth, double depth_rate) {
  ControlRates r;
  r.error = depth - c.target_depth;
  // PID on the error (its rate is the depth's: the target is constant), then the deflection limits.
  const double u = c.kp * r.error + c.ki * s.integral + c.kd * depth_rate;
  r.command = std::clamp(u, -c.max_deflection, c.max_deflection);
  // Back-calculation: while the command saturates, the integral is pulled
  // back towards the value that would just reach the limit.
  r.dintegral = c.ki != 0 ? r.error + (r.command - u) / (c.ki * c.tracking_time) : r.error;
  // First-order servo, rate-limited.
  r.ddeflection = std::clamp((r.command - s.deflection) / c.servo_time_constant, -c.max_rate, c.max_rate);
  return r;
}

double applied_deflection(const DepthControl& c, const ControlState& s) {
  return std::clamp(s.deflection, -c.max_deflection, c.max_deflection);
}

}  // namespace towsim
