// Physics validation of the cable (docs/contract.md §P2-P3): each test compares a run (or one
// evaluation of the dynamics) with something independent of the code under
// test: a closed-form solution, a conservation law, or a convergence rate.
// Quantities are recomputed here from public outputs (Samples) with formulas
// taken from docs/theory.md, never by calling the code's own load routines.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/paper.hpp"

namespace towsim {
namespace {

using testing::CableSpec;
using testing::RunCase;
constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;

using testing::run_case_param_name;

// ---------------------------------------------------------------------------
// 1. Single rod pendulum in vacuum: period against the exact elliptic integral.
// A homogeneous rod of length L pinned at one end: I = m L^2 / 3 about the pin,
// centre at d = L/2, so  T = 4 sqrt(I / (m g d)) K(k) = 4 sqrt(2 L / (3 g)) K(k),
// k = sin(theta0 / 2), K the complete elliptic integral of the first kind
// (std::comp_ellint_1 takes the modulus k). Small amplitude: T0 = 2 pi sqrt(2L/(3g)).
// ---------------------------------------------------------------------------
struct PendulumCase {
  RunCase run;
  double theta0;  // release angle from the downward vertical [rad]
};

class RodPendulum : public ::testing::TestWithParam<PendulumCase> {};

TEST_P(RodPendulum, PeriodMatchesEllipticIntegral) {
  const PendulumCase c = GetParam();
  const double L = 2.0;
  CableSpec spec;
  spec.n = 1;
  spec.length = L;
  spec.mass_per_length = 1.5;
  Model m = testing::cable_model(spec, /*rho=*/0.0, kG);
  m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point is a fixed pin at the origin
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3(std::sin(c.theta0), 0, -std::cos(c.theta0));

  const double T0 = 2 * kPi * std::sqrt(2 * L / (3 * kG));
  const double T_exact = 4 * std::sqrt(2 * L / (3 * kG)) * std::comp_ellint_1(std::sin(c.theta0 / 2));
  m.sim.duration = 4.1 * T_exact;  // 8 zero crossings: t = T/4 + j T/2, j = 0..7
  m.sim.time_step = 0.005;
  m.sim.output_interval = 0.01;
  m.sim.integrator = c.run.integrator;
  m.sim.tolerance = 1e-10;
  m.sim.formulation = c.run.formulation;
  const auto samples = testing::run(m);

  std::vector<double> t, x, xd;
  for (const Sample& s : samples) {
    t.push_back(s.t);
    x.push_back(s.node_pos[1].x() - s.node_pos[0].x());
    xd.push_back(s.node_vel[1].x() - s.node_vel[0].x());
  }
  const auto cr = testing::zero_crossings(t, x, xd);
  ASSERT_EQ(cr.size(), 8u);
  const double T = testing::period_from_crossings(cr);
  const double err = std::abs(T - T_exact) / T_exact;
  std::cout << "[measured] rod pendulum theta0=" << c.theta0 << " T=" << T << " T_exact=" << T_exact
            << " rel.err=" << err << " (T/T0-1=" << T / T0 - 1 << ")\n";
  // Tolerance 1e-8 relative. RK4 at h = 5 ms: the relative phase error is
  // ~(w h)^4 / 120 with w = 2 pi / T <= 2.7 rad/s, i.e. ~2e-10 (the large
  // swing at 2.5 rad reaches higher rates near the bottom: a few 1e-10);
  // DOPRI5 runs at tolerance 1e-10. The crossing times come from cubic
  // Hermite interpolation between 10 ms samples, error ~(w dt)^4 / 384 of the
  // period ~ 2e-9. Measured: <= 5e-10 (RK4), <= 2.3e-10 (DOPRI5).
  EXPECT_LT(err, 1e-8);
  // The first crossing must be at T/4 (released at rest at the turning point).
  EXPECT_NEAR(cr.front(), T_exact / 4, 1e-8 * T_exact);
  if (c.theta0 < 0.1) {
    // Small amplitude: T / T0 = 1 + theta0^2 / 16 + 11 theta0^4 / 3072 + ...
    // The series' next term is 173 theta0^6 / 737280 ~ 2e-14 at 0.02 rad;
    // the tolerance is the period's own measurement error above.
    const double series = 1 + c.theta0 * c.theta0 / 16 + 11 * std::pow(c.theta0, 4) / 3072;
    EXPECT_NEAR(T / T0, series, 1e-8);
  }
}

std::vector<PendulumCase> pendulum_cases() {
  std::vector<PendulumCase> out;
  for (const RunCase& r : testing::all_run_cases())
    for (double th : {0.02, 1.0, 2.5}) out.push_back({r, th});
  return out;
}

INSTANTIATE_TEST_SUITE_P(Vacuum, RodPendulum, ::testing::ValuesIn(pendulum_cases()), [](const auto& info) {
  const int mrad = static_cast<int>(std::lround(info.param.theta0 * 1000));
  return testing::run_case_name(info.param.run) + "_theta" + std::to_string(mrad) + "mrad";
});

// ---------------------------------------------------------------------------
// 2. Chain in vacuum released from horizontal: energy conservation, and the
// order of RK4 measured by halving the step.
// ---------------------------------------------------------------------------
Model vacuum_chain(int n, double length) {
  CableSpec spec;
  spec.n = n;
  spec.length = length;
  spec.mass_per_length = 1.0;
  Model m = testing::cable_model(spec, /*rho=*/0.0, kG);
  m.tow.mode = Tow::Mode::Motion;  // pinned at the origin
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3::UnitX();
  return m;
}

class ChainEnergy : public ::testing::TestWithParam<RunCase> {};

TEST_P(ChainEnergy, ConservedInVacuum) {
  const RunCase c = GetParam();
  Model m = vacuum_chain(6, 3.0);
  m.sim.duration = 2.0;  // falls through the bottom and whips back up
  m.sim.time_step = 1e-3;
  m.sim.output_interval = 0.01;
  m.sim.integrator = c.integrator;
  m.sim.tolerance = 1e-10;
  m.sim.formulation = c.formulation;
  const auto samples = testing::run(m);
  ASSERT_GT(samples.size(), 100u);
  // Scale: the potential energy released by the fall of the whole chain
  // from horizontal to hanging, M g L / 2.
  const double M = 3.0, scale = M * kG * 3.0 / 2;
  const double E0 = testing::cable_energy(m, samples.front()).total();
  double drift = 0, ke_max = 0;
  for (const Sample& s : samples) {
    const auto E = testing::cable_energy(m, s);
    drift = std::max(drift, std::abs(E.total() - E0) / scale);
    ke_max = std::max(ke_max, E.kinetic / scale);
  }
  std::cout << "[measured] chain energy " << testing::run_case_name(c) << ": max |E-E0|/(MgL/2) = " << drift
            << " (max KE/(MgL/2) = " << ke_max << ")\n";
  EXPECT_GT(ke_max, 0.5);  // the chain really moved: most of the energy went kinetic
  // Bound 1e-7. RK4 is not symplectic: its energy error is its truncation
  // error, O(h^4). The whip of the free end brings the chain's fastest rate
  // to tens of rad/s for a short time, where (w h)^4 / 120 reaches ~1e-8 per
  // step at h = 1 ms; elsewhere w ~ 3-5 rad/s and the error is negligible.
  // Measured: 4e-9 (Default), 3e-9 (Paper); DOPRI5 at tolerance 1e-10: 2e-11.
  EXPECT_LT(drift, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(Vacuum, ChainEnergy, ::testing::ValuesIn(testing::all_run_cases()), run_case_param_name);

class Rk4Order : public ::testing::TestWithParam<Formulation> {};

/// Joint positions at the end of a fixed-step RK4 run.
std::vector<Vec3> rk4_end_positions(Model m, double h) {
  m.sim.integrator = Integrator::RK4;
  m.sim.time_step = h;
  m.sim.output_interval = m.sim.duration;
  return testing::run(m).back().node_pos;
}

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, (a[k] - b[k]).norm());
  return d;
}

/// err(h) / err(h/2) at the end of a run, against a reference at h/32.
double rk4_ratio(const Model& m, double h, const std::string& what) {
  const auto ref = rk4_end_positions(m, h / 32);
  const double ea = max_distance(rk4_end_positions(m, h), ref);
  const double eb = max_distance(rk4_end_positions(m, h / 2), ref);
  std::cout << "[measured] RK4 order " << what << " " << testing::formulation_name(m.sim.formulation) << ": err(h=" << h
            << ")=" << ea << " err(h/2)=" << eb << " ratio=" << ea / eb << " (order " << std::log2(ea / eb) << ")\n";
  // Errors must be truncation, far above round-off.
  EXPECT_GT(eb, 1e-11);
  return ea / eb;
}

// An order-4 method gives err(h)/err(h/2) -> 16 as h -> 0. We accept 13..19
// (order 3.7..4.25): the reference at h/32 carries err(h/2)/65536, nothing;
// the rest is the O(h^5) term of the error expansion, which still moves the
// ratio by several percent at the steps used (it approaches 16 from below
// here: 13.6, 14.6, 15.3, 15.7 for h = 12, 6, 3, 1.5 ms).
TEST_P(Rk4Order, ErrorFallsSixteenfoldWhenStepHalves) {
  // The chain of test 2 falling from horizontal for 0.6 s (before the whip,
  // whose rates of ~50 rad/s would need h < 1 ms to be in the asymptotic range).
  Model m = vacuum_chain(6, 3.0);
  m.sim.duration = 0.6;
  m.sim.formulation = GetParam();
  const double ratio = rk4_ratio(m, 3e-3, "pinned chain");
  EXPECT_GT(ratio, 13.0);
  EXPECT_LT(ratio, 19.0);
}

/// A towed cable in water, tow point on a smooth track (natural cubic spline:
/// continuous acceleration, knots on whole seconds, i.e. on step boundaries).
/// No tangential friction: its smoothed sign (v_s = 1 mm/s) makes the
/// right-hand side vary on a time scale of ~1 ms whenever an element's axial
/// relative speed crosses zero, which scatters the measured ratios (9..22).
Model smooth_tow_model() {
  CableSpec spec;
  spec.n = 6;
  spec.length = 30;
  spec.tangential = 0.0;
  Model m = testing::cable_model(spec);
  Track p;
  for (int i = -2; i <= 10; ++i) {
    const double t = i;
    p.time.push_back(t);
    p.pos.push_back(Vec3(1.5 * t + 0.3 * std::sin(t), 0.5 * std::sin(0.7 * t), 0.3 * std::sin(1.3 * t)));
  }
  m.tow.pieces.push_back(p);
  return m;
}

TEST_P(Rk4Order, TowedCableOnSmoothTrack) {
  // Fluid loads, added mass, Motion mode: still order 4 when the imposed tow
  // acceleration is continuous. Measured ratios 25, 20, 17.5 for h = 20, 10, 5 ms (from above).
  Model m = smooth_tow_model();
  m.sim.duration = 6.0;
  m.sim.formulation = GetParam();
  const double ratio = rk4_ratio(m, 5e-3, "towed cable, smooth track");
  EXPECT_GT(ratio, 13.0);
  EXPECT_LT(ratio, 19.0);
}

// The same cable on the ramp tow law. The ramp's acceleration jumps at t = 0
// (0 -> V/T) and at t = T (V/T -> 0). RK4 keeps order 4 only if no step
// straddles a jump and a stage at the start of a step sees the right limit of
// the tow acceleration, a stage at its end the left limit. The run loop lands
// on tow_breakpoints() and the systems evaluate the law inside the step's
// window (StepWindow). Before that fix both tests measured ratio 2.0
// (order 1, err ~1.1e-3 m at h = 20 ms).
TEST_P(Rk4Order, TowedCableOnRampStart) {
  // Ramp longer than the run: only the jump at t = 0.
  Model m = smooth_tow_model();
  m.tow.pieces.clear();
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 10.0));
  m.sim.duration = 6.0;
  m.sim.formulation = GetParam();
  const double ratio = rk4_ratio(m, 0.02, "towed cable, ramp start");
  EXPECT_GT(ratio, 13.0) << "RK4 loses its order on the ramp's acceleration jump at t = 0 (see comment)";
  EXPECT_LT(ratio, 19.0);
}

