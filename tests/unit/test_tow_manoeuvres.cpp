// Manoeuvres (turn with angle_deg, speed changes) on the vessel course, and
// the fluid's point interface, against closed forms and finite differences
// (docs/theory.md 6.2; include/towsim/tow/tow.hpp).
//
// Tolerances. Closed forms are evaluated in a different way from the course
// (arc geometry from the centre of the circle, distance from the speed
// profile's integral), so they agree to round-off: a few eps times the
// largest length involved (~1e3 m here), i.e. ~1e-12 m; we allow 1e-10 m for
// positions and 1e-12 for unit directions. Finite-difference bounds as in
// test_tow_law.cpp: |D_h f - f'| <= h^2/6 max|f'''| + 8 eps |f| / h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "towsim/model/model.hpp"

namespace {

using towsim::CourseState;
using towsim::Heave;
using towsim::Ramp;
using towsim::SpeedChange;
using towsim::Tow;
using towsim::TowKinematics;
using towsim::Turn;
using towsim::Vec3;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;
constexpr double kPosTol = 1e-10;  // [m] round-off on lengths of ~1e3 m (see the header)
constexpr double kDirTol = 1e-12;  // [-] round-off on unit vectors

Tow motion(std::vector<towsim::TowLaw> pieces) {
  Tow tow;
  tow.pieces = std::move(pieces);
  return tow;
}
Turn turn(double R, double t0, bool port, double angle_deg) { return Turn{R, t0, port, angle_deg * kPi / 180}; }

// A 90-degree port turn at constant speed: on the analytic arc (distance R
// from its centre, at the angle V (t - t0) / R), it ends at t0 + (pi/2) R / V
// with the velocity rotated by exactly 90 degrees, then goes straight on.
TEST(Manoeuvres, NinetyDegreeTurnEndsOnTheArcWithTheVelocityRotated) {
  const double V = 2.0, R = 50.0, t0 = 20.0;
  const Vec3 d = Vec3(3, 4, 0).normalized();  // initial heading
  const Tow tow = motion({Ramp{d, V, 0}, turn(R, t0, true, 90)});
  const Vec3 n(-d.y(), d.x(), 0);  // port: the centre is to the left
  const Vec3 p0 = V * t0 * d;
  const Vec3 centre = p0 + R * n;
  const double t_end = t0 + kPi / 2 * R / V;
  double arc_err = 0;
  for (int i = 0; i <= 100; ++i) {
    const double t = t0 + (t_end - t0) * i / 100.0;
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    const double phi = V * (t - t0) / R;
    const Vec3 expected = centre - R * std::cos(phi) * n + R * std::sin(phi) * d;
    arc_err = std::max({arc_err, (k.pos - expected).norm(), std::abs((k.pos - centre).norm() - R)});
  }
  std::printf("[measured] 90-degree turn: max distance from the analytic arc %.3e m (tol %.0e)\n", arc_err, kPosTol);
  EXPECT_LE(arc_err, kPosTol);
  // The turn's end is a breakpoint, computed from the speed profile.
  const auto b = towsim::tow_breakpoints(tow);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0], t0);
  EXPECT_NEAR(b[1], t_end, 1e-12 * t_end);
  // After it: velocity = V n (rotated by +90 degrees), no acceleration, straight on.
  for (double t : {t_end + 1e-9, t_end + 10.0, t_end + 1000.0}) {
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    const double rot_err = (k.vel / V - n).norm();
    std::printf("[measured] after the turn (t = %.1f s): |v/V - rotated heading| = %.3e (tol %.0e)\n", t, rot_err,
                kDirTol);
    EXPECT_LE(rot_err, kDirTol);
    EXPECT_LE(k.acc.norm(), kDirTol);
    EXPECT_LE((k.pos - (centre + R * d + V * (t - t_end) * n)).norm(), kPosTol);
  }
}

// Starboard, 180 degrees, 40 s straight, starboard 180 degrees again (a
// racetrack): back on the initial line and heading.
TEST(Manoeuvres, RacetrackOfTwoHalfTurns) {
  const double V = 1.5, R = 30.0;
  const double half = kPi * R / V;  // duration of a half turn [s]
  const Tow tow = motion({Ramp{Vec3::UnitX(), V, 0}, turn(R, 10, false, 180), turn(R, 10 + half + 40, false, 180)});
  const double t_end = 10 + half + 40 + half;
  const TowKinematics k = towsim::tow_kinematics(tow, t_end + 5);
  // x: 10 V forward, 40 V back, 5 V forward again; y: down one diameter and back.
  const Vec3 expected(10 * V - 40 * V + 5 * V, 0, 0);
  std::printf("[measured] racetrack closure error %.3e m\n", (k.pos - expected).norm());
  EXPECT_LE((k.pos - expected).norm(), kPosTol);
  EXPECT_LE((k.vel - V * Vec3::UnitX()).norm(), kDirTol);
}

