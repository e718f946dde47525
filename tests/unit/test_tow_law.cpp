// Tow laws (tow_kinematics, tow_force, tow_breakpoints) against closed forms,
// hand calculations and central finite differences (docs/scenario.md "tow", docs/theory.md §6.1).
//
// Finite-difference tolerances. For a smooth f, the central difference
//   D_h f(t) = [f(t+h) - f(t-h)] / (2h) = f'(t) + h^2/6 f'''(xi),
// so |D_h f - f'| <= h^2/6 * max|f'''| (truncation) + ~eps |f| / h (round-off
// of the two values of size |f|). Each check below computes that bound from
// the law's own analytic third derivative (jerk for positions, its derivative
// for velocities) and asserts the error is below it, with a factor 2 margin and
// a round-off term 8 eps |f| / h. Step h = 1e-4 s: truncation ~1e-9 x jerk,
// round-off ~1e-11 x |f| for the magnitudes used here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "towsim/model/model.hpp"

namespace {

using towsim::Tow;
using towsim::TowKinematics;
using TowPiece = towsim::TowLaw;
using towsim::Vec3;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kH = 1e-4;  // FD step [s]

void report(const char* what, double err, double tol) {
  std::printf("[measured] %-58s max err %.3e  (tol %.3e)\n", what, err, tol);
}

TowPiece ramp(Vec3 dir, double speed, double ramp_time) { return towsim::Ramp{dir, speed, ramp_time}; }
TowPiece heave(double amplitude, double period, double start) { return towsim::Heave{amplitude, period, start}; }
TowPiece turn(double radius, double start, bool port) { return towsim::Turn{radius, start, port}; }
TowPiece track(std::vector<double> t, std::vector<Vec3> x) {
  towsim::Track p;  // spline not prepared: evaluated from the rows
  p.time = std::move(t);
  p.pos = std::move(x);
  return p;
}
Tow motion(std::vector<TowPiece> pieces, Vec3 start = Vec3::Zero()) {
  Tow tow;
  tow.mode = Tow::Mode::Motion;
  tow.start = start;
  tow.pieces = std::move(pieces);
  return tow;
}

/// Max FD errors of a law over sample times (away from `avoid` by > 2h).
struct FdErrors {
  double vel = 0, acc = 0;          // measured |D_h x - v|, |D_h v - a|
  double vel_tol = 0, acc_tol = 0;  // largest bound used
  int checked = 0;
};

/// Check v = dx/dt and a = dv/dt by central differences at times ts.
/// jerk: bound on |x'''|; snap: bound on |x''''| = |v'''| near the samples.
FdErrors check_fd(const Tow& tow, const std::vector<double>& ts, const std::vector<double>& avoid, double jerk,
                  double snap) {
  FdErrors r;
  for (double t : ts) {
    if (std::any_of(avoid.begin(), avoid.end(), [&](double b) { return std::abs(t - b) < 2 * kH; })) continue;
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    const TowKinematics kp = towsim::tow_kinematics(tow, t + kH);
    const TowKinematics km = towsim::tow_kinematics(tow, t - kH);
    const Vec3 dx = (kp.pos - km.pos) / (2 * kH);
    const Vec3 dv = (kp.vel - km.vel) / (2 * kH);
    const double tol_v = 2 * (kH * kH / 6 * jerk) + 8 * kEps * (kp.pos.norm() + km.pos.norm()) / kH;
    const double tol_a = 2 * (kH * kH / 6 * snap) + 8 * kEps * (kp.vel.norm() + km.vel.norm()) / kH;
    const double ev = (dx - k.vel).norm(), ea = (dv - k.acc).norm();
    EXPECT_LE(ev, tol_v) << "velocity vs FD of position at t = " << t;
    EXPECT_LE(ea, tol_a) << "acceleration vs FD of velocity at t = " << t;
    r.vel = std::max(r.vel, ev);
    r.acc = std::max(r.acc, ea);
    r.vel_tol = std::max(r.vel_tol, tol_v);
    r.acc_tol = std::max(r.acc_tol, tol_a);
    ++r.checked;
  }
  return r;
}

std::vector<double> grid(double a, double b, int n) {
  std::vector<double> ts;
  for (int i = 0; i <= n; ++i) ts.push_back(a + (b - a) * i / n);
  return ts;
}

/// One-sided limits at t: |f(t + d) - f(t - d)| for position, velocity.
struct Jumps {
  Vec3 dpos, dvel, dacc;
};
Jumps jumps(const Tow& tow, double t, double d = 1e-9) {
  const TowKinematics a = towsim::tow_kinematics(tow, t - d), b = towsim::tow_kinematics(tow, t + d);
  return {b.pos - a.pos, b.vel - a.vel, b.acc - a.acc};
}

}  // namespace

