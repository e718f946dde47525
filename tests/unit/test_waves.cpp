// Linear waves (towsim/waves/waves.hpp) against the dispersion relation, the
// Airy boundary-value problem (continuity, irrotationality, kinematic and
// dynamic surface conditions, by finite differences), closed-form amplitudes,
// and the statistics of a long synthetic record (MODEL.md 9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "../support/fd.hpp"
#include "towsim/waves/waves.hpp"

namespace {

using Vec3 = Eigen::Vector3d;
using towsim::WaveField;
using towsim::testing::fd_with_bound;
constexpr double kG = 9.81;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

void report(const char* what, double value, double tol) {
  std::printf("[measured] %-60s %.3e  (tol %.3e)\n", what, value, tol);
}

Eigen::VectorXd v3(const Vec3& v) { return Eigen::VectorXd(v); }

// Dispersion: omega^2 = g k tanh(k h) solved to a relative residual of 1e-12
// (Newton stops at |dk| <= 1e-15 k; the residual is then round-off, ~1e-15).
TEST(Waves, DispersionRelationSolvedTo1e12) {
  double worst = 0;
  for (double T : {2.0, 5.0, 9.0, 15.0, 30.0})
    for (double h : {1.0, 10.0, 50.0, 200.0, 5000.0}) {
      const double w = 2 * kPi / T, k = towsim::wave_number(w, h, kG);
      worst = std::max(worst, std::abs(kG * k * std::tanh(k * h) - w * w) / (w * w));
    }
  report("max relative residual of omega^2 = g k tanh(kh)", worst, 1e-12);
  EXPECT_LE(worst, 1e-12);
  // Deep water: exactly omega^2 / g.
  EXPECT_DOUBLE_EQ(towsim::wave_number(0.7, kInf, kG), 0.49 / kG);
  // Shallow limit: k h -> 0 gives c = sqrt(g h): k = omega / sqrt(g h) (1 + (kh)^2/6 + ...).
  const double h = 1.0, w = 0.05, k = towsim::wave_number(w, h, kG);
  EXPECT_NEAR(k, w / std::sqrt(kG * h), 1e-3 * k) << "kh = " << k * h << ": the O((kh)^2) term is < 1e-3";
}

// A small irregular sea for the field identities (any superposition must satisfy them).
WaveField sea(double depth) {
  return towsim::make_irregular_sea(3.0, 9.0, 3.3, 30, 7, Vec3(std::cos(0.4), std::sin(0.4), 0), depth, kG);
}

// Continuity div u = 0 and curl u = 0 by central differences of step
// h = 1e-2 m. Truncation h^2/6 |u'''| ~ 1e-4 * k^3 a omega ~ 1e-7 m/s/m for these
// waves (k <= 0.3 1/m, a omega <= 1 m/s); tolerance 1e-6 [1/s].
TEST(Waves, AiryFieldIsDivergenceAndCurlFree) {
  for (double depth : {kInf, 40.0}) {
    const WaveField w = sea(depth);
    const double h = 1e-2, t = 13.7;
    double worst_div = 0, worst_curl = 0;
    for (const Vec3& x : {Vec3(3, -2, -0.5), Vec3(-20, 7, -6), Vec3(50, 11, -15)}) {
      Eigen::Matrix3d J;  // J(i, j) = du_i / dx_j
      for (int j = 0; j < 3; ++j) {
        const Vec3 d = h * Vec3::Unit(j);
        J.col(j) = (w.velocity(x + d, t) - w.velocity(x - d, t)) / (2 * h);
      }
      worst_div = std::max(worst_div, std::abs(J.trace()));
      worst_curl = std::max(worst_curl, (J - J.transpose()).norm());
    }
    report(depth == kInf ? "deep: |div u|" : "h = 40 m: |div u|", worst_div, 1e-6);
    report(depth == kInf ? "deep: |curl u|" : "h = 40 m: |curl u|", worst_curl, 1e-6);
    EXPECT_LE(worst_div, 1e-6);
    EXPECT_LE(worst_curl, 1e-6);
  }
}

// Surface conditions at z = 0 (linearised): kinematic d(eta)/dt = w, and
// dynamic (p = 0 on the surface, linearised Euler) du_h/dt = -g grad(eta).
// The analytic acceleration is also the time derivative of the velocity.
// Finite differences with their own error bounds (tests/support/fd.hpp),
// plus the round-off of the phases omega t (eps omega t per harmonic, divided
// by the step: 8 eps t sum a omega^n / h).
TEST(Waves, AiryKinematicAndDynamicSurfaceConditions) {
  for (double depth : {kInf, 40.0}) {
    const WaveField w = sea(depth);
    double s1 = 0, s2 = 0;
    for (const auto& c : w.components) s1 += c.amplitude * c.omega, s2 += c.amplitude * c.omega * c.omega;
    constexpr double eps = std::numeric_limits<double>::epsilon();
    for (double t : {0.0, 21.3, 400.1}) {
      const double r1 = 8 * eps * t * s1 / 1e-4, r2 = 8 * eps * t * s2 / 1e-4;
      const Vec3 x(12.0, -4.0, 0.0);
      auto eta_t = [&](double s) { return Eigen::VectorXd::Constant(1, w.elevation(x, s)); };
      const auto [deta, b1] = fd_with_bound(eta_t, t, 1e-4);
      EXPECT_NEAR(deta[0], w.velocity(x, t).z(), b1 + r1 + 1e-12);
      for (int j = 0; j < 2; ++j) {
        auto eta_x = [&](double s) {
          Vec3 y = x;
          y[j] = s;
          return Eigen::VectorXd::Constant(1, w.elevation(y, t));
        };
        const auto [grad, b2] = fd_with_bound(eta_x, x[j], 1e-3);
        EXPECT_NEAR(w.acceleration(x, t)[j], -kG * grad[0], kG * b2 + 1e-12) << "component " << j;
      }
      const Vec3 xd(5.0, 3.0, -7.0);
      auto u_t = [&](double s) { return v3(w.velocity(xd, s)); };
      const auto [du, b3] = fd_with_bound(u_t, t, 1e-4);
      EXPECT_LE((du - v3(w.acceleration(xd, t))).norm(), b3 + r2 + 1e-12);
    }
  }
}

// Regular deep-water wave: horizontal velocity amplitude a omega e^{kz}
// (the maximum over a period, sampled at 1/2000 of it: cos error < 5e-6).
TEST(Waves, ParticleVelocityAmplitudeDecaysAsExpKz) {
  const double H = 2.0, T = 8.0, a = H / 2, w = 2 * kPi / T, k = w * w / kG;
  const WaveField f = towsim::make_regular_wave(H, T, Vec3::UnitX(), kInf, kG);
  for (double z : {0.0, -5.0, -20.0, -60.0}) {
    double umax = 0, wmax = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 u = f.velocity(Vec3(0, 0, z), T * i / 2000.0);
      umax = std::max(umax, u.x());
      wmax = std::max(wmax, u.z());
    }
    const double expect = a * w * std::exp(k * z);
    EXPECT_NEAR(umax, expect, 5e-6 * expect) << "z = " << z;
    EXPECT_NEAR(wmax, expect, 5e-6 * expect) << "z = " << z;
  }
  // Crest at the origin at t = 0.
  EXPECT_DOUBLE_EQ(f.elevation(Vec3::Zero(), 0.0), a);
  // Above the still surface: no kinematics (documented choice).
  EXPECT_EQ(f.velocity(Vec3(0, 0, 0.1), 0.0), Vec3::Zero());
  EXPECT_EQ(f.acceleration(Vec3(0, 0, 0.1), 0.0), Vec3::Zero());
}