TEST_P(Rk4Order, TowedCableOnRampEnd) {
  // Ramp ending inside the run (T = 3 s): the jump at t = T. Steps of 40 and
  // 20 ms keep the truncation error (~1e-7 m) far above the 1e-12 relative
  // shift of the law's evaluation time inside a step.
  Model m = smooth_tow_model();
  m.tow.pieces.clear();
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 3.0));
  m.sim.duration = 6.0;
  m.sim.formulation = GetParam();
  const double ratio = rk4_ratio(m, 0.04, "towed cable, ramp end");
  EXPECT_GT(ratio, 13.0) << "RK4 loses its order on the ramp's acceleration jump at t = T (see comment)";
  EXPECT_LT(ratio, 19.0);
}

INSTANTIATE_TEST_SUITE_P(Vacuum, Rk4Order, ::testing::Values(Formulation::Default, Formulation::Paper),
                         [](const auto& info) { return testing::formulation_name(info.param); });

// ---------------------------------------------------------------------------
// 3. Cable towed at constant speed, no tangential friction, Morison added
// mass: the steady cable is straight at the critical angle phi (from the
// horizontal). Derivation: element axis e = (-cos phi, 0, -sin phi) (trailing
// aft and down), relative velocity u = V x, so u.e = -V cos phi and
// u_n = u - (u.e) e = V sin phi (sin phi, 0, -cos phi) = V sin phi n with
// n = (sin phi, 0, -cos phi). Normal drag -k L |u_n| u_n = -k L V^2 sin^2 phi n
// (k = 1/2 rho Cd D). Apparent weight W = -w L z has W.n = w L cos phi and
// W.e = w L sin phi. The lowest element carries no force at its free end, so
// its moment balance about G forces the joint force along e, hence zero normal
// load: w cos phi = k V^2 sin^2 phi = k V^2 (1 - cos^2 phi), a quadratic in c =
// cos phi: k V^2 c^2 + w c - k V^2 = 0, c = (-w + sqrt(w^2 + 4 k^2 V^4)) / (2 k V^2).
// The joint force is then along e, so the element above sees the same
// balance: every element is at phi. The load on each element is w L sin phi e,
// so the tow force is F_R = -sum = w L_tot sin phi (cos phi, 0, sin phi):
// horizontal = total drag, vertical = apparent weight minus drag's lift.
// ---------------------------------------------------------------------------
class SteadyTow : public ::testing::TestWithParam<RunCase> {};