// ---------------------------------------------------------------- ramp

// x = V t^2/(2T) d for 0 <= t < T, V (t - T/2) d after; zero before t = 0.
TEST(TowLaw, RampClosedForm) {
  const Vec3 dir(3, 4, 0);  // not unit: the law normalises it
  const Vec3 d(0.6, 0.8, 0);
  const double V = 2.0, T = 10.0;
  const Vec3 x0(1, -2, -3);
  const Tow tow = motion({ramp(dir, V, T)}, x0);
  double err = 0;
  for (double t : {-1.0, 0.0, 0.3, 2.5, 7.0, 9.999, 10.0, 10.001, 12.5, 40.0}) {
    Vec3 x = x0, v = Vec3::Zero(), a = Vec3::Zero();
    if (t >= 0 && t < T) {
      x += V * t * t / (2 * T) * d;
      v = V * t / T * d;
      a = V / T * d;
    } else if (t >= T) {
      x += V * (t - T / 2) * d;
      v = V * d;
    }
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    err = std::max({err, (k.pos - x).norm(), (k.vel - v).norm(), (k.acc - a).norm()});
  }
  // Closed form evaluated the same way: round-off on |x| <= 80 m.
  const double tol = 1e-13;
  report("RampClosedForm |law - closed form|", err, tol);
  EXPECT_LE(err, tol);

  // ramp_time = 0: at full speed from t = 0, x = V t d.
  const Tow at_once = motion({ramp(dir, V, 0.0)});
  const TowKinematics k = towsim::tow_kinematics(at_once, 5.0);
  EXPECT_LE((k.pos - 5 * V * d).norm(), 1e-14);
  EXPECT_LE((k.vel - V * d).norm(), 1e-15);
  EXPECT_EQ(k.acc, Vec3::Zero());
}

// Position quadratic then linear: x''' = 0 inside each piece, the FD error is
// pure round-off (bound 8 eps |x| / h).
TEST(TowLaw, RampDerivativesMatchFiniteDifferences) {
  const Tow tow = motion({ramp(Vec3(1, 0, -0.2), 2.0, 10.0)});
  const FdErrors r = check_fd(tow, grid(-3, 40, 173), {0.0, 10.0}, 0.0, 0.0);
  report("RampFD velocity", r.vel, r.vel_tol);
  report("RampFD acceleration", r.acc, r.acc_tol);
  EXPECT_GT(r.checked, 150);
}

// C0 in position at t = 0 and at T; C0 in velocity at T (acceleration jumps by -V/T).
TEST(TowLaw, RampContinuity) {
  const double V = 2.0, T = 10.0, d = 1e-9;
  const Tow tow = motion({ramp(Vec3::UnitX(), V, T)});
  for (double b : {0.0, T}) {
    const Jumps j = jumps(tow, b, d);
    // |x(b+d) - x(b-d)| <= 2 d |v|max; |v(b+d) - v(b-d)| <= 2 d |a|max
    EXPECT_LE(j.dpos.norm(), 2 * d * V + 1e-13) << "t = " << b;
    EXPECT_LE(j.dvel.norm(), 2 * d * V / T + 1e-15) << "t = " << b;
  }
  EXPECT_NEAR(jumps(tow, T).dacc.x(), -V / T, 1e-15);  // the documented breakpoint
  EXPECT_NEAR(jumps(tow, 0.0).dacc.x(), V / T, 1e-15);
}

// ---------------------------------------------------------------- heave