// Cut-off: below each component's cut height its kinematics are skipped; the
// error against the full sum (computed here from the closed form) is bounded
// by kWaveCutoff * sum a_i omega_i^n.
TEST(Waves, CutOffErrorIsBounded) {
  const WaveField w = towsim::make_irregular_sea(3.0, 9.0, 3.3, 200, 1, Vec3::UnitX(), kInf, kG);
  double sum_v = 0, sum_a = 0;
  for (const auto& c : w.components) sum_v += c.amplitude * c.omega, sum_a += c.amplitude * c.omega * c.omega;
  double worst_v = 0, worst_a = 0;
  for (double z : {-2.0, -10.0, -40.0, -100.0, -200.0, -400.0})
    for (double t : {0.0, 17.0, 333.0}) {
      Vec3 u = Vec3::Zero(), acc = Vec3::Zero();
      for (const auto& c : w.components) {
        const double th = c.omega * t - c.phase, e = std::exp(c.k * z);
        u += c.amplitude * c.omega * e * Vec3(std::cos(th), 0, -std::sin(th));
        acc += -c.amplitude * c.omega * c.omega * e * Vec3(std::sin(th), 0, std::cos(th));
      }
      worst_v = std::max(worst_v, (u - w.velocity(Vec3(0, 0, z), t)).norm() / sum_v);
      worst_a = std::max(worst_a, (acc - w.acceleration(Vec3(0, 0, z), t)).norm() / sum_a);
    }
  report("cut-off: velocity error / sum a omega", worst_v, towsim::kWaveCutoff);
  report("cut-off: acceleration error / sum a omega^2", worst_a, towsim::kWaveCutoff);
  EXPECT_LE(worst_v, towsim::kWaveCutoff);
  EXPECT_LE(worst_a, towsim::kWaveCutoff);
  // Deep below every cut: exactly zero work and value.
  EXPECT_EQ(w.velocity(Vec3(0, 0, -5000), 1.0), Vec3::Zero());
}

