// Independent physics for the validation tests: energies, loads and
// measurements computed from public outputs (Samples) with formulas written
// out here from docs/theory.md, never by calling the code under test.
#pragma once

#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "towsim/integrators/system.hpp"
#include "towsim/model/model.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::testing {

inline std::string formulation_name(Formulation f) { return f == Formulation::Paper ? "Paper" : "Default"; }
inline std::string integrator_name(Integrator i) {
  switch (i) {
    case Integrator::RK4:
      return "RK4";
    case Integrator::DOPRI5:
      return "DOPRI5";
    case Integrator::CashKarp54:
      return "CashKarp54";
    case Integrator::Rosenbrock:
      return "Rosenbrock";
  }
  return "?";
}

/// Formulation x integrator, the usual test parameter.
struct RunCase {
  Formulation formulation;
  Integrator integrator;
};
inline std::string run_case_name(const RunCase& c) {
  return formulation_name(c.formulation) + "_" + integrator_name(c.integrator);
}

/// Test-name generator for INSTANTIATE_TEST_SUITE_P over RunCase values.
inline std::string run_case_param_name(const ::testing::TestParamInfo<RunCase>& info) {
  return run_case_name(info.param);
}
inline std::vector<RunCase> all_run_cases() {
  return {{Formulation::Default, Integrator::RK4},
          {Formulation::Default, Integrator::DOPRI5},
          {Formulation::Paper, Integrator::RK4},
          {Formulation::Paper, Integrator::DOPRI5},
          {Formulation::Default, Integrator::Rosenbrock}};
}

/// Run `m` to completion and return its samples; the run must end "ok".
inline std::vector<Sample> run(const Model& m, RunStats* stats_out = nullptr) {
  MemorySink sink;
  const RunStats st = simulate(m, sink);
  EXPECT_EQ(st.status, "ok") << st.message;
  if (stats_out) *stats_out = st;
  return sink.samples;
}

/// A ramp piece of tow motion: speed reached linearly over ramp_time.
inline TowLaw ramp_piece(const Vec3& direction, double speed, double ramp_time) {
  return Ramp{direction, speed, ramp_time};
}
/// A heave piece: z += amplitude sin(2 pi (t - start) / period) after start.
inline TowLaw heave_piece(double amplitude, double period, double start_time) {
  return Heave{amplitude, period, start_time};
}

/// A turn piece: leaves the straight path at start_time on a circle of `radius`.
inline TowLaw turn_piece(double radius, double start_time, bool port = true) { return Turn{radius, start_time, port}; }

/// Kinetic and potential energy [J].
struct Energy {
  double kinetic = 0, potential = 0;
  double total() const { return kinetic + potential; }
};

/// Energy of the cable in vacuum from joint positions and velocities only:
/// each element is a homogeneous rod, translational energy of its centre
/// (midpoint of its joints) + rotational energy (m L^2/12) |omega|^2 / 2 with
/// |omega| = |v_k - v_{k-1}| / L (omega is normal to the rod), potential m g z_G.
/// Added mass is not counted: use in vacuum (rho = 0).
inline Energy cable_energy(const Model& m, const Sample& s) {
  Energy E;
  const double g = m.fluid.g;
  for (int k = 1; k <= m.cable.n(); ++k) {
    const Element& el = m.cable.elements[k - 1];
    const Vec3 vG = 0.5 * (s.node_vel[k] + s.node_vel[k - 1]);
    const double zG = 0.5 * (s.node_pos[k].z() + s.node_pos[k - 1].z());
    const double w = (s.node_vel[k] - s.node_vel[k - 1]).norm() / el.length;
    E.kinetic += 0.5 * el.mass * vG.squaredNorm() + 0.5 * el.mass * el.length * el.length / 12 * w * w;
    E.potential += el.mass * g * zG;
  }
  return E;
}