// A speed change: the distance run equals the integral of the speed profile,
// U0 tau + (U1 - U0) tau^2 / (2T) during the change and
// (U0 + U1) T / 2 + U1 (tau - T) after it, along the unchanged heading.
TEST(Manoeuvres, SpeedChangeDistanceIsTheIntegralOfTheSpeed) {
  const double U0 = 2.0, U1 = 3.0, ts = 300, T = 30;
  const Vec3 d = Vec3(1, -2, 0).normalized();
  const Tow tow = motion({Ramp{d, U0, 10}, SpeedChange{U1, ts, T}});
  const double s0 = U0 * (ts - 5);  // the ramp's distance at ts (it lost 10/2 s)
  double err = 0, vel_err = 0;
  for (double tau : {0.0, 1.0, 7.5, 15.0, 29.0, 30.0, 31.0, 100.0, 1000.0}) {
    const TowKinematics k = towsim::tow_kinematics(tow, ts + tau);
    const double s = tau <= T ? U0 * tau + (U1 - U0) * tau * tau / (2 * T) : (U0 + U1) * T / 2 + U1 * (tau - T);
    const double U = tau <= T ? U0 + (U1 - U0) * tau / T : U1;
    err = std::max(err, (k.pos - (s0 + s) * d).norm());
    vel_err = std::max(vel_err, (k.vel - U * d).norm());
    if (tau > 0 && tau < T) {
      EXPECT_LE((k.acc - (U1 - U0) / T * d).norm(), 1e-14);
    }
    if (tau > T) {
      EXPECT_EQ(k.acc.norm(), 0.0);
    }
  }
  std::printf("[measured] speed change: distance error %.3e m, speed error %.3e m/s\n", err, vel_err);
  EXPECT_LE(err, kPosTol);
  EXPECT_LE(vel_err, 1e-13);
  EXPECT_EQ(towsim::tow_breakpoints(tow), (std::vector<double>{10, ts, ts + T}));
}

// A turn whose speed changes while it runs ends when the distance run is
// R * angle: t solves U0 tau + a tau^2 / 2 = R angle.
TEST(Manoeuvres, TurnEndsAtItsAngleWhileTheSpeedChanges) {
  const double U0 = 2.0, U1 = 1.0, R = 20.0;
  const Tow tow = motion({Ramp{Vec3::UnitX(), U0, 0}, turn(R, 10, true, 60), SpeedChange{U1, 10, 40}});
  const double a = (U1 - U0) / 40, s = R * kPi / 3;
  const double tau = (-U0 + std::sqrt(U0 * U0 + 2 * a * s)) / a;  // textbook root (independent of the code's form)
  const auto b = towsim::tow_breakpoints(tow);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_NEAR(b[1], 10 + tau, 1e-9);  // root of a quadratic: ~1e-15 relative, 1e-9 s is generous
  EXPECT_EQ(b[2], 50.0);
  const TowKinematics k = towsim::tow_kinematics(tow, 60.0);
  const Vec3 h(std::cos(kPi / 3), std::sin(kPi / 3), 0);
  EXPECT_LE((k.vel - U1 * h).norm(), kDirTol);
}