// The spectrum integrates to hs^2 / 16 (trapezoid in omega on [0.05, 40]
// rad/s, step 1e-4: quadrature error < 1e-6, the tail beyond 40 rad/s ~1e-9 of
// m0); PM equals its closed form (5/16) Hs^2 wp^4 w^-5 exp(-5/4 (wp/w)^4).
TEST(Waves, SpectralDensityNormalisation) {
  for (double gamma : {1.0, 3.3, 7.0}) {
    double m0 = 0;
    const double dw = 1e-4;
    for (double w = 0.05; w < 40; w += dw)
      m0 += 0.5 * dw * (towsim::spectral_density(3, 9, gamma, w) + towsim::spectral_density(3, 9, gamma, w + dw));
    EXPECT_NEAR(m0, 9.0 / 16, 1e-5 * 9.0 / 16) << "gamma " << gamma;
  }
  const double wp = 2 * kPi / 9;
  for (double w : {0.4, 0.7, 1.0, 2.0}) {
    const double pm = 5.0 / 16 * 9 * std::pow(wp, 4) * std::pow(w, -5) * std::exp(-1.25 * std::pow(wp / w, 4));
    EXPECT_NEAR(towsim::spectral_density(3, 9, 1.0, w), pm, 1e-6 * pm);
  }
}

// The phase generator is the standard's mt19937_64: its 10000th output from
// the default seed is fixed by the C++ standard ([rand.predef]).
TEST(Waves, PhaseGeneratorIsTheStandardMt19937_64) {
  std::mt19937_64 g;
  g.discard(9999);
  EXPECT_EQ(g(), 9981545732273789042ULL);
}

// A 3-hour JONSWAP record (Hs 3 m, Tp 9 s, gamma 3.3, 200 components,
// sampled at 0.5 s): 4 std(eta) = Hs within 3 %, the peak of its smoothed
// periodogram at Tp within 5 % (band-average over 0.03 rad/s), same seed ->
// same record, another seed -> another record.
TEST(Waves, JonswapRecordHasHsAndTp) {
  const double Hs = 3.0, Tp = 9.0, dt = 0.5, T = 3 * 3600;
  const WaveField w = towsim::make_irregular_sea(Hs, Tp, 3.3, 200, 1, Vec3::UnitX(), kInf, kG);
  const int n = static_cast<int>(T / dt);
  std::vector<double> eta(n);
  double mean = 0;
  for (int i = 0; i < n; ++i) mean += (eta[i] = w.elevation(Vec3::Zero(), i * dt)) / n;
  double var = 0;
  for (double e : eta) var += (e - mean) * (e - mean) / n;
  const double hs = 4 * std::sqrt(var);
  report("3 h record: |4 std(eta) / Hs - 1|", std::abs(hs / Hs - 1), 0.03);
  EXPECT_NEAR(hs, Hs, 0.03 * Hs);
  // Periodogram on a grid of frequencies, then a moving band average.
  const double dw = 0.002;
  std::vector<double> ws, P;
  for (double om = 0.3; om < 1.5; om += dw) {
    double re = 0, im = 0;
    for (int i = 0; i < n; ++i)
      re += (eta[i] - mean) * std::cos(om * i * dt), im += (eta[i] - mean) * std::sin(om * i * dt);
    ws.push_back(om);
    P.push_back(re * re + im * im);
  }
  const int half = static_cast<int>(0.015 / dw);
  double best = -1, wpk = 0;
  for (int i = half; i + half < static_cast<int>(P.size()); ++i) {
    double s = 0;
    for (int j = i - half; j <= i + half; ++j) s += P[j];
    if (s > best) best = s, wpk = ws[i];
  }
  const double tp = 2 * kPi / wpk;
  report("3 h record: |Tp(peak of periodogram) / Tp - 1|", std::abs(tp / Tp - 1), 0.05);
  EXPECT_NEAR(tp, Tp, 0.05 * Tp);
  const WaveField same = towsim::make_irregular_sea(Hs, Tp, 3.3, 200, 1, Vec3::UnitX(), kInf, kG);
  const WaveField other = towsim::make_irregular_sea(Hs, Tp, 3.3, 200, 2, Vec3::UnitX(), kInf, kG);
  for (double t : {0.0, 100.0, 5000.0}) {
    EXPECT_EQ(same.elevation(Vec3(1, 2, 0), t), w.elevation(Vec3(1, 2, 0), t));
    EXPECT_NE(other.elevation(Vec3(1, 2, 0), t), w.elevation(Vec3(1, 2, 0), t));
  }
  // Every component carries the same energy: exactly Hs^2 / 16 in all.
  EXPECT_NEAR(w.variance(), Hs * Hs / 16, 1e-12);
}

}  // namespace

