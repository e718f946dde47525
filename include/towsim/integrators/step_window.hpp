// The span of the step being taken, for the time-dependent inputs
// (docs/theory.md §6 "Breakpoints").
#pragma once

#include <algorithm>
#include <cmath>

namespace towsim {

/// The step [t0, t1] a stage belongs to: time-dependent inputs (tow law,
/// deflections, winch schedule) are evaluated strictly inside it, so a step
/// ending on a breakpoint of a law sees the piece before it and a step
/// starting there the piece after it. The default spans all time: inputs
/// at t itself.
struct StepWindow {
  double t0 = -1e300, t1 = 1e300;  // [s]

  /// The right limit at t (an output at a breakpoint: the state is already past it).
  static StepWindow after(double t) { return {t, 1e300}; }

  /// Time at which to evaluate the inputs for a stage at t: t moved inside
  /// the window by a relative 1e-12 [s].
  double law_time(double t) const {
    const double d = 1e-12 * std::max(1.0, std::abs(t));
    if (t1 - t0 <= 2 * d) return t;
    return std::clamp(t, t0 + d, t1 - d);
  }
};

}  // namespace towsim
