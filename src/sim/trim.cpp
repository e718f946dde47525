// The link point for a body's trim (`towsim statics --trim`).
#include <cmath>

#include "towsim/sim/statics.hpp"

namespace towsim {

TrimResult link_point_for_pitch(const Model& model, const Vec3& V, std::size_t body, double pitch_deg,
                                const volatile int* stop_flag) {
  TrimResult out;
  Model m = model;
  const double x0 = model.bodies[body].link_point.x();
  int solves = 0;
  // The pitch less the target with the link at x, or NaN when the solve fails.
  const auto miss = [&](double x) {
    m.bodies[body].link_point.x() = x;
    out.statics = solve_statics(m, V, stop_flag);
    ++solves;
    if (!out.statics.converged) return std::nan("");
    return out.statics.sample.bodies[body].rpy_deg.y() - pitch_deg;
  };
  const auto stopped = [&] { return stop_flag != nullptr && *stop_flag != 0; };
  double a = x0, fa = miss(x0);
  if (stopped()) return out;
  if (std::abs(fa) <= kTrimTolerance) {
    out = TrimResult{x0, fa + pitch_deg, true, "", out.statics};
    return out;
  }
  // Bracket: outward from x0, forward and aft alternately.
  double b = x0, fb = std::nan("");
  double last[2] = {x0, x0}, flast[2] = {fa, fa};
  bool bracketed = false;
  for (int k = 0; k < 9 && !bracketed && !stopped(); ++k)
    for (int side = 0; side < 2 && !bracketed; ++side) {
      const double x = x0 + (side == 0 ? 1 : -1) * 0.02 * std::ldexp(1.0, k);
      const double f = miss(x);
      if (std::isnan(f)) continue;
      if (!std::isnan(flast[side]) && (f > 0) != (flast[side] > 0)) {
        a = last[side], fa = flast[side], b = x, fb = f;
        bracketed = true;
      }
      last[side] = x, flast[side] = f;
    }
  if (stopped()) return out;
  if (!bracketed) {
    out.message = "no link point within 5.12 m of x = " + std::to_string(x0) + " m gives a pitch of " +
                  std::to_string(pitch_deg) + " deg";
    return out;
  }
  // Illinois: the secant on the bracket, the stale end's value halved.
  int stale = 0;
  for (int it = 0; it < 100 && !stopped(); ++it) {
    const double x = (a * fb - b * fa) / (fb - fa);
    const double f = miss(x);
    if (std::isnan(f)) {
      out.message = "the statics failed with the link at x = " + std::to_string(x) + " m: " + out.statics.message;
      return out;
    }
    if (std::abs(f) <= kTrimTolerance) {
      out.link_x = x;
      out.pitch_deg = f + pitch_deg;
      out.found = true;
      return out;
    }
    if ((f > 0) == (fb > 0)) {
      b = x, fb = f;
      fa *= stale == -1 ? 0.5 : 1.0;
      stale = -1;
    } else {
      a = b, fa = fb;
      b = x, fb = f;
      stale = 1;
    }
  }
  if (!stopped()) out.message = "the link point search did not converge after " + std::to_string(solves) + " solves";
  return out;
}

}  // namespace towsim