namespace {

// Build-up (ramp_time): nothing at t = 0, the full sea after it, and during it
// the acceleration is still the time derivative of the velocity (r' u + r
// du/dt), by central differences with their bound plus the phase round-off.
TEST(Waves, BuildUpRampIsSmoothAndConsistent) {
  WaveField w = towsim::make_irregular_sea(3.0, 9.0, 3.3, 30, 7, Vec3::UnitX(), kInf, kG);
  const WaveField full = w;
  w.ramp_time = 20;
  const Vec3 x(4, 0, -3);
  EXPECT_EQ(w.elevation(x, 0.0), 0.0);
  EXPECT_EQ(w.velocity(x, 0.0), Vec3::Zero());
  EXPECT_EQ(w.velocity(x, 25.0), full.velocity(x, 25.0));
  EXPECT_EQ(w.acceleration(x, 25.0), full.acceleration(x, 25.0));
  for (double t : {0.5, 7.0, 13.3, 19.9}) {
    auto u_t = [&](double s) { return v3(w.velocity(x, s)); };
    const auto [du, b] = fd_with_bound(u_t, t, 1e-4);
    EXPECT_LE((du - v3(w.acceleration(x, t))).norm(), b + 1e-10) << "t = " << t;
  }
}

}  // namespace

namespace {

// Wheeler stretching (waves.stretching: wheeler): under a crest the
// velocity at the surface z = eta equals the linear field's at z = 0, a point
// d below the surface sees the linear value at depth d (deep water), the
// seabed stays at -h (finite depth), nothing acts above the surface; without
// stretching nothing acts above z = 0. The truth is the unstretched linear
// field evaluated by the same code at the stretched height (closed form:
// z' = z - eta deep, (z - eta) h / (h + eta) finite); 1e-12: round-off of
// the sums of a few terms of size a omega ~ 1.6 m/s.
TEST(Waves, WheelerStretchingMapsTheSurfaceToZ0) {
  constexpr double kTol = 1e-12;
  for (double h : {kInf, 30.0}) {
    const WaveField lin = towsim::make_regular_wave(4.0, 8.0, Vec3::UnitX(), h, kG);
    WaveField wh = lin;
    wh.wheeler = true;
    const double a = 2.0;
    // Crest at x = 0, t = 0 (eta = a); trough at t = T/2 (eta = -a).
    const Vec3 crest(0, 0, a);
    EXPECT_NEAR(wh.elevation(crest, 0), a, kTol);
    EXPECT_LT((wh.velocity(crest, 0) - lin.velocity(Vec3::Zero(), 0)).norm(), kTol) << "h = " << h;
    const double coth = std::isfinite(h) ? 1 / std::tanh(lin.components[0].k * h) : 1.0;
    EXPECT_NEAR(wh.velocity(crest, 0).x(), a * 2 * kPi / 8.0 * coth, kTol) << "a omega coth(kh) at the crest";
    EXPECT_LT((wh.acceleration(crest, 0) - lin.acceleration(Vec3::Zero(), 0)).norm(), kTol);
    EXPECT_EQ(wh.velocity(Vec3(0, 0, a + 1e-9), 0), Vec3::Zero()) << "above the crest";
    EXPECT_EQ(wh.velocity(Vec3(0, 0, -a + 0.5), 4.0), Vec3::Zero()) << "above the trough";
    EXPECT_EQ(lin.velocity(Vec3(0, 0, 0.5), 0), Vec3::Zero()) << "linear: nothing above z = 0";
    for (double t : {0.0, 1.3, 4.0}) {
      const Vec3 x(3.0, 1.0, 0);
      const double eta = wh.elevation(x, t);
      for (double d : {0.0, 5.0, 12.0}) {
        const double z = eta - d;
        const double zs = std::isfinite(h) ? (z - eta) * h / (h + eta) : z - eta;
        EXPECT_LT((wh.velocity(Vec3(x.x(), x.y(), z), t) - lin.velocity(Vec3(x.x(), x.y(), zs), t)).norm(), kTol)
            << "h = " << h << ", t = " << t << ", d = " << d;
      }
      if (std::isfinite(h)) {
        EXPECT_LT((wh.velocity(Vec3(x.x(), x.y(), -h), t) - lin.velocity(Vec3(x.x(), x.y(), -h), t)).norm(), kTol)
            << "the seabed stays at -h";
      }
    }
  }
}

}  // namespace