// z = A sin(2 pi (t - t0) / P) after t0: rises first, amplitude A, zero before.
TEST(TowLaw, HeaveRisesFirstWithAmplitude) {
  const double A = 1.5, P = 8.0, t0 = 3.0;
  const Tow tow = motion({heave(A, P, t0)});
  EXPECT_EQ(towsim::tow_kinematics(tow, t0 - 1).pos, Vec3::Zero());
  EXPECT_EQ(towsim::tow_kinematics(tow, t0).pos, Vec3::Zero());
  EXPECT_GT(towsim::tow_kinematics(tow, t0 + 0.01).pos.z(), 0.0) << "heave must rise first";
  EXPECT_GT(towsim::tow_kinematics(tow, t0 + 0.01).vel.z(), 0.0);
  double zmax = -1e9, zmin = 1e9;
  for (double t : grid(t0, t0 + 3 * P, 30000)) {
    const Vec3 x = towsim::tow_kinematics(tow, t).pos;
    EXPECT_EQ(x.x(), 0.0);
    EXPECT_EQ(x.y(), 0.0);
    zmax = std::max(zmax, x.z());
    zmin = std::min(zmin, x.z());
  }
  EXPECT_NEAR(towsim::tow_kinematics(tow, t0 + P / 4).pos.z(), A, 1e-14);
  EXPECT_NEAR(towsim::tow_kinematics(tow, t0 + 3 * P / 4).pos.z(), -A, 1e-14);
  EXPECT_NEAR(towsim::tow_kinematics(tow, t0 + P / 2).pos.z(), 0.0, 1e-14);
  // Grid spacing 8e-4 s: the sampled max is within A (w dt)^2/2 ~ 2e-7 of A.
  EXPECT_NEAR(zmax, A, 1e-6);
  EXPECT_NEAR(zmin, -A, 1e-6);
}

// x''' = A w^3, x'''' = A w^4.
TEST(TowLaw, HeaveDerivativesMatchFiniteDifferences) {
  const double A = 1.5, P = 8.0, t0 = 3.0, w = 2 * std::numbers::pi / P;
  const Tow tow = motion({heave(A, P, t0)});
  const FdErrors r = check_fd(tow, grid(0, 30, 157), {t0}, A * w * w * w, A * w * w * w * w);
  report("HeaveFD velocity", r.vel, r.vel_tol);
  report("HeaveFD acceleration", r.acc, r.acc_tol);
  EXPECT_GT(r.checked, 150);
}

// Position continuous at the start; the velocity jumps by A w (theory 6.1).
TEST(TowLaw, HeaveContinuity) {
  const double A = 1.5, P = 8.0, t0 = 3.0, w = 2 * std::numbers::pi / P, d = 1e-9;
  const Tow tow = motion({heave(A, P, t0)});
  const Jumps j = jumps(tow, t0, d);
  EXPECT_LE(j.dpos.norm(), 2 * d * A * w + 1e-15);
  EXPECT_NEAR(j.dvel.z(), A * w, 1e-12);
}

// ---------------------------------------------------------------- turn

namespace {
struct TurnCase {
  Vec3 dir;
  bool port;
};
}  // namespace