/// Body attitude (body axes -> R_g) from the sample's roll, pitch, yaw [deg]:
/// R = Rz(yaw) Ry(pitch) Rx(roll) (docs/theory.md §4).
inline Mat3 body_rotation(const Sample& s) {
  const double d2r = std::numbers::pi / 180;
  const Vec3 a = s.bodies[0].rpy_deg * d2r;
  return (Eigen::AngleAxisd(a.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(a.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(a.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

/// Energy of the body in vacuum: 1/2 m |v_G|^2 + 1/2 w^T I_G w + m g z_G,
/// plus, if the body carries a user added-mass matrix M_A (about O_t, body
/// axes), the fluid's kinetic energy 1/2 nu^T M_A nu (Kirchhoff; still fluid).
/// R: attitude (body axes -> R_g), O, vO: origin O_t and its velocity, w: angular velocity.
inline Energy body_energy(const Model& m, const Mat3& R, const Vec3& O, const Vec3& vO, const Vec3& w) {
  const Body& b = m.bodies[0];
  const Vec3 rG = R * b.cg;
  const Vec3 vG = vO + w.cross(rG);
  const Mat3 I = R * b.inertia_cg * R.transpose();
  Energy E;
  E.kinetic = 0.5 * b.mass * vG.squaredNorm() + 0.5 * w.dot(I * w);
  Vec6 nu;
  nu << R.transpose() * vO, R.transpose() * w;
  E.kinetic += 0.5 * nu.dot(b.added_mass * nu);
  E.potential = b.mass * m.fluid.g * (O + rG).z();
  return E;
}
inline Energy body_energy(const Model& m, const Sample& s) {
  return body_energy(m, body_rotation(s), s.bodies[0].pos, s.bodies[0].vel, s.bodies[0].omega);
}

/// Joint positions and velocities rebuilt from a physical state:
/// P_k = P_{k-1} + L_k e_k, v_k = v_{k-1} + L_k w_k x e_k.
inline void joints_of_state(const Model& m, const PhysicalState& s, std::vector<Vec3>& P, std::vector<Vec3>& v) {
  P.assign(1, s.r0);
  v.assign(1, s.v0);
  for (int k = 0; k < m.cable.n(); ++k) {
    const double L = m.cable.elements[k].length;
    P.push_back(P.back() + L * s.e[k]);
    v.push_back(v.back() + L * s.w[k].cross(s.e[k]));
  }
}

/// Total energy (cable + body) of a physical state in vacuum.
inline Energy state_energy(const Model& m, const PhysicalState& s) {
  Sample smp;
  joints_of_state(m, s, smp.node_pos, smp.node_vel);
  Energy E = cable_energy(m, smp);
  if (!m.bodies.empty()) {
    const Mat3 R = s.bodies[0].q.toRotationMatrix();
    const Vec3 rQ = R * m.bodies[0].link_point;
    const Energy Eb = body_energy(m, R, smp.node_pos.back() - rQ, smp.node_vel.back() - s.bodies[0].w.cross(rQ),
                                  s.bodies[0].w);
    E.kinetic += Eb.kinetic;
    E.potential += Eb.potential;
  }
  return E;
}

/// Fluid and gravity loads on cable element k (1-based) written out from
/// docs/theory.md §3 with the sample's joint positions and velocities: apparent
/// weight, normal drag -1/2 rho Cd D L |u_n| u_n and Pode tangential friction
/// -1/2 rho Cd f D L |u|^2 sgn_s(u.e) e. Still water; no added mass (use at
/// steady state, where accelerations and de/dt vanish).
struct CableCoefs {
  double mass_per_length, diameter, cd, f;
};
inline Vec3 element_steady_load(const Model& m, const CableCoefs& c, const Sample& s, int k) {
  const double rho = m.fluid.rho, g = m.fluid.g;
  const Vec3 d = s.node_pos[k] - s.node_pos[k - 1];
  const double L = d.norm();
  const Vec3 e = d / L;
  const Vec3 u = 0.5 * (s.node_vel[k] + s.node_vel[k - 1]);
  const Vec3 un = u - u.dot(e) * e;
  const double A = std::numbers::pi * c.diameter * c.diameter / 4;
  Vec3 F(0, 0, -(c.mass_per_length - rho * A) * g * L);
  F -= 0.5 * rho * c.cd * c.diameter * L * un.norm() * un;
  const double ue = u.dot(e), vs = m.cable.sign_smoothing_speed;
  F -= 0.5 * rho * c.cd * c.f * c.diameter * L * u.squaredNorm() * (ue / std::sqrt(ue * ue + vs * vs)) * e;
  return F;
}

/// Times at which a sampled signal x(t) crosses zero, located on the cubic
/// Hermite interpolant of (x, dx/dt) between samples (error O(dt^4)).
inline std::vector<double> zero_crossings(const std::vector<double>& t, const std::vector<double>& x,
                                          const std::vector<double>& xd) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (!((x[i] < 0 && x[i + 1] >= 0) || (x[i] > 0 && x[i + 1] <= 0))) continue;
    const double h = t[i + 1] - t[i];
    auto H = [&](double s) {  // Hermite cubic on [0, 1]
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * x[i] + (s3 - 2 * s2 + s) * h * xd[i] + (-2 * s3 + 3 * s2) * x[i + 1] +
             (s3 - s2) * h * xd[i + 1];
    };
    double a = 0, b = 1, fa = H(a);
    for (int it = 0; it < 100; ++it) {  // bisection to round-off
      const double mid = 0.5 * (a + b), fm = H(mid);
      if ((fm < 0) == (fa < 0))
        a = mid, fa = fm;
      else
        b = mid;
    }
    out.push_back(t[i] + 0.5 * (a + b) * h);
  }
  return out;
}

/// Mean period from successive zero crossings (two per period): 2 (t_last - t_first) / (N - 1).
inline double period_from_crossings(const std::vector<double>& c) {
  if (c.size() < 2) return NAN;
  return 2 * (c.back() - c.front()) / static_cast<double>(c.size() - 1);
}

/// Integrate a System with fixed RK4 steps from (y, t0) for `steps` steps of
/// h, projecting after each step exactly like simulate() does.
inline void integrate_rk4(System& sys, StateVector& y, double t0, double h, long steps,
                          const std::function<void(const StateVector&, double)>& each = {}) {
  boost::numeric::odeint::runge_kutta4<StateVector> rk;
  double t = t0;
  for (long i = 0; i < steps; ++i) {
    rk.do_step(sys.in_window({}), y, t, h);
    t = t0 + (i + 1) * h;
    sys.project(y, t);
    if (each) each(y, t);
  }
}

/// Integrate m's system from the physical state s for `duration` [s] with
/// fixed RK4 steps h (step window and projection as simulate()); returns the
/// state. `each` (optional) sees the state after every step.
inline PhysicalState integrate_state(const Model& m, const PhysicalState& s, double duration, double h,
                                     const std::function<void(const PhysicalState&)>& each = {}) {
  auto sys = make_system(m);
  StateVector y = sys->initial(s, 0.0);
  boost::numeric::odeint::runge_kutta4<StateVector> rk4;
  double t = 0;
  const long steps = std::lround(duration / h);
  for (long i = 0; i < steps; ++i) {
    rk4.do_step(sys->in_window({t, t + h}), y, t, h);
    t += h;
    sys->project(y, t);
    if (each) each(sys->physical(y));
  }
  return sys->physical(y);
}

}  // namespace towsim::testing