namespace {

// Short-crested sea (spectrum.spreading: s): the directions drawn follow the
// cos-2s spreading function, whose circular moments are closed forms,
// E[cos theta] = s / (s + 1), E[cos 2 theta] = s (s - 1) / ((s + 1)(s + 2)),
// E[sin theta] = 0. 20000 components: standard errors <= 0.004 (the
// variances of cos, sin and cos 2theta are <= 0.3 here); tolerance 0.012 (3
// standard errors).
TEST(Waves, SpreadDirectionsFollowCos2s) {
  for (double s : {1.0, 4.0, 15.0}) {
    WaveField w = towsim::make_irregular_sea(3.0, 9.0, 3.3, 20000, 7, Vec3(0, 1, 0), kInf, kG);
    towsim::spread_directions(w, s, 7);
    ASSERT_TRUE(w.spread);
    double c1 = 0, s1 = 0, c2 = 0;
    const double n = static_cast<double>(w.components.size());
    for (const auto& c : w.components) {
      const double th = std::atan2(w.direction.x() * c.dy - w.direction.y() * c.dx,
                                   w.direction.x() * c.dx + w.direction.y() * c.dy);
      ASSERT_NEAR(std::hypot(c.dx, c.dy), 1.0, 1e-15);
      c1 += std::cos(th) / n, s1 += std::sin(th) / n, c2 += std::cos(2 * th) / n;
    }
    std::printf("[measured] cos-2s s=%g: E[cos]=%.4f (%.4f), E[sin]=%.4f, E[cos2]=%.4f (%.4f)\n", s, c1, s / (s + 1),
                s1, c2, s * (s - 1) / ((s + 1) * (s + 2)));
    EXPECT_NEAR(c1, s / (s + 1), 0.012);
    EXPECT_NEAR(s1, 0.0, 0.012);
    EXPECT_NEAR(c2, s * (s - 1) / ((s + 1) * (s + 2)), 0.012);
  }
}

// A short-crested sea is the sum of its components, each a long-crested
// field along its own direction (built here one by one with the same
// amplitude, frequency and phase): elevation, velocity and acceleration agree
// to round-off (1e-12 of the surface scale sum a omega^2 ~ 1 m/s^2) at the
// surface, at depth and during the build-up.
TEST(Waves, SpreadSeaIsTheSumOfItsComponents) {
  WaveField w = towsim::make_irregular_sea(3.0, 9.0, 3.3, 40, 3, Vec3(1, 0, 0), 60.0, kG);
  towsim::spread_directions(w, 2.0, 3);
  w.ramp_time = 10;
  for (const Vec3& x : {Vec3(0, 0, 0), Vec3(12, -7, -3), Vec3(-30, 4, -25)})
    for (double t : {3.0, 17.0}) {
      double eta = 0;
      Vec3 u = Vec3::Zero(), a = Vec3::Zero();
      for (const auto& c : w.components) {
        WaveField one = w;
        one.spread = false;
        one.direction = Vec3(c.dx, c.dy, 0);
        one.components = {c};
        one.components[0].z_cut = -kInf;  // the sum must keep every term the spread field keeps
        eta += one.elevation(x, t);
        if (c.z_cut <= x.z()) u += one.velocity(x, t), a += one.acceleration(x, t);
      }
      EXPECT_NEAR(w.elevation(x, t), eta, 1e-12);
      EXPECT_LT((w.velocity(x, t) - u).norm(), 1e-12) << x.transpose() << " t " << t;
      EXPECT_LT((w.acceleration(x, t) - a).norm(), 1e-12) << x.transpose() << " t " << t;
    }
}

}  // namespace