// A turn leaves the straight path at the horizontal speed reached at its start,
// on a circle of radius R whose centre is R to port (left of the heading:
// +y when heading +x) or to starboard (-y). The vertical motion carries on.
TEST(TowLaw, TurnKeepsSpeedAndRadius) {
  const double V = 2.0, T = 10.0, R = 50.0, ts = 30.0;
  const TurnCase cases[] = {{Vec3::UnitX(), true},
                            {Vec3::UnitX(), false},
                            {Vec3(1, 1, 0), true},
                            {Vec3(-1, 2, 0), false}};
  double err_speed = 0, err_radius = 0;
  for (const TurnCase& c : cases) {
    const Tow tow = motion({ramp(c.dir, V, T), turn(R, ts, c.port)}, Vec3(5, 6, -7));
    const TowKinematics k0 = towsim::tow_kinematics(tow, ts);
    const Vec3 h = c.dir.normalized();
    // Left of the heading h = (hx, hy): (-hy, hx).
    const Vec3 left(-h.y(), h.x(), 0);
    const Vec3 centre = k0.pos + (c.port ? R : -R) * left;
    for (double t : grid(ts, ts + 400, 997)) {
      const TowKinematics k = towsim::tow_kinematics(tow, t);
      const Vec3 vh(k.vel.x(), k.vel.y(), 0);
      const Vec3 rel(k.pos.x() - centre.x(), k.pos.y() - centre.y(), 0);
      err_speed = std::max(err_speed, std::abs(vh.norm() - V));
      err_radius = std::max(err_radius, std::abs(rel.norm() - R));
      EXPECT_DOUBLE_EQ(k.pos.z(), -7.0);
      EXPECT_EQ(k.vel.z(), 0.0);
    }
    // Early in the turn the path bends towards the centre's side.
    const TowKinematics k1 = towsim::tow_kinematics(tow, ts + 5);
    EXPECT_GT((k1.pos - k0.pos).dot(c.port ? left : Vec3(-left)), 0.0);
    EXPECT_GT(k1.acc.dot(c.port ? left : Vec3(-left)), 0.0);
  }
  // Heading +x: port turns towards +y, starboard towards -y.
  const Tow port = motion({ramp(Vec3::UnitX(), V, T), turn(R, ts, true)});
  const Tow stbd = motion({ramp(Vec3::UnitX(), V, T), turn(R, ts, false)});
  EXPECT_GT(towsim::tow_kinematics(port, ts + 10).pos.y(), 0.0);
  EXPECT_LT(towsim::tow_kinematics(stbd, ts + 10).pos.y(), 0.0);
  // Half a turn later (pi R / V) heading is reversed, displaced by 2R sideways.
  const TowKinematics half = towsim::tow_kinematics(port, ts + std::numbers::pi * R / V);
  EXPECT_NEAR(half.pos.y(), 2 * R, 1e-9);
  EXPECT_NEAR(half.vel.x(), -V, 1e-12);
  // Values of size R = 50 m: round-off of cos, sin ~ 1e-14 relative.
  const double tol = 1e-11;
  report("TurnKeepsSpeedAndRadius | |v_h| - V |", err_speed, tol);
  report("TurnKeepsSpeedAndRadius | |x - C| - R |", err_radius, tol);
  EXPECT_LE(err_speed, tol);
  EXPECT_LE(err_radius, tol);
}

// A turn started during the ramp keeps the speed reached at its start (V t/T),
// not the ramp's final speed.
TEST(TowLaw, TurnDuringRampKeepsSpeedAtStart) {
  const double V = 2.0, T = 10.0, R = 20.0, ts = 4.0;
  const Tow tow = motion({ramp(Vec3::UnitX(), V, T), turn(R, ts, true)});
  for (double t : {4.5, 8.0, 12.0, 50.0}) {
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    EXPECT_NEAR(Vec3(k.vel.x(), k.vel.y(), 0).norm(), V * ts / T, 1e-13) << t;
    EXPECT_NEAR(k.acc.norm(), (V * ts / T) * (V * ts / T) / R, 1e-13) << t;
  }
}

// Circle at speed V, radius R: |x'''| = V^3/R^2, |x''''| = V^4/R^3 (plus the
// heave's A w^3, A w^4 on z).
TEST(TowLaw, TurnDerivativesMatchFiniteDifferences) {
  const double V = 2.0, T = 10.0, R = 30.0, ts = 25.0;
  for (bool port : {true, false}) {
    const Tow tow = motion({ramp(Vec3(1, -0.5, 0), V, T), turn(R, ts, port)});
    const FdErrors r = check_fd(tow, grid(ts, ts + 120, 311), {ts}, V * V * V / (R * R), V * V * V * V / (R * R * R));
    report(port ? "TurnFD (port) velocity" : "TurnFD (starboard) velocity", r.vel, r.vel_tol);
    report(port ? "TurnFD (port) acceleration" : "TurnFD (starboard) acceleration", r.acc, r.acc_tol);
    EXPECT_GT(r.checked, 300);
  }
}

