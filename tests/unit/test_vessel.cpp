// Vessel wave motion from RAOs and the tow point it carries
// (towsim/waves/vessel.hpp; INTERFACE.md "Ship motion from waves").
// Checks against closed forms: a unit heave RAO reproduces the wave, a pitch
// RAO moves a sheave at x by -x pitch, the encounter frequency omega + k U in
// head seas (omega - k U following) from zero crossings, the phase lag, the
// port-starboard mirror, and the analytic rates against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "../support/fd.hpp"
#include "towsim/waves/vessel.hpp"

namespace {

using namespace towsim;
constexpr double kG = 9.81;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
enum { kSurge, kSway, kHeave, kRoll, kPitch, kYaw };

/// A table of one dof at every (period, heading) with one amplitude and phase.
RaoTable table(int dof, double amplitude, double phase_deg, std::vector<double> headings = {0, 90, 180}) {
  RaoTable t;
  t.periods = {2, 30};
  t.headings = headings;
  t.amplitude.assign(6 * 2 * headings.size(), 0.0);
  t.phase_deg.assign(t.amplitude.size(), 0.0);
  for (std::size_t h = 0; h < headings.size(); ++h)
    for (std::size_t p = 0; p < 2; ++p) {
      t.amplitude[t.index(dof, h, p)] = amplitude;
      t.phase_deg[t.index(dof, h, p)] = phase_deg;
    }
  return t;
}

/// A tow at speed U along +x from t = 0 (no ramp), carrying `vessel`.
Tow tow_at(double U, std::shared_ptr<const Vessel> vessel) {
  Tow tow;
  tow.pieces.push_back(Ramp{Vec3::UnitX(), U, 0.0});
  tow.vessel = std::move(vessel);
  return tow;
}

/// Wave travelling at `heading_deg` relative to a course along +x.
std::shared_ptr<const WaveField> regular(double H, double T, double heading_deg) {
  const double c = heading_deg * kPi / 180;
  return std::make_shared<const WaveField>(make_regular_wave(H, T, Vec3(std::cos(c), std::sin(c), 0), kInf, kG));
}

// Heave RAO 1, phase 0, vessel at rest: the tow point's heave is the wave
// elevation at the RAO origin, to round-off (1e-12 m on a 1 m wave), whatever
// the sheave offset (heave moves every point of the ship alike).
TEST(Vessel, UnitHeaveRaoReproducesTheWave) {
  auto w = regular(2.0, 8.0, 180);
  auto v = std::make_shared<const Vessel>(Vec3(-30, 4, 5), 0.0, w, table(kHeave, 1.0, 0.0));
  const Tow tow = tow_at(0.0, v);
  double worst = 0;
  for (int i = 0; i < 400; ++i) {
    const double t = 0.05 * i;
    const TowKinematics k = tow_kinematics(tow, t);
    worst = std::max(worst, std::abs(k.pos.z() - 5 - w->elevation(Vec3::Zero(), t)));
    EXPECT_NEAR(k.pos.x(), -30, 1e-12);
    EXPECT_NEAR(k.pos.y(), 4, 1e-12);
  }
  std::printf("[measured] unit heave RAO: max |tow heave - eta| %.3e m (tol 1e-12)\n", worst);
  EXPECT_LE(worst, 1e-12);
}

// Short-crested sea: each component meets the vessel at its own relative
// heading beta_i, so a heave RAO linear in heading (0.2 m/m in following
// seas to 1.0 m/m in head seas, one-sided table mirrored) gives
// heave = sum a_i (0.2 + 0.8 beta_i / 180) cos(omega_i t - eps_i) for a
// vessel at rest at the origin, computed here from the components' own
// directions; to round-off (1e-11 m on a sum of 40 terms of ~0.2 m).
TEST(Vessel, SpreadSeaUsesEachComponentsHeading) {
  WaveField sea = towsim::make_irregular_sea(2.0, 8.0, 3.3, 40, 5, Vec3(std::cos(2.6), std::sin(2.6), 0), kInf, kG);
  towsim::spread_directions(sea, 3.0, 5);
  auto w = std::make_shared<const WaveField>(sea);
  RaoTable t = table(kHeave, 1.0, 0.0);
  for (std::size_t h = 0; h < t.headings.size(); ++h)
    for (std::size_t p = 0; p < 2; ++p) t.amplitude[t.index(kHeave, h, p)] = 0.2 + 0.8 * t.headings[h] / 180;
  auto v = std::make_shared<const Vessel>(Vec3::Zero(), 0.0, w, t);
  const Tow tow = tow_at(0.0, v);
  double worst = 0;
  for (int i = 0; i < 50; ++i) {
    const double time = 0.37 * i;
    double heave = 0;
    for (const auto& c : w->components) {
      double beta = std::fmod(std::atan2(c.dy, c.dx) * 180 / kPi + 360, 360.0);
      if (beta > 180) beta = 360 - beta;
      heave += c.amplitude * (0.2 + 0.8 * beta / 180) * std::cos(c.omega * time - c.phase);
    }
    worst = std::max(worst, std::abs(tow_kinematics(tow, time).pos.z() - heave));
  }
  std::printf("[measured] spread sea, heave RAO by heading: max |tow heave - sum| %.3e m (tol 1e-11)\n", worst);
  EXPECT_LE(worst, 1e-11);
}

// Pitch RAO only (2 deg/m, phase 0) and a sheave at x = -30 m: heave of the
// sheave = x * pitch (pitch in rad, + = bow up), and surge = -z * pitch for a
// sheave height z = 5 m (small-angle theta x r_s), to round-off.
TEST(Vessel, PitchRaoMovesTheSheaveByXTimesPitch) {
  auto w = regular(2.0, 8.0, 180);
  const double x = -30, z = 5;
  auto v = std::make_shared<const Vessel>(Vec3(x, 0, z), 0.0, w, table(kPitch, 2.0, 0.0));
  const Tow tow = tow_at(0.0, v);
  for (int i = 0; i < 100; ++i) {
    const double t = 0.13 * i;
    const double pitch = 2.0 * kPi / 180 * w->elevation(Vec3::Zero(), t);  // RAO 2 deg/m, in phase
    const TowKinematics k = tow_kinematics(tow, t);
    EXPECT_NEAR(k.pos.z() - z, x * pitch, 1e-12);
    EXPECT_NEAR(k.pos.x() - x, -z * pitch, 1e-12);
  }
}

// Exact rotations (vessel.rotations: exact): the sheave is r_s turned by
// Rz(yaw) Ry(-pitch) Rx(roll) (pitch + = bow up) plus the translations, to
// round-off, with large angles (RAOs of 8-12 deg/m on a 1 m wave) where the
// small-angle form is visibly off; its rates match finite differences.
TEST(Vessel, ExactRotationOfTheSheaveOffset) {
  auto w = regular(2.0, 8.0, 150);
  RaoTable t = table(kPitch, 10.0, 0.0);
  for (std::size_t h = 0; h < t.headings.size(); ++h)
    for (std::size_t p = 0; p < 2; ++p) {
      t.amplitude[t.index(kRoll, h, p)] = 12.0, t.phase_deg[t.index(kRoll, h, p)] = 50;
      t.amplitude[t.index(kYaw, h, p)] = 8.0, t.phase_deg[t.index(kYaw, h, p)] = -30;
      t.amplitude[t.index(kHeave, h, p)] = 0.9, t.phase_deg[t.index(kHeave, h, p)] = 10;
    }
  const Vec3 rs(-30, 4, 5);
  auto exact = std::make_shared<Vessel>(rs, 0.0, w, t);
  exact->set_exact_rotations(true);
  auto small = std::make_shared<const Vessel>(rs, 0.0, w, t);
  const Tow tow = tow_at(0.0, exact), tow_small = tow_at(0.0, small);
  double differs = 0;
  for (double t0 : {0.7, 3.1, 5.9}) {
    const VesselMotion m = exact->motion(tow_law_kinematics(tow, t0), t0);
    const Mat3 R = (Eigen::AngleAxisd(m.x[5], Vec3::UnitZ()) * Eigen::AngleAxisd(-m.x[4], Vec3::UnitY()) *
                    Eigen::AngleAxisd(m.x[3], Vec3::UnitX()))
                       .toRotationMatrix();
    const Vec3 expect = m.x.head<3>() + R * rs;
    EXPECT_LE((tow_kinematics(tow, t0).pos - expect).norm(), 1e-12) << "t = " << t0;
    differs = std::max(differs, (tow_kinematics(tow_small, t0).pos - expect).norm());
    auto pos = [&](double s) { return Eigen::VectorXd(tow_kinematics(tow, s).pos); };
    auto vel = [&](double s) { return Eigen::VectorXd(tow_kinematics(tow, s).vel); };
    const auto [dp, bp] = towsim::testing::fd_with_bound(pos, t0, 1e-4);
    const auto [dv, bv] = towsim::testing::fd_with_bound(vel, t0, 1e-4);
    EXPECT_LE((dp - Eigen::VectorXd(tow_kinematics(tow, t0).vel)).norm(), bp);
    EXPECT_LE((dv - Eigen::VectorXd(tow_kinematics(tow, t0).acc)).norm(), bv);
  }
  std::printf("[measured] small-angle vs exact sheave position at ~10 deg: %.3f m\n", differs);
  EXPECT_GT(differs, 0.1);  // the two forms are really different here
}

// Phase lag: a heave RAO with a 90 deg lag peaks a quarter period after the crest.
TEST(Vessel, PhaseIsALagBehindTheCrest) {
  const double T = 10.0;
  auto w = regular(2.0, T, 180);
  auto v = std::make_shared<const Vessel>(Vec3::Zero(), 0.0, w, table(kHeave, 1.0, 90.0));
  const Tow tow = tow_at(0.0, v);
  EXPECT_NEAR(tow_kinematics(tow, 0.0).pos.z(), 0.0, 1e-12);    // crest at t = 0: heave 0
  EXPECT_NEAR(tow_kinematics(tow, T / 4).pos.z(), 1.0, 1e-12);  // its maximum a quarter period later
}

// Port-starboard mirror: with a table on [0, 180], a wave from 270 deg (travelling
// to starboard... i.e. relative heading 270) gives the 90 deg sway reversed.
TEST(Vessel, OneSidedTableIsMirrored) {
  auto w90 = regular(2.0, 8.0, 90), w270 = regular(2.0, 8.0, 270);
  auto v90 = std::make_shared<const Vessel>(Vec3::Zero(), 0.0, w90, table(kSway, 0.7, 30.0));
  auto v270 = std::make_shared<const Vessel>(Vec3::Zero(), 0.0, w270, table(kSway, 0.7, 30.0));
  const Tow a = tow_at(0.0, v90), b = tow_at(0.0, v270);
  for (double t : {0.0, 1.3, 4.4}) {
    // At the origin both waves have the same elevation history; sway flips sign.
    EXPECT_NEAR(tow_kinematics(a, t).pos.y(), -tow_kinematics(b, t).pos.y(), 1e-12);
    EXPECT_GT(std::abs(tow_kinematics(a, t).pos.y()), 1e-3);
  }
}

// The analytic velocity and acceleration are the time derivatives of the
// position (central differences with their bounds, tests/support/fd.hpp):
// moving at 2 m/s on a straight course, and in a steady turn (the course
// rate is then constant, the case the small-angle/course-rate form is exact).
TEST(Vessel, TowPointRatesAreDerivativesOfPosition) {
  auto w = std::make_shared<const WaveField>(make_irregular_sea(3.0, 9.0, 3.3, 40, 3, Vec3(-1, 0, 0), kInf, kG));
  RaoTable t = table(kHeave, 1.0, 20.0);
  for (int d : {kSurge, kSway, kRoll, kPitch, kYaw})
    for (std::size_t h = 0; h < t.headings.size(); ++h)
      for (std::size_t p = 0; p < 2; ++p) {
        t.amplitude[t.index(d, h, p)] = 0.3 + 0.1 * d + 0.2 * static_cast<double>(p);
        t.phase_deg[t.index(d, h, p)] = 40.0 * d - 70.0 * static_cast<double>(h);
      }
  auto v = std::make_shared<const Vessel>(Vec3(-30, 2, 5), 0.0, w, t);
  // In the turn the relative heading falls from 180 deg at 0.76 deg/s: the
  // sample times stay inside the table interval [90, 180] (the interpolation
  // has kinks at the table's headings), where the RAOs' heading rates count.
  Tow straight = tow_at(2.0, v);
  Tow turning = tow_at(2.0, v);
  Turn turn;
  turn.start_time = 1.0;
  turn.radius = 150;
  turning.pieces.push_back(turn);
  for (const Tow* tow : {&straight, &turning})
    for (double t0 : {10.0, 37.3, 80.0}) {
      auto pos = [&](double s) { return Eigen::VectorXd(tow_kinematics(*tow, s).pos); };
      auto vel = [&](double s) { return Eigen::VectorXd(tow_kinematics(*tow, s).vel); };
      const auto [dp, bp] = towsim::testing::fd_with_bound(pos, t0, 1e-4);
      const auto [dv, bv] = towsim::testing::fd_with_bound(vel, t0, 1e-4);
      const TowKinematics k = tow_kinematics(*tow, t0);
      EXPECT_LE((dp - Eigen::VectorXd(k.vel)).norm(), bp) << "t = " << t0;
      EXPECT_LE((dv - Eigen::VectorXd(k.acc)).norm(), bv) << "t = " << t0;
    }
}

// Build-up: during the waves' ramp_time the motions are scaled by r(t) and
// the tow point's rates still match finite differences of its position.
TEST(Vessel, BuildUpRampKeepsRatesConsistent) {
  WaveField wf = make_irregular_sea(3.0, 9.0, 3.3, 40, 3, Vec3(-1, 0, 0), kInf, kG);
  wf.ramp_time = 30;
  auto w = std::make_shared<const WaveField>(wf);
  auto v = std::make_shared<const Vessel>(Vec3(-30, 2, 5), 0.0, w, table(kPitch, 2.0, 30.0));
  const Tow tow = tow_at(2.0, v);
  EXPECT_NEAR(tow_kinematics(tow, 0.0).pos.z(), 5.0, 1e-15);  // no motion yet
  for (double t0 : {3.0, 15.0, 29.0}) {
    auto pos = [&](double s) { return Eigen::VectorXd(tow_kinematics(tow, s).pos); };
    auto vel = [&](double s) { return Eigen::VectorXd(tow_kinematics(tow, s).vel); };
    const auto [dp, bp] = towsim::testing::fd_with_bound(pos, t0, 1e-4);
    const auto [dv, bv] = towsim::testing::fd_with_bound(vel, t0, 1e-4);
    EXPECT_LE((dp - Eigen::VectorXd(tow_kinematics(tow, t0).vel)).norm(), bp) << "t = " << t0;
    EXPECT_LE((dv - Eigen::VectorXd(tow_kinematics(tow, t0).acc)).norm(), bv) << "t = " << t0;
  }
}

/// Mean zero-up-crossing period of the tow point's heave about its mean
/// (linear interpolation of the crossings, sampled at dt).
double heave_period(const Tow& tow, double duration, double dt) {
  std::vector<double> z;
  for (double t = 0; t <= duration; t += dt) z.push_back(tow_kinematics(tow, t).pos.z());
  double first = -1, last = 0;
  int n = 0;
  for (std::size_t i = 1; i < z.size(); ++i)
    if (z[i - 1] < 0 && z[i] >= 0) {
      const double tc = dt * (static_cast<double>(i - 1) + z[i - 1] / (z[i - 1] - z[i]));
      if (first < 0) first = tc;
      last = tc, ++n;
    }
  return (last - first) / (n - 1);
}

// Encounter frequency: at U = 4 m/s a T = 8 s deep-water wave (k = omega^2/g)
// is met at omega + k U in head seas and |omega - k U| following; the
// zero-crossing period of the tow point's heave over 600 s matches 2 pi /
// omega_e within 1e-4 (crossings interpolated on a 0.01 s grid: error
// ~1e-6 s per crossing, over ~100 cycles).
TEST(Vessel, EncounterFrequencyFromZeroCrossings) {
  const double T = 8.0, U = 4.0, w = 2 * kPi / T, k = w * w / kG;
  for (double heading : {180.0, 0.0}) {
    auto v = std::make_shared<const Vessel>(Vec3::Zero(), 0.0, regular(2.0, T, heading), table(kHeave, 1.0, 0.0));
    const Tow tow = tow_at(U, v);
    const double we = std::abs(w - k * U * std::cos(heading * kPi / 180));
    const double Te = heave_period(tow, 600, 0.01);
    std::printf("[measured] heading %3.0f: encounter period %.6f s, 2 pi / omega_e %.6f s\n", heading, Te,
                2 * kPi / we);
    EXPECT_NEAR(Te, 2 * kPi / we, 1e-4 * Te);
  }
}

// Measured motions: the spline passes through the rows, and a record of
// heave = sin(t) sampled every 0.05 s gives velocity cos(t) within the spline's
// O(h^2) error (h^2/6 ~ 4e-4) away from the ends.
TEST(Vessel, MeasuredMotionRecord) {
  std::vector<double> ts;
  std::vector<Vec6> xs;
  for (int i = 0; i <= 400; ++i) {
    ts.push_back(0.05 * i);
    Vec6 r = Vec6::Zero();
    r[kHeave] = std::sin(0.05 * i);
    xs.push_back(r);
  }
  auto v = std::make_shared<const Vessel>(Vec3::Zero(), 0.0, nullptr, ts, xs);
  const Tow tow = tow_at(0.0, v);
  EXPECT_NEAR(tow_kinematics(tow, 5.0).pos.z(), std::sin(5.0), 1e-12);
  for (double t : {3.0, 7.77, 12.1}) {
    EXPECT_NEAR(tow_kinematics(tow, t).pos.z(), std::sin(t), 1e-5);
    EXPECT_NEAR(tow_kinematics(tow, t).vel.z(), std::cos(t), 4e-4);
    EXPECT_NEAR(tow_kinematics(tow, t).acc.z(), -std::sin(t), 4e-3);
  }
}

// The long-crested RAO sums (one sin and cos per harmonic, the lags by angle
// sums, partial sums in lanes) against the short-crested path, a separate
// direct sum (sin and cos of each phase minus its lag, summed in order), on
// the same 200-harmonic sea with every component given the sea's direction:
// all six motions with distinct RAOs, a moving, accelerating origin, a
// relative heading between two table headings (weights and their rate). The
// two differ by round-off: each term by a few ulp of its amplitude, so the
// sums by < 1e-13 of sum |A| (times the encounter frequency, or its square,
// for the rates): tolerance 1e-12 of those.
TEST(Vessel, LongCrestedSumsEqualTheDirectSum) {
  const WaveField sea = make_irregular_sea(3.0, 9.0, 3.3, 200, 11, Vec3(-0.9, 0.3, 0).normalized(), kInf, kG);
  WaveField spread = sea;
  for (auto& c : spread.components) c.dx = sea.direction.x(), c.dy = sea.direction.y();
  spread.spread = true;
  RaoTable t = table(kHeave, 1.0, 20.0, {0, 45, 90, 135, 180});
  for (int d = 0; d < 6; ++d)
    for (std::size_t h = 0; h < t.headings.size(); ++h)
      for (std::size_t p = 0; p < 2; ++p) {
        t.amplitude[t.index(d, h, p)] = 0.2 + 0.1 * d + 0.15 * static_cast<double>(p) + 0.05 * static_cast<double>(h);
        t.phase_deg[t.index(d, h, p)] = 40.0 * d - 35.0 * static_cast<double>(h) + 10.0 * static_cast<double>(p);
      }
  const Vessel a(Vec3(-30, 2, 5), 0.0, std::make_shared<const WaveField>(sea), t);
  const Vessel b(Vec3(-30, 2, 5), 0.0, std::make_shared<const WaveField>(spread), t);
  double sa = 0, sw = 0, sw2 = 0;
  for (const auto& c : sea.components) {
    const double w = c.omega + c.k * 2.5;  // above the encounter frequency at 2.5 m/s
    sa += 4.5 * c.amplitude, sw += 4.5 * c.amplitude * w, sw2 += 4.5 * c.amplitude * w * w;
  }
  double worst = 0;
  for (double t0 : {0.0, 13.7, 250.0, 10799.3}) {
    // Course 20 deg turning at 0.01 rad/s: relative heading ~141 deg, between 135 and 180.
    const double psi = 20 * kPi / 180;
    const TowKinematics o{Vec3(2.0 * t0, 0.5 * t0, 0), 2.0 * Vec3(std::cos(psi), std::sin(psi), 0),
                          0.02 * Vec3(-std::sin(psi), std::cos(psi), 0)};
    const VesselMotion ma = a.motion(o, t0), mb = b.motion(o, t0);
    worst = std::max({worst, (ma.x - mb.x).lpNorm<Eigen::Infinity>() / sa, (ma.v - mb.v).lpNorm<Eigen::Infinity>() / sw,
                      (ma.a - mb.a).lpNorm<Eigen::Infinity>() / sw2});
    EXPECT_GT(ma.x.cwiseAbs().minCoeff(), 0) << "every motion present";
  }
  std::printf("[measured] long-crested RAO sums against the direct sum: %.3e of sum |A| (tol 1e-12)\n", worst);
  EXPECT_LE(worst, 1e-12);
}

}  // namespace