// Zig-zag with speed changes during turns: v = dx/dt and a = dv/dt by central
// differences, away from the breakpoints; C0 position and velocity across them.
TEST(Manoeuvres, ZigZagDerivativesMatchFiniteDifferences) {
  const double Umax = 3.0, R = 25.0;
  const Tow tow = motion({Ramp{Vec3(1, 1, 0), 2.0, 20}, Heave{0.5, 8.0, 5.0}, turn(R, 30, true, 40),
                          SpeedChange{3.0, 40, 30}, turn(R, 70, false, 80), turn(R, 110, true, 40),
                          SpeedChange{0.5, 120, 20}});
  const auto breaks = towsim::tow_breakpoints(tow);
  ASSERT_GE(breaks.size(), 10u);
  // Bounds: |a| <= 2.5/20 m/s^2, kappa = 1/R; |x'''| <= 3|a|U k + U^3 k^2 (+ heave A w^3),
  // |x''''| <= 3 a^2 k + 6 |a| U^2 k^2 + U^4 k^3 (+ heave A w^4).
  const double acc = 2.5 / 20, k = 1 / R, w = 2 * kPi / 8.0;
  const double jerk = 3 * acc * Umax * k + Umax * Umax * Umax * k * k + 0.5 * w * w * w;
  const double snap = 3 * acc * acc * k + 6 * acc * Umax * Umax * k * k + std::pow(Umax, 4) * k * k * k +
                      0.5 * w * w * w * w;
  const double h = 1e-4;
  double ev = 0, ea = 0;
  int checked = 0;
  for (int i = 1; i <= 2000; ++i) {  // t > 0: before t = 0 the ramp is at rest
    const double t = 0.1 * i;
    if (std::any_of(breaks.begin(), breaks.end(), [&](double b) { return std::abs(t - b) < 2 * h; })) continue;
    const TowKinematics k0 = towsim::tow_kinematics(tow, t), kp = towsim::tow_kinematics(tow, t + h),
                        km = towsim::tow_kinematics(tow, t - h);
    const double tol_v = 2 * (h * h / 6 * jerk) + 8 * kEps * (kp.pos.norm() + km.pos.norm()) / h;
    const double tol_a = 2 * (h * h / 6 * snap) + 8 * kEps * (kp.vel.norm() + km.vel.norm()) / h;
    const double e_v = ((kp.pos - km.pos) / (2 * h) - k0.vel).norm();
    const double e_a = ((kp.vel - km.vel) / (2 * h) - k0.acc).norm();
    EXPECT_LE(e_v, tol_v) << "t = " << t;
    EXPECT_LE(e_a, tol_a) << "t = " << t;
    ev = std::max(ev, e_v);
    ea = std::max(ea, e_a);
    ++checked;
  }
  std::printf("[measured] zig-zag FD: velocity %.3e, acceleration %.3e over %d times\n", ev, ea, checked);
  EXPECT_GT(checked, 1900);  // all but the few times next to a breakpoint
  // Across each breakpoint position and velocity are continuous (to round-off);
  // but the heave, which starts with a velocity jump by design (rising first).
  for (double b : breaks) {
    if (b == 5.0) continue;
    const TowKinematics l = towsim::tow_kinematics(tow, b - 1e-9), r = towsim::tow_kinematics(tow, b + 1e-9);
    EXPECT_LE((r.pos - l.pos).norm(), 1e-8) << "position jump at " << b;  // 2e-9 s x 3 m/s
    EXPECT_LE((r.vel - l.vel).norm(), 1e-8) << "velocity jump at " << b;  // 2e-9 s x |a| + round-off
  }
}

// The course starts from the offsets' horizontal motion; the vertical carries on.
TEST(Manoeuvres, HeaveCarriesOnDuringTheCourse) {
  const double A = 0.8, P = 7.0, w = 2 * kPi / P;
  const Tow tow = motion({Ramp{Vec3::UnitX(), 2.0, 0}, Heave{A, P, 3.0}, SpeedChange{1.0, 10, 5}});
  for (double t : {12.0, 40.0}) {
    const TowKinematics k = towsim::tow_kinematics(tow, t);
    EXPECT_NEAR(k.pos.z(), A * std::sin(w * (t - 3.0)), 1e-14);
    EXPECT_NEAR(k.vel.z(), A * w * std::cos(w * (t - 3.0)), 1e-14);
  }
  CourseState c;
  ASSERT_TRUE(towsim::final_course(tow, c));
  EXPECT_EQ(c.U, 1.0);
  EXPECT_EQ(c.h, Vec3::UnitX());
}