TEST_P(SteadyTow, CriticalAngleAndTowForce) {
  const RunCase c = GetParam();
  CableSpec spec;  // the paper's 5.1 cable, 8 elements of 5 m
  spec.n = 8;
  spec.length = 40;
  spec.tangential = 0.0;
  spec.am = AddedMassModel::Morison;
  Model m = testing::cable_model(spec);
  const double V = 2.0;
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), V, 5.0));
  m.sim.duration = 200;
  m.sim.time_step = 0.02;
  m.sim.output_interval = 10;
  m.sim.integrator = c.integrator;
  // DOPRI5 at rest grows its steps to max_step, beyond the stability limit of
  // the cable's fast modes; it then holds round-off-seeded motion at the
  // tolerance level (see the hanging-body test), hence a tight tolerance.
  m.sim.tolerance = 1e-10;
  m.sim.formulation = c.formulation;
  const auto samples = testing::run(m);
  const Sample& s = samples.back();
  const Sample& s_prev = samples[samples.size() - 2];

  const double rho = m.fluid.rho, A = kPi * spec.diameter * spec.diameter / 4;
  const double w = (spec.mass_per_length - rho * A) * kG;  // apparent weight per length [N/m]
  const double k = 0.5 * rho * spec.cd * spec.diameter;    // [kg/m^2]
  const double cphi = (-w + std::sqrt(w * w + 4 * k * k * std::pow(V, 4))) / (2 * k * V * V);
  const double phi = std::acos(cphi);

  // Settled: every joint moves with the tow point, the tow force no longer changes.
  double dv = 0;
  for (const Vec3& v : s.node_vel) dv = std::max(dv, (v - V * Vec3::UnitX()).norm());
  const double dF = (s.tow_force - s_prev.tow_force).norm();
  double dphi = 0;
  for (int i = 1; i <= spec.n; ++i) {
    const Vec3 d = s.node_pos[i] - s.node_pos[i - 1];
    const double phi_i = std::atan2(-d.z(), -d.x());
    dphi = std::max(dphi, std::abs(phi_i - phi));
    EXPECT_NEAR(d.y(), 0.0, 1e-9) << "element " << i;
  }
  Vec3 sum = Vec3::Zero();
  testing::CableCoefs coefs{spec.mass_per_length, spec.diameter, spec.cd, 0.0};
  for (int i = 1; i <= spec.n; ++i) sum += testing::element_steady_load(m, coefs, s, i);
  const Vec3 F_closed = w * spec.length * std::sin(phi) * Vec3(cphi, 0, std::sin(phi));
  const double errF_sum = (s.tow_force + sum).norm() / s.tow_force.norm();
  const double errF_closed = (s.tow_force - F_closed).norm() / F_closed.norm();
  std::cout << "[measured] steady tow " << testing::run_case_name(c) << ": phi_exact=" << phi * 180 / kPi
            << " deg, max|phi_i-phi|=" << dphi << " rad, max|v-V|=" << dv << " m/s, |dF| over last 10 s=" << dF
            << " N, tow force " << s.tow_force.transpose() << " vs closed form " << F_closed.transpose() << " (rel "
            << errF_closed << "), vs -sum of loads rel " << errF_sum << "\n";
  // Settled to 1e-7 m/s: the transients decay exponentially (drag linearised
  // about V damps every mode at a rate ~ k V / (mass per length), ~0.1-1 /s),
  // so after 200 s only the integrator's and the solver's residuals remain.
  // Measured: RK4 1.6e-13 m/s, angles 8e-14 rad, forces 1e-13; DOPRI5 (at
  // its tolerance-level noise) 2e-9 m/s, 5e-12 rad, 7e-9 against the loads.
  EXPECT_LT(dv, 1e-7);
  EXPECT_LT(dF, 1e-5 * s.tow_force.norm());
  // Angles to 1e-7 rad: the residual of the settling above divided by the
  // cable's restoring stiffness; the steady state itself is exact for RK4
  // (a fixed point of the ODE is a fixed point of the scheme).
  EXPECT_LT(dphi, 1e-7);
  // Tow force = -(sum of loads) to 1e-7 relative: the residual accelerations
  // times the cable mass (~70 kg * 1e-7 m/s^2) over a force of ~300 N, and
  // the closed form to the same precision (phi enters through sin, cos).
  EXPECT_LT(errF_sum, 1e-7);
  EXPECT_LT(errF_closed, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(StillWater, SteadyTow, ::testing::ValuesIn(testing::all_run_cases()), run_case_param_name);

// ---------------------------------------------------------------------------
// 4. A horizontal cable sinking freely (tow force 0, f = 0). By symmetry every
// element translates straight down with no joint force, so per unit length
//   mu dv/dt = -w + k v^2,  mu = m' + ma' (mass and normal added mass per
// length), k = 1/2 rho Cd D, v < 0 the vertical velocity. From rest:
//   v(t) = -V_t tanh(t / tau), z(t) = z0 - V_t tau ln cosh(t / tau),
//   V_t = sqrt(w / k) = sqrt(2 w / (rho Cd D)),  tau = mu V_t / w.
// Check: dv/dt = -(V_t/tau) sech^2 and -w + k V_t^2 tanh^2 = -w sech^2.
// ---------------------------------------------------------------------------
class SinkingCable : public ::testing::TestWithParam<RunCase> {};

TEST_P(SinkingCable, ReachesTerminalVelocity) {
  const RunCase c = GetParam();
  CableSpec spec;
  spec.n = 5;
  spec.length = 20;
  spec.tangential = 0.0;
  Model m = testing::cable_model(spec);
  m.tow.mode = Tow::Mode::Force;
  m.tow.force_value = {Vec3::Zero()};
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3::UnitX();
  m.sim.duration = 3.0;
  m.sim.time_step = 2e-3;
  m.sim.output_interval = 0.02;
  m.sim.integrator = c.integrator;
  m.sim.tolerance = 1e-10;
  m.sim.formulation = c.formulation;
  const auto samples = testing::run(m);

  const double rho = m.fluid.rho, A = kPi * spec.diameter * spec.diameter / 4;
  const double w = (spec.mass_per_length - rho * A) * kG;
  const double k = 0.5 * rho * spec.cd * spec.diameter;
  const double mu = spec.mass_per_length + spec.ca * rho * A;
  const double Vt = std::sqrt(w / k), tau = mu * Vt / w;
  double ev = 0, ez = 0, eh = 0;
  for (const Sample& s : samples) {
    const double v = -Vt * std::tanh(s.t / tau), z = -Vt * tau * std::log(std::cosh(s.t / tau));
    for (int i = 0; i <= spec.n; ++i) {
      ev = std::max(ev, (s.node_vel[i] - Vec3(0, 0, v)).norm() / Vt);
      ez = std::max(ez, std::abs(s.node_pos[i].z() - z));
      eh = std::max(eh, std::abs(s.node_pos[i].x() - i * spec.length / spec.n));
    }
  }
  const Sample& last = samples.back();
  const double vt_meas = -last.node_vel[spec.n / 2].z();
  std::cout << "[measured] sinking cable " << testing::run_case_name(c) << ": V_t=" << Vt << " m/s, measured "
            << vt_meas << " (rel " << std::abs(vt_meas - Vt) / Vt << "), tau=" << tau << " s, max|v-v(t)|/V_t=" << ev
            << ", max|z-z(t)|=" << ez << " m, max horizontal shift=" << eh << " m\n";
  // t_end = 3 s = 24 tau: tanh(24) = 1 - 3e-21, the terminal velocity is reached exactly.
  // Tolerances 1e-8: the motion is a 1-DOF ODE whose RK4 error at h = 2 ms
  // is ~(h/tau)^4/120 ~ 5e-10 relative over one tau; DOPRI5 at 1e-10. The
  // shape must stay exactly straight (round-off only).
  EXPECT_LT(std::abs(vt_meas - Vt) / Vt, 1e-8);
  EXPECT_LT(ev, 1e-8);
  EXPECT_LT(ez, 1e-8 * Vt * m.sim.duration);
  EXPECT_LT(eh, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(StillWater, SinkingCable, ::testing::ValuesIn(testing::all_run_cases()), run_case_param_name);

// ---------------------------------------------------------------------------
// 4b. A vertical cable falling end first (tow force 0), with each tangential
// law. Every element moves straight down at the same speed v and carries the
// same loads, so no joint force: per unit length m' dv/dt = -w + c v^2 (no
// added mass along e), with c = 1/2 rho Cd f D (pode) or 1/2 rho pi D Ct
// (skin): terminal speed V_t = sqrt(w / c), time constant tau = m' V_t / w.
// Default formulation only: the paper's angles are singular for a vertical
// element (MODEL.md 2).
// ---------------------------------------------------------------------------
class FallingCable : public ::testing::TestWithParam<RunCase> {};

TEST_P(FallingCable, ReachesTheTangentialLawsTerminalSpeed) {
  const RunCase c = GetParam();
  for (const TangentialLaw law : {TangentialLaw::Pode, TangentialLaw::Skin}) {
    CableSpec spec;
    spec.n = 4;
    spec.length = 20;
    spec.law = law;
    spec.tangential = law == TangentialLaw::Pode ? 0.02 : 0.01;
    Model m = testing::cable_model(spec);
    m.tow.mode = Tow::Mode::Force;
    m.tow.force_value = {Vec3::Zero()};
    m.sim.duration = 15.0;
    m.sim.time_step = 2e-3;
    m.sim.output_interval = 0.5;
    m.sim.integrator = c.integrator;
    m.sim.tolerance = 1e-10;
    m.sim.formulation = c.formulation;
    const auto samples = testing::run(m);

    const double rho = m.fluid.rho, D = spec.diameter, A = kPi * D * D / 4;
    const double w = (spec.mass_per_length - rho * A) * kG;
    const double cf = law == TangentialLaw::Pode ? 0.5 * rho * spec.cd * spec.tangential * D
                                                 : 0.5 * rho * kPi * D * spec.tangential;
    const double Vt = std::sqrt(w / cf), tau = spec.mass_per_length * Vt / w;
    const Sample& last = samples.back();
    double ev = 0;
    for (int i = 0; i <= spec.n; ++i) ev = std::max(ev, (last.node_vel[i] - Vec3(0, 0, -Vt)).norm() / Vt);
    std::cout << "[measured] falling cable " << testing::run_case_name(c) << " "
              << (law == TangentialLaw::Pode ? "pode" : "skin") << ": V_t=" << Vt << " m/s, tau=" << tau
              << " s, max|v-V_t|/V_t at t_end=" << ev << "\n";
    // t_end = 15 s > 20 tau (tau = 0.74 s pode, 0.79 s skin): tanh(20) = 1 - 8e-18.
    // The smoothed sign x/sqrt(x^2 + v_s^2) (v_s = 1e-3 m/s) lowers the Pode
    // drag by (v_s/V_t)^2/2 = 1.5e-8; tolerance 1e-7 covers that and the
    // integrators' error at h = 2 ms or tolerance 1e-10.
    EXPECT_LT(ev, 1e-7) << (law == TangentialLaw::Pode ? "pode" : "skin");
  }
}

INSTANTIATE_TEST_SUITE_P(StillWater, FallingCable,
                         ::testing::Values(RunCase{Formulation::Default, Integrator::RK4},
                                           RunCase{Formulation::Default, Integrator::DOPRI5},
                                           RunCase{Formulation::Default, Integrator::Rosenbrock}),
                         run_case_param_name);

// ---------------------------------------------------------------------------
// 5. In vacuum with zero tow force the only external force is gravity, so the
// centre of mass moves as r_c(t) = r_c(0) + v_c(0) t - g t^2/2 z, whatever the
// chain does internally.
// ---------------------------------------------------------------------------

/// Centre of mass position and velocity from a physical state (joints
/// rebuilt here: P_k = P_{k-1} + L_k e_k, v_k = v_{k-1} + L_k w_k x e_k).
std::pair<Vec3, Vec3> centre_of_mass(const Model& m, const PhysicalState& s) {
  Vec3 P = s.r0, v = s.v0, c = Vec3::Zero(), vc = Vec3::Zero();
  double M = 0;
  for (int k = 0; k < m.cable.n(); ++k) {
    const Element& el = m.cable.elements[k];
    const Vec3 ed = s.w[k].cross(s.e[k]);
    c += el.mass * (P + 0.5 * el.length * s.e[k]);
    vc += el.mass * (v + 0.5 * el.length * ed);
    P += el.length * s.e[k];
    v += el.length * ed;
    M += el.mass;
  }
  return {c / M, vc / M};
}

/// A bent chain with rates: directions in a zig-zag, random angular velocities.
PhysicalState bent_chain(const Model& m, std::mt19937& rng, double rate) {
  std::normal_distribution<double> N(0.0, 1.0);
  PhysicalState s = PhysicalState::hanging(m);
  s.r0 = Vec3(1, -2, -5);
  s.v0 = Vec3(0.3, 0.1, 0.5);
  for (int k = 0; k < m.cable.n(); ++k) {
    s.e[k] = Vec3(std::cos(1.1 * k), std::sin(0.7 * k), 0.4 * std::cos(2.3 * k)).normalized();
    const Vec3 w = rate * Vec3(N(rng), N(rng), N(rng));
    s.w[k] = w - w.dot(s.e[k]) * s.e[k];
  }
  return s;
}

class FreeFall : public ::testing::TestWithParam<Formulation> {};

TEST_P(FreeFall, CentreOfMassAccelerationIsGravity) {
  // One evaluation at random states: the centre-of-mass acceleration rebuilt
  // here from a0 and the element angular accelerations,
  // a_{P_k} = a_{P_{k-1}} + L (alpha x e + w x (w x e)), must be -g z.
  CableSpec spec;
  spec.n = 7;
  spec.length = 7;
  Model m = testing::cable_model(spec, 0.0, kG);
  m.tow.mode = Tow::Mode::Force;
  m.tow.force_value = {Vec3::Zero()};
  std::mt19937 rng(99);
  Workspace ws(m);
  PaperWorkspace pw(m);
  double worst = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const PhysicalState s = bent_chain(m, rng, 1.5);
    const Accelerations* acc = nullptr;
    if (GetParam() == Formulation::Default) {
      forward_dynamics(m, s, 0.0, ws);
      acc = &ws.acc;
    } else {
      paper_dynamics(m, to_paper(m, s), 0.0, pw);
      acc = &pw.acc;
    }
    Vec3 a = acc->a0, ac = Vec3::Zero();
    double M = 0;
    double scale = kG;
    for (int k = 0; k < m.cable.n(); ++k) {
      const Element& el = m.cable.elements[k];
      const Vec3 de = acc->alpha[k].cross(s.e[k]) + s.w[k].cross(s.w[k].cross(s.e[k]));
      ac += el.mass * (a + 0.5 * el.length * de);
      a += el.length * de;
      M += el.mass;
      scale = std::max(scale, el.length * acc->alpha[k].norm());
    }
    ac /= M;
    worst = std::max(worst, (ac + kG * Vec3::UnitZ()).norm() / scale);
  }
  std::cout << "[measured] free fall " << testing::formulation_name(GetParam())
            << ": max |a_c + g z| / (largest joint acceleration) = " << worst << "\n";
  // Round-off: a_c is a sum of joint accelerations of size up to `scale`
  // (the recursion and the dense solve each lose a few digits).
  EXPECT_LT(worst, 1e-12);
}

TEST_P(FreeFall, CentreOfMassFollowsParabola) {
  CableSpec spec;
  spec.n = 7;
  spec.length = 7;
  Model m = testing::cable_model(spec, 0.0, kG);
  m.tow.mode = Tow::Mode::Force;
  m.tow.force_value = {Vec3::Zero()};
  m.sim.formulation = GetParam();
  std::mt19937 rng(7);
  const PhysicalState s0 = bent_chain(m, rng, 1.0);
  const auto [c0, vc0] = centre_of_mass(m, s0);
  auto sys = make_system(m);
  StateVector y = sys->initial(s0, 0.0);
  sys->project(y, 0.0);
  const double h = 2e-3;
  double err = 0, travel = 0;
  testing::integrate_rk4(*sys, y, 0.0, h, 1000, [&](const StateVector& yy, double t) {
    const auto [c, vc] = centre_of_mass(m, sys->physical(yy));
    const Vec3 c_exact = c0 + vc0 * t - 0.5 * kG * t * t * Vec3::UnitZ();
    const Vec3 v_exact = vc0 - kG * t * Vec3::UnitZ();
    err = std::max({err, (c - c_exact).norm(), (vc - v_exact).norm() * 1.0 /*s*/});
    travel = (c - c0).norm();
  });
  std::cout << "[measured] free-fall parabola " << testing::formulation_name(GetParam())
            << ": max |c - c_exact|, |v_c - v_exact|*1s over 2 s = " << err << " (fell " << travel << " m)\n";
  // The centre of mass is a nonlinear function of the state, so RK4 does not
  // reproduce its parabola exactly: it inherits the truncation error of the
  // internal motion (rates up to ~5 rad/s while the chain unfolds, (w h)^4
  // ~ 1e-8 per unit time at h = 2 ms), reduced because the internal errors
  // largely cancel in the mass-weighted sum (measured 1e-11 m). Bound 1e-9 m
  // on a 17 m fall.
  EXPECT_GT(travel, 15.0);
  EXPECT_LT(err, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Vacuum, FreeFall, ::testing::Values(Formulation::Default, Formulation::Paper),
                         [](const auto& info) { return testing::formulation_name(info.param); });

// ---------------------------------------------------------------------------
// 6. The paper's formulation does not depend on the pole axis of the element
// charts: same physical accelerations to round-off, same trajectories to
// truncation error.
// ---------------------------------------------------------------------------
TEST(PoleAxis, SameAccelerationsNearTheSingularity) {
  CableSpec spec;
  spec.n = 8;
  spec.length = 80;
  spec.tangential = 0.02;
  Model m = testing::cable_model(spec);
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.3, 0), 2.0, 10.0));
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  PaperWorkspace pa(m), pb(m);
  const Vec3 tilted = Vec3(1, 1, 1).normalized();
  double worst = 0;
  for (int trial = 0; trial < 6; ++trial) {
    // Elements near the paper's singular axis z_g: 26..35 deg from the
    // vertical (still inside the z_g chart, |cos theta| < 0.9) pointing down
    // or up, random azimuths and rates.
    PhysicalState s = PhysicalState::hanging(m);
    const double t = 4.0;
    const auto kin = tow_kinematics(m.tow, t);
    s.r0 = kin.pos, s.v0 = kin.vel;
    for (int k = 0; k < m.cable.n(); ++k) {
      const double off = (26 + 9 * U(rng)) * kPi / 180, az = 2 * kPi * U(rng);
      const double up = (k % 3 == 2) ? 1 : -1;
      s.e[k] = Vec3(std::sin(off) * std::cos(az), std::sin(off) * std::sin(az), up * std::cos(off));
      const Vec3 w = 0.3 * Vec3(N(rng), N(rng), N(rng));
      s.w[k] = w - w.dot(s.e[k]) * s.e[k];
    }
    const PaperState qa = to_paper(m, s);          // pole z_g
    const PaperState qb = to_paper(m, s, tilted);  // pole (1,1,1)/sqrt(3)
    int differ = 0;
    for (int k = 0; k < m.cable.n(); ++k) differ += (qa.chart[k] - qb.chart[k]).norm() > 1e-3;
    ASSERT_GE(differ, m.cable.n() / 2) << "the two charts must differ";
    paper_dynamics(m, qa, t, pa);
    paper_dynamics(m, qb, t, pb);
    double amax = 1e-300, fmax = 1e-300;
    for (int k = 0; k < m.cable.n(); ++k) amax = std::max(amax, pa.acc.alpha[k].norm());
    fmax = std::max(pa.acc.tow_force.norm(), 1.0);
    for (int k = 0; k < m.cable.n(); ++k) worst = std::max(worst, (pa.acc.alpha[k] - pb.acc.alpha[k]).norm() / amax);
    worst = std::max(worst, (pa.acc.tow_force - pb.acc.tow_force).norm() / fmax);
  }
  std::cout << "[measured] pole re-choice: max relative difference of accelerations and tow force = " << worst << "\n";
  // Round-off of two dense solves of differently scaled systems (1/sin theta
  // factors of the charts, sin theta >= 0.44 here): 1e-12 relative.
  EXPECT_LT(worst, 1e-12);
}