// Position and velocity continuous at the start of the turn (acceleration
// jumps to the centripetal V^2/R).
TEST(TowLaw, TurnContinuity) {
  const double V = 2.0, T = 10.0, R = 30.0, ts = 25.0, d = 1e-9;
  for (bool port : {true, false}) {
    const Tow tow = motion({ramp(Vec3(1, -0.5, 0), V, T), turn(R, ts, port)});
    const Jumps j = jumps(tow, ts, d);
    EXPECT_LE(j.dpos.norm(), 2 * d * V + 1e-13);
    EXPECT_LE(j.dvel.norm(), 2 * d * V * V / R + 1e-14);
    EXPECT_NEAR(j.dacc.norm(), V * V / R, 1e-12);
  }
}

// ---------------------------------------------------------------- track

// Three points (0,0), (1,1), (2,0) in x: natural spline by hand. On [0,1]
// S = a t + c t^3 with S''(0) = 0 and, by the one interior equation
// 2 (h0 + h1) M1 = 6 [(0-1)/1 - (1-0)/1], M1 = S''(1) = -3: c = -1/2, a = 3/2.
// S(0.5) = 0.6875, S'(0.5) = 1.125, S''(0.5) = -1.5; S'(1) = 0 (symmetry).
TEST(TowLaw, TrackThreePointHandCalculation) {
  const Tow tow = motion({track({0, 1, 2}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0)})}, Vec3(10, 0, 0));
  TowKinematics k = towsim::tow_kinematics(tow, 0.5);
  EXPECT_NEAR(k.pos.x(), 10.6875, 1e-14);
  EXPECT_NEAR(k.vel.x(), 1.125, 1e-14);
  EXPECT_NEAR(k.acc.x(), -1.5, 1e-14);
  k = towsim::tow_kinematics(tow, 1.5);  // mirror image
  EXPECT_NEAR(k.pos.x(), 10.6875, 1e-14);
  EXPECT_NEAR(k.vel.x(), -1.125, 1e-14);
  EXPECT_NEAR(towsim::tow_kinematics(tow, 1.0).vel.x(), 0.0, 1e-14);
  // Straight-line extrapolation outside the table at the end slopes 3/2, -3/2.
  k = towsim::tow_kinematics(tow, -2.0);
  EXPECT_NEAR(k.pos.x(), 10 - 3.0, 1e-14);
  EXPECT_NEAR(k.vel.x(), 1.5, 1e-14);
  EXPECT_EQ(k.acc, Vec3::Zero());
  k = towsim::tow_kinematics(tow, 4.0);
  EXPECT_NEAR(k.pos.x(), 10 - 3.0, 1e-14);
  EXPECT_NEAR(k.vel.x(), -1.5, 1e-14);
}

