// The vessel course between events (include/towsim/tow/course.hpp,
// docs/theory.md 6.2): closed forms in the distance run s(t).
#include "towsim/tow/course.hpp"

#include <cmath>

namespace towsim {

namespace {
/// Distance run tau after the segment's start [m].
double distance(const CourseState& c, double tau) { return c.a == 0 ? c.U * tau : c.U * tau + 0.5 * c.a * tau * tau; }
}  // namespace

TowKinematics course_at(const CourseState& c, double t) {
  const double tau = t - c.t0;
  const double s = distance(c, tau);
  const double U = c.a == 0 ? c.U : c.U + c.a * tau;  // speed at t [m/s]
  TowKinematics k;
  if (c.R == 0) {  // straight line
    k.pos = c.p + s * c.h;
    k.vel = U * c.h;
    k.acc = c.a * c.h;
    return k;
  }
  // Arc of radius R: heading turned by phi = s / R towards n.
  const double R = c.R;
  const double phi = s / R;
  k.pos = c.p + R * (1 - std::cos(phi)) * c.n + R * std::sin(phi) * c.h;
  k.vel = U * (std::cos(phi) * c.h + std::sin(phi) * c.n);
  k.acc = U * U / R * (std::cos(phi) * c.n - std::sin(phi) * c.h);           // centripetal
  if (c.a != 0) k.acc += c.a * (std::cos(phi) * c.h + std::sin(phi) * c.n);  // tangential
  return k;
}

double turn_end_time(const CourseState& c) {
  if (c.R == 0 || !std::isfinite(c.turn_left)) return CourseState::kNever;
  const double s = c.R * c.turn_left;  // arc left [m]
  if (c.a == 0) return c.U > 0 ? c.t0 + s / c.U : CourseState::kNever;
  // U tau + a tau^2 / 2 = s, the root without cancellation.
  const double disc = c.U * c.U + 2 * c.a * s;
  if (disc < 0) return CourseState::kNever;  // the speed falls to zero first
  const double den = c.U + std::sqrt(disc);
  return den > 0 ? c.t0 + 2 * s / den : CourseState::kNever;
}

void advance(CourseState& c, double te, bool turn_ends) {
  const double tau = te - c.t0;
  const double s = distance(c, tau);
  if (c.R == 0) {
    c.p += s * c.h;
  } else {
    // The end of the arc run so far; at a turn's end exactly its angle.
    const double phi = turn_ends ? c.turn_left : s / c.R;
    const double cs = std::cos(phi), sn = std::sin(phi);
    c.p += c.R * (1 - cs) * c.n + c.R * sn * c.h;
    const Vec3 h = cs * c.h + sn * c.n;
    c.n = cs * c.n - sn * c.h;
    c.h = h.normalized();
    c.turn_left -= phi;
    if (turn_ends) {
      c.R = 0;
      c.n.setZero();
      c.turn_left = CourseState::kNever;
    }
  }
  if (c.a != 0) c.U += c.a * tau;
  c.t0 = te;
}

}  // namespace towsim