/// The paper's formulation as an ODE in its own coordinates, started with the
/// element charts of a chosen pole axis (PaperSystem always starts from z_g).
class PaperChartSystem {
 public:
  PaperChartSystem(const Model& m, const PhysicalState& s, const Vec3& pole)
      : m_(m), pw_(m), p_(to_paper(m, s, pole)), na_(paper_angle_count(m)) {}
  StateVector initial() const {
    StateVector y(6 + 2 * na_);
    pack(p_, y);
    return y;
  }
  void operator()(const StateVector& y, StateVector& dy, double t) {
    unpack(y, p_);
    const auto k = tow_kinematics(m_.tow, t);
    p_.r0 = k.pos, p_.v0 = k.vel;
    paper_dynamics(m_, p_, t, pw_);
    dy.resize(y.size());
    for (int i = 0; i < 3; ++i) dy[i] = p_.v0[i], dy[3 + i] = pw_.acc.a0[i];
    for (int i = 0; i < na_; ++i) dy[6 + i] = p_.qd[i], dy[6 + na_ + i] = pw_.qdd[i];
  }
  void project(StateVector& y, double t) {
    unpack(y, p_);
    const auto k = tow_kinematics(m_.tow, t);
    p_.r0 = k.pos, p_.v0 = k.vel;
    rechart(m_, p_);
    pack(p_, y);
  }
  PhysicalState physical(const StateVector& y) {
    unpack(y, p_);
    return from_paper(m_, p_);
  }