// A natural cubic spline is the unique C2 piecewise cubic through the points
// with zero second derivative at both ends. Check each property on an uneven
// 3-D table: interpolation, C2 at the knots, natural ends, acceleration linear
// in each segment (so the position is cubic), and v = x', a = v' by FD.
TEST(TowLaw, TrackIsNaturalCubicSpline) {
  const std::vector<double> ts = {0, 2, 3, 7, 8.5, 12};
  const std::vector<Vec3> xs = {Vec3(0, 0, 0),    Vec3(3, 1, -0.5),    Vec3(5, 1.5, -1),
                                Vec3(9, -2, 0.5), Vec3(11, -2.5, 0.2), Vec3(16, 0, 0)};
  const Vec3 x0(100, 200, -5);
  const Tow tow = motion({track(ts, xs)}, x0);
  double err_pts = 0, err_c2 = 0, err_lin = 0, jerk = 0;
  const double d = 1e-9;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    err_pts = std::max(err_pts, (towsim::tow_kinematics(tow, ts[i]).pos - (x0 + xs[i])).norm());
    if (i > 0 && i + 1 < ts.size()) {
      const Jumps j = jumps(tow, ts[i], d);
      err_c2 = std::max({err_c2, j.dpos.norm(), j.dvel.norm(), j.dacc.norm()});
    }
  }
  // Natural ends: S'' = 0 at the first and last knot (one-sided, inside).
  EXPECT_LE(towsim::tow_kinematics(tow, ts.front() + 1e-12).acc.norm(), 1e-10);
  EXPECT_LE(towsim::tow_kinematics(tow, ts.back() - 1e-12).acc.norm(), 1e-10);
  // Acceleration linear on each segment: samples at s = 0.1 and 0.9 of the
  // segment fix the line; s = 0.25, 0.5, 0.75 must lie on it.
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    const double hs = ts[i + 1] - ts[i];
    const Vec3 a0 = towsim::tow_kinematics(tow, ts[i] + 0.1 * hs).acc;
    const Vec3 a1 = towsim::tow_kinematics(tow, ts[i] + 0.9 * hs).acc;
    jerk = std::max(jerk, (a1 - a0).norm() / (0.8 * hs));
    for (double s : {0.25, 0.5, 0.75}) {
      const double t = ts[i] + s * hs;
      err_lin = std::max(err_lin, (towsim::tow_kinematics(tow, t).acc - (a0 + (s - 0.1) / 0.8 * (a1 - a0))).norm());
    }
  }
  // Knot values: round-off on |x| ~ 200 m; one-sided limits at distance d:
  // jumps of pos, vel, acc bounded by 2 d (|v|, |a|, |jerk|) < 1e-7 for |v|, |a|,
  // |jerk| < 50 here.
  report("TrackIsNaturalCubicSpline |S(t_i) - x_i|", err_pts, 1e-12);
  report("TrackIsNaturalCubicSpline C2 jumps at knots", err_c2, 1e-7);
  report("TrackIsNaturalCubicSpline acc linearity in segments", err_lin, 1e-12);
  EXPECT_LE(err_pts, 1e-12);
  EXPECT_LE(err_c2, 1e-7);
  EXPECT_LE(err_lin, 1e-12);
  // Derivatives: |x'''| <= max segment jerk; x'''' = 0 inside a segment.
  const FdErrors r = check_fd(tow, grid(-2, 14, 401), ts, jerk, 0.0);
  report("TrackFD velocity", r.vel, r.vel_tol);
  report("TrackFD acceleration", r.acc, r.acc_tol);
  EXPECT_GT(r.checked, 380);
}

// Collinear points equally timed: the spline is the straight line itself.
TEST(TowLaw, TrackThroughCollinearPointsIsLinear) {
  const Vec3 v(1.5, -0.5, 0.1);
  const Tow tow = motion({track({0, 1, 3, 4, 9}, {0 * v, 1 * v, 3 * v, 4 * v, 9 * v})});
  double err = 0;
  for (double t : grid(-1, 10, 57)) {
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    err = std::max({err, (k.pos - t * v).norm(), (k.vel - v).norm(), k.acc.norm()});
  }
  report("TrackThroughCollinearPointsIsLinear", err, 1e-13);
  EXPECT_LE(err, 1e-13);
}

// ---------------------------------------------------------------- sums

// Pieces without a turn add: law(all) = start + sum of law(piece) (each from 0).
TEST(TowLaw, PiecesAdd) {
  const TowPiece r = ramp(Vec3(1, 0.2, 0), 1.8, 12.0);
  const TowPiece h = heave(0.7, 6.0, 5.0);
  const TowPiece tr = track({0, 10, 20, 35}, {Vec3::Zero(), Vec3(0, 2, 0), Vec3(0, 1, 1), Vec3(0, -1, 0)});
  const Vec3 x0(1, 2, -10);
  const Tow all = motion({r, h, tr}, x0);
  double err = 0;
  for (double t : grid(-1, 50, 211)) {
    const TowKinematics ka = towsim::tow_kinematics(all, t);
    TowKinematics sum{x0, Vec3::Zero(), Vec3::Zero()};
    for (const TowPiece& p : {r, h, tr}) {
      const TowKinematics k = towsim::tow_kinematics(motion({p}), t);
      sum.pos += k.pos;
      sum.vel += k.vel;
      sum.acc += k.acc;
    }
    err = std::max({err, (ka.pos - sum.pos).norm(), (ka.vel - sum.vel).norm(), (ka.acc - sum.acc).norm()});
  }
  report("PiecesAdd |law(sum) - sum of laws|", err, 1e-13);
  EXPECT_LE(err, 1e-13);
}