// The tow's course plan (finalize_tow) gives the walk's numbers bit for bit (the
// same segment states, so no tolerance): at random and repeated times, before
// the first manoeuvre, on each side of every breakpoint, after the tow changed
// and was finalized again, with a track, and with pieces added without
// finalizing (the stale plan is not used). The cursor's last result is kept
// only for the plan it came from.
TEST(Manoeuvres, CoursePlanGivesTheWalksNumbersExactly) {
  Tow tow = motion({Ramp{Vec3(1, 1, 0), 2.0, 20}, Heave{0.5, 8.0, 5.0}, turn(25, 30, true, 40),
                    SpeedChange{3.0, 40, 30}, turn(25, 70, false, 80), turn(25, 110, true, 40),
                    SpeedChange{0.5, 120, 20}});
  towsim::finalize_tow(tow);
  towsim::CourseCursor cursor;
  auto same = [&](double t) {
    const TowKinematics a = towsim::tow_law_kinematics(tow, t), b = towsim::tow_law_kinematics(tow, t, cursor);
    const TowKinematics c = towsim::tow_kinematics(tow, t, cursor);
    return a.pos == b.pos && a.vel == b.vel && a.acc == b.acc && b.pos == c.pos && b.acc == c.acc;
  };
  std::vector<double> times{-1.0, 0.0, 29.999, 30.0, 200.0, 200.0, 1e6};
  for (double b : towsim::tow_breakpoints(tow)) times.insert(times.end(), {b, b, std::nextafter(b, 0.0), b + 1e-9});
  for (int i = 0; i < 3000; ++i) times.push_back(std::fmod(i * 0.6180339887 * 97.0, 200.0));  // out of order
  int differ = 0;
  for (double t : times) differ += same(t) ? 0 : 1;
  EXPECT_EQ(differ, 0);
  // The tow changes and is finalized again: a later first turn, then no manoeuvre at all.
  std::get<Turn>(tow.pieces[2]).start_time = 35;
  towsim::finalize_tow(tow);
  EXPECT_TRUE(same(36.0));
  EXPECT_TRUE(same(200.0));
  tow.pieces.resize(2);
  towsim::finalize_tow(tow);
  EXPECT_TRUE(same(200.0));
  tow.start = Vec3(1, 2, 3);
  towsim::finalize_tow(tow);
  EXPECT_TRUE(same(200.0));
  // A track under the course, with its plan; then a piece added without finalize.
  tow.pieces.insert(tow.pieces.begin(), towsim::Track::make({0, 10, 20}, {Vec3::Zero(), Vec3(5, 1, 0), Vec3(9, 4, 0)}));
  tow.pieces.push_back(turn(25, 30, true, 40));
  towsim::finalize_tow(tow);
  for (double t : {15.0, 31.0, 45.0, 200.0}) EXPECT_TRUE(same(t)) << t;
  tow.pieces.push_back(SpeedChange{1.0, 100, 10});
  EXPECT_TRUE(same(200.0));
  EXPECT_TRUE(same(105.0));
  // A piece edited in place after finalize (same count and start): a new
  // cursor (a new run's Workspace) finds the plan stale and walks.
  towsim::finalize_tow(tow);
  std::get<SpeedChange>(tow.pieces.back()).speed = 2.0;
  cursor.checked = nullptr, cursor.plan.reset();  // as a new cursor
  EXPECT_TRUE(same(150.0));
  EXPECT_TRUE(same(200.0));
}

// Material acceleration of a depth-profile current: zero for a horizontal
// current; U_z U'(z) with a vertical component, checked against the change of
// velocity seen by a water particle (central difference along x' = u).
TEST(FluidPoint, VelocityRateAndAcceleration) {
  towsim::Fluid f;
  f.current_depth = {0, 10, 50};
  f.current_velocity = {Vec3(1, 0, 0), Vec3(0.5, 0.2, 0), Vec3(0, 0, 0)};
  const Vec3 x(3, -4, -5), v(0.3, 0.1, -0.7);
  EXPECT_EQ(f.velocity(x, 12.0), f.current(-5));
  EXPECT_EQ(f.rate_seen(x, v, 12.0), f.current_gradient(-5) * v.z());
  EXPECT_EQ(f.acceleration(x, 12.0), Vec3::Zero());
  f.current_velocity = {Vec3(1, 0, 0.1), Vec3(0.5, 0.2, 0.1), Vec3(0, 0, 0.1)};
  const double h = 1e-4;  // FD over a path of speed ~1 m/s inside one linear piece: exact but for round-off
  const Vec3 fd = (f.velocity(x + h * f.velocity(x, 0), h) - f.velocity(x - h * f.velocity(x, 0), -h)) / (2 * h);
  EXPECT_LE((f.acceleration(x, 0) - fd).norm(), 1e-10);  // round-off 1e-16 / 1e-4 x ~1
  EXPECT_GT(f.acceleration(x, 0).norm(), 1e-3);
  EXPECT_TRUE(towsim::Fluid{}.uniform());
}

}  // namespace