 private:
  void pack(const PaperState& p, StateVector& y) const {
    for (int i = 0; i < 3; ++i) y[i] = p.r0[i], y[3 + i] = p.v0[i];
    for (int i = 0; i < na_; ++i) y[6 + i] = p.q[i], y[6 + na_ + i] = p.qd[i];
  }
  void unpack(const StateVector& y, PaperState& p) const {
    for (int i = 0; i < 3; ++i) p.r0[i] = y[i], p.v0[i] = y[3 + i];
    for (int i = 0; i < na_; ++i) p.q[i] = y[6 + i], p.qd[i] = y[6 + na_ + i];
  }
  const Model& m_;
  PaperWorkspace pw_;
  PaperState p_;
  int na_;
};

/// Joint positions after integrating the paper's equations with RK4 from the
/// hanging state, element charts first built on `pole`.
std::vector<Vec3> paper_run(const Model& m, const Vec3& pole, double h, double T) {
  PhysicalState s0 = PhysicalState::hanging(m);
  const auto k0 = tow_kinematics(m.tow, 0.0);
  s0.r0 = k0.pos, s0.v0 = k0.vel;
  PaperChartSystem sys(m, s0, pole);
  StateVector y = sys.initial();
  boost::numeric::odeint::runge_kutta4<StateVector> rk;
  const long steps = std::lround(T / h);
  for (long i = 0; i < steps; ++i) {
    rk.do_step(std::ref(sys), y, i * h, h);
    sys.project(y, (i + 1) * h);
  }
  const PhysicalState s = sys.physical(y);
  std::vector<Vec3> P{s.r0};
  for (int k = 0; k < m.cable.n(); ++k) P.push_back(P.back() + m.cable.elements[k].length * s.e[k]);
  return P;
}