namespace {

/// The kinematics summed term by term with the C library's sin, cos and exp
/// (the direct evaluation the vectorised sums replace): velocity and local
/// acceleration at x, with the build-up, Wheeler stretching, short-crested
/// directions and finite depth as WaveField documents them.
void direct_kinematics(const WaveField& w, const Vec3& x, double t, Vec3& u, Vec3& a) {
  u.setZero(), a.setZero();
  double eta = 0;
  for (const auto& c : w.components) {
    const double si = w.spread ? c.dx * x.x() + c.dy * x.y() : w.direction.x() * x.x() + w.direction.y() * x.y();
    eta += c.amplitude * std::cos(c.omega * t - c.k * si - c.phase);
  }
  double r, rd, rdd;
  w.ramp(t, r, rd, rdd);
  eta = w.wheeler ? r * eta : 0.0;
  if (x.z() > eta) return;
  const double z = w.stretched(x.z(), eta);
  for (const auto& c : w.components) {
    if (c.z_cut > z) continue;
    double C = std::exp(c.k * z), S = C;
    if (std::isfinite(w.depth)) {
      const double zc = std::max(z, -w.depth), den = std::sinh(c.k * w.depth);
      C = std::cosh(c.k * (zc + w.depth)) / den;
      S = std::sinh(c.k * (zc + w.depth)) / den;
    }
    const Eigen::Vector2d d = w.spread ? Eigen::Vector2d(c.dx, c.dy) : Eigen::Vector2d(w.direction.head<2>());
    const double si = d.x() * x.x() + d.y() * x.y(), th = c.omega * t - c.k * si - c.phase;
    const double aw = c.amplitude * c.omega, aw2 = aw * c.omega;
    const Vec3 ui(aw * C * std::cos(th) * d.x(), aw * C * std::cos(th) * d.y(), -aw * S * std::sin(th));
    const Vec3 ai(-aw2 * C * std::sin(th) * d.x(), -aw2 * C * std::sin(th) * d.y(), -aw2 * S * std::cos(th));
    u += r * ui;
    a += r * ai + rd * ui;
  }
}

// The vectorised sums (WaveField::kinematics, velocity, acceleration) against
// the direct evaluation: 200 JONSWAP harmonics, deep and 60 m deep water,
// long- and short-crested, with and without Wheeler stretching, during and
// after the build-up, at points from the surface to 150 m down and times to
// 3 hours. Tolerance 1e-13 of the largest possible surface value sum a omega
// (resp. sum a omega^2): the terms' round-off (a phase of 3e4 rad carries
// 3e4 * 1.1e-16 = 3.3e-12 rad in either evaluation, times a omega / sum a omega
// ~ 1/200) summed over 200 terms.
TEST(Waves, VectorisedSumsEqualTheDirectEvaluation) {
  double worst = 0;
  for (double depth : {kInf, 60.0})
    for (bool spread : {false, true})
      for (bool wheeler : {false, true}) {
        WaveField w = towsim::make_irregular_sea(3.0, 9.0, 3.3, 200, 5, Vec3(std::cos(0.3), std::sin(0.3), 0), depth,
                                                 kG);
        if (spread) towsim::spread_directions(w, 4.0, 9);
        w.wheeler = wheeler;
        w.ramp_time = 20;
        double su = 0, sa = 0;
        for (const auto& c : w.components) su += c.amplitude * c.omega, sa += c.amplitude * c.omega * c.omega;
        std::mt19937_64 g(21);
        auto U = [&g](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(g() >> 11) * 0x1.0p-53; };
        for (int i = 0; i < 200; ++i) {
          const Vec3 x(U(-500, 500), U(-200, 200), i % 10 == 0 ? U(-1, 1) : -U(0, 150));
          const double t = i % 4 == 0 ? U(0, 20) : U(0, 10800);
          Vec3 u, a, ur, ar;
          w.kinematics(x, t, &u, &a);
          direct_kinematics(w, x, t, ur, ar);
          worst = std::max({worst, (u - ur).lpNorm<Eigen::Infinity>() / su, (a - ar).lpNorm<Eigen::Infinity>() / sa,
                            (w.velocity(x, t) - u).norm() / su, (w.acceleration(x, t) - a).norm() / sa});
        }
      }
  report("max |vectorised - direct| / sum a omega (resp. a omega^2)", worst, 1e-13);
  EXPECT_LE(worst, 1e-13);
}

}  // namespace