// Ramp + heave + turn: FD checks on the sum; the heave carries on during the
// turn on z while the horizontal path is the circle.
TEST(TowLaw, SumOfPiecesDerivativesMatchFiniteDifferences) {
  const double V = 2.0, R = 40.0, A = 0.8, P = 7.0, w = 2 * std::numbers::pi / P;
  const Tow tow = motion({ramp(Vec3::UnitX(), V, 10.0), heave(A, P, 6.0), turn(R, 30.0, false)});
  // Jerk: ramp 0, heave A w^3, turn V^3/R^2 (orthogonal components: sum bounds it).
  const FdErrors r = check_fd(tow, grid(0, 120, 503), {0.0, 6.0, 10.0, 30.0}, A * w * w * w + V * V * V / (R * R),
                              A * w * w * w * w + V * V * V * V / (R * R * R));
  report("SumFD velocity", r.vel, r.vel_tol);
  report("SumFD acceleration", r.acc, r.acc_tol);
  EXPECT_GT(r.checked, 490);
  // During the turn z is exactly the heave's.
  const TowKinematics k = towsim::tow_kinematics(tow, 55.0);
  EXPECT_NEAR(k.pos.z(), A * std::sin(w * (55.0 - 6.0)), 1e-13);
  EXPECT_NEAR(Vec3(k.vel.x(), k.vel.y(), 0).norm(), V, 1e-13);
}

// ---------------------------------------------------------------- force

// Linear interpolation between rows, held constant beyond the ends.
TEST(TowLaw, ForceTableInterpolatesAndHolds) {
  Tow tow;
  tow.mode = Tow::Mode::Force;
  tow.force_time = {0, 10, 30};
  tow.force_value = {Vec3(0, 0, 0), Vec3(100, -20, 10), Vec3(200, 0, 0)};
  EXPECT_EQ(towsim::tow_force(tow, -5), Vec3(0, 0, 0));
  EXPECT_LE((towsim::tow_force(tow, 5) - Vec3(50, -10, 5)).norm(), 1e-13);
  EXPECT_LE((towsim::tow_force(tow, 10) - Vec3(100, -20, 10)).norm(), 1e-13);
  EXPECT_LE((towsim::tow_force(tow, 25) - Vec3(175, -5, 2.5)).norm(), 1e-12);  // s = 3/4
  EXPECT_EQ(towsim::tow_force(tow, 30), Vec3(200, 0, 0));
  EXPECT_EQ(towsim::tow_force(tow, 1e6), Vec3(200, 0, 0));
  Tow one = tow;
  one.force_time = {4};
  one.force_value = {Vec3(1, 2, 3)};
  EXPECT_EQ(towsim::tow_force(one, 0), Vec3(1, 2, 3));
  EXPECT_EQ(towsim::tow_force(one, 100), Vec3(1, 2, 3));
  Tow none = tow;
  none.force_time.clear();
  none.force_value.clear();
  EXPECT_EQ(towsim::tow_force(none, 3), Vec3::Zero());
}

// ---------------------------------------------------------------- breakpoints

// End of a ramp, start of a heave or a turn, ends of a track, rows of a force
// table: only times > 0, sorted, without duplicates.
TEST(TowLaw, Breakpoints) {
  Tow tow = motion({ramp(Vec3::UnitX(), 2, 10), heave(1, 5, 7), turn(30, 40, true),
                    track({-1, 3, 10, 25}, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}), heave(1, 5, 0),
                    ramp(Vec3::UnitY(), 1, 0)});
  EXPECT_EQ(towsim::tow_breakpoints(tow), (std::vector<double>{7, 10, 25, 40}));
  // A force table's rows count only in force mode.
  tow.force_time = {0, 5, 12};
  tow.force_value = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  EXPECT_EQ(towsim::tow_breakpoints(tow), (std::vector<double>{7, 10, 25, 40}));
  tow.mode = Tow::Mode::Force;
  EXPECT_EQ(towsim::tow_breakpoints(tow), (std::vector<double>{5, 7, 10, 12, 25, 40}));
  EXPECT_TRUE(towsim::tow_breakpoints(motion({ramp(Vec3::UnitX(), 2, 0)})).empty());
}