// Both run comparisons use the smooth track (test above): with the ramp, the
// tow law's O(h) error (TowedCableOnRamp) would dominate each run, though it
// is identical in both and cancels in their difference.
TEST(PoleAxis, SameTrajectoryToTruncationError) {
  const Model m = smooth_tow_model();
  const double T = 6.0;
  const Vec3 tilted = Vec3(1, 1, 1).normalized();
  // Hanging start: singular in z_g, so that chart starts on equator charts;
  // the tilted pole keeps its own charts (|cos theta| = 0.58 < 0.9).
  const double d1 = max_distance(paper_run(m, Vec3::UnitZ(), 5e-3, T), paper_run(m, tilted, 5e-3, T));
  const double d2 = max_distance(paper_run(m, Vec3::UnitZ(), 2.5e-3, T), paper_run(m, tilted, 2.5e-3, T));
  std::cout << "[measured] pole re-choice run: max joint distance z_g vs tilted charts h=5ms " << d1 << " m, h=2.5ms "
            << d2 << " m, ratio " << d1 / d2 << "\n";
  // Each run carries its own RK4 error C h^4 (the charts give different
  // coordinates, so different error constants); the difference of two order-4
  // solutions falls ~16x per halving. Accept 13..19 as for the order tests
  // (measured 25, 21, 19, 17 for h = 40 .. 5 ms: it approaches 16 from above);
  // the differences must be truncation, not round-off (>> 1e-12 m).
  EXPECT_GT(d2, 1e-11);
  EXPECT_GT(d1 / d2, 13.0);
  EXPECT_LT(d1 / d2, 19.0);
}

TEST(PoleAxis, PaperAgreesWithDefaultToTruncationError) {
  Model m = smooth_tow_model();
  m.sim.duration = 6.0;
  auto end = [&](Formulation f, double h) {
    m.sim.formulation = f;
    return rk4_end_positions(m, h);
  };
  const double d1 = max_distance(end(Formulation::Paper, 0.01), end(Formulation::Default, 0.01));
  const double d2 = max_distance(end(Formulation::Paper, 0.005), end(Formulation::Default, 0.005));
  std::cout << "[measured] paper vs default run: max joint distance h=10ms " << d1 << " m, h=5ms " << d2 << " m, ratio "
            << d1 / d2 << "\n";
  // Same argument as above: two order-4 discretisations of the same ODE
  // (measured 19, 15, 16 for h = 20 .. 5 ms); differences ~1e-11 m at 5 ms
  // are still 10x above round-off of positions of ~10 m.
  EXPECT_GT(d2, 1e-11);
  EXPECT_GT(d1 / d2, 13.0);
  EXPECT_LT(d1 / d2, 19.0);
}

}  // namespace
}  // namespace towsim
