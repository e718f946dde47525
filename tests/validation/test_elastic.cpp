// Elastic cable elements (docs/theory.md §5.4): the recursion against an
// independent nodal Lagrangian, energy conservation of a mixed chain, the
// static stretch in closed form, the tension wave's impedance and speed, slack
// under a heaving tow point, and convergence to the inextensible cable as
// EA -> infinity.
#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

using testing::cable_model;
using testing::CableSpec;

/// Make every element of m elastic with axial stiffness EA [N] and damping c [N s].
void make_elastic(Model& m, double EA, double c = 0) {
  for (Element& el : m.cable.elements) el.axial_stiffness = EA, el.axial_damping = c;
}

// --- 1. The recursion against a nodal Lagrangian ----------------------------
//
// Independent formulation: the joints P_1..P_n as Cartesian coordinates (the
// tow point P_0 imposed, a_0 = 0). Element k's material interpolates linearly
// between its joints, so its kinetic energy is the consistent-mass form
// 1/6 (v_i^T Mt v_i + v_i^T Mt v_j + v_j^T Mt v_j) (Mt = m I + ma (I - ee^T),
// the acceleration part of the added mass; its velocity part and every other
// load come with F and M). Loads: F at the centre gives F/2 to each joint; the
// moment M about the centre is the couple -+ (M x e)/l at the joints; the
// tension T pulls the joints together. An attachment is a point mass at its
// joint. One dense 3n x 3n solve: M_nodal a = f.
struct Nodal {
  std::vector<Vec3> a;  // joint accelerations a_1..a_n [m/s^2]
  Vec3 tow_force;       // F_R on the cable at P_0 [N]
};

Nodal nodal_reference(const Model& m, const PhysicalState& s) {
  const int n = m.cable.n();
  std::vector<Vec3> P(1, s.r0), v(1, s.v0);
  for (int k = 0; k < n; ++k) {
    const double l = s.length[k], ld = s.length_rate[k];
    P.push_back(P.back() + l * s.e[k]);
    v.push_back(v.back() + ld * s.e[k] + l * s.w[k].cross(s.e[k]));
  }
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(3 * (n + 1), 3 * (n + 1));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * (n + 1));
  for (int k = 1; k <= n; ++k) {
    const Element& el = m.cable.elements[k - 1];
    const Vec3 d = P[k] - P[k - 1];
    const double l = d.norm();
    const Vec3 e = d / l;
    const Vec3 dv = v[k] - v[k - 1];
    const Vec3 edot = (dv - dv.dot(e) * e) / l;  // normal part of d' over l
    const Mat3 Mt = el.mass * Mat3::Identity() + el.added_mass * (Mat3::Identity() - e * e.transpose());
    const int i = 3 * (k - 1), j = 3 * k;
    M.block<3, 3>(i, i) += Mt / 3;
    M.block<3, 3>(j, j) += Mt / 3;
    M.block<3, 3>(i, j) += Mt / 6;
    M.block<3, 3>(j, i) += Mt / 6;
    Vec3 F, Mom;
    element_loads(m, el, e, edot, 0.5 * (v[k] + v[k - 1]), 0.5 * (P[k] + P[k - 1]), 0.0, F, Mom);
    const double strain = l / el.length - 1, rate = dv.dot(e) / el.length;
    const double T = strain > 0 ? std::max(0.0, el.axial_stiffness * strain + el.axial_damping * rate) : 0.0;
    const Vec3 couple = Mom.cross(e) / l;
    f.segment<3>(i) += 0.5 * F - couple + T * e;
    f.segment<3>(j) += 0.5 * F + couple - T * e;
  }
  for (const Attachment& a : m.cable.attachments) {
    const int j = 3 * a.joint;
    M.block<3, 3>(j, j) += (a.mass + a.added_mass) * Mat3::Identity();
    f(j + 2) -= (a.mass - m.fluid.rho * a.volume) * m.fluid.g;
    const auto k = static_cast<std::size_t>(a.joint);
    const Vec3 u = v[k] - m.fluid.velocity(P[k], 0.0);
    f.segment<3>(j) -= 0.5 * m.fluid.rho * a.drag_area * u.norm() * u;
    f.segment<3>(j) += a.added_mass * m.fluid.rate_seen(P[k], v[k], 0.0);  // sheared current seen by the joint
  }
  // Free joints 1..n; P_0 imposed with a_0 = 0.
  const int N = 3 * n;
  const Eigen::VectorXd acc = M.bottomRightCorner(N, N).fullPivLu().solve(f.tail(N));
  Nodal out;
  for (int k = 0; k < n; ++k) out.a.push_back(acc.segment<3>(3 * k));
  // Joint 0's equation: F_R + f_0 = (M a)_0.
  out.tow_force = M.block(0, 3, 3, N) * acc - f.head<3>();
  return out;
}

TEST(ElasticNodalReference, RecursionMatchesTheConsistentMassLagrangian) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (AddedMassModel am : {AddedMassModel::Morison, AddedMassModel::IdealFluid}) {
    for (int n : {1, 2, 3, 7}) {
      CableSpec c;
      c.n = n;
      c.length = 12.0 * n;
      c.tangential = 0.02;
      c.am = am;
      Model m = cable_model(c);
      m.fluid.current_depth = {0, 30};
      m.fluid.current_velocity = {Vec3(0.7, -0.2, 0), Vec3(0.2, 0.1, 0)};
      make_elastic(m, 2e5, 300);
      m.cable.attachments.push_back({n, 0, 15.0, 0.004, 0.05, 3.0});  // an end weight
      if (n >= 3) m.cable.attachments.push_back({1, 0, 4.0, 0.01, 0.02, 1.0});
      PhysicalState s = testing::random_state(m, rng);
      for (int k = 0; k < n; ++k) {
        // Stretched, and one element slack (strain < 0: no tension).
        s.length[k] = m.cable.elements[k].length * (1 + (k == 1 ? -0.02 : 0.01 * (1 + U(rng))));
        s.length_rate[k] = 0.3 * U(rng);
      }
      Workspace ws(m);
      forward_dynamics(m, s, 0.0, ws);
      const Nodal ref = nodal_reference(m, s);
      // Joint accelerations from the recursion: a_k = a_{k-1} + d_k'',
      // d'' = l'' e + 2 l' (w x e) + l (alpha x e) - l |w|^2 e.
      Vec3 a = ws.acc.a0;
      double scale = 0, err = 0;
      for (int k = 0; k < n; ++k) {
        const Vec3 &e = s.e[k], &w = s.w[k];
        const double l = s.length[k], ld = s.length_rate[k];
        a += ws.acc.length_acc[k] * e + 2 * ld * w.cross(e) + l * ws.acc.alpha[k].cross(e) - l * w.squaredNorm() * e;
        err = std::max(err, (a - ref.a[k]).norm());
        scale = std::max(scale, ref.a[k].norm());
      }
      // Two O(n) vs dense LU computations of the same linear system: agree
      // to round-off amplified by the mass matrix's condition (~1e3 here).
      constexpr double kRel = 1e-11;
      EXPECT_LT(err, kRel * scale) << "n = " << n;
      EXPECT_LT((ws.acc.tow_force - ref.tow_force).norm(), kRel * ref.tow_force.norm()) << "n = " << n;
      for (int k = 0; k < n; ++k) EXPECT_NEAR(ws.acc.alpha[k].dot(s.e[k]), 0.0, 1e-12 * scale);
    }
  }
}

// --- 2. Energy of a mixed chain in vacuum -------------------------------------
//
// Elastic section - in-line body - inextensible section with an attachment -
// elastic section - end sphere, in vacuum, tow point fixed, no damping:
// kinetic + gravity + strain energy is conserved by the exact motion. The
// energy is written out here from joints rebuilt from the state.

/// Joint positions and velocities and the bodies' (O, vO) from a state, by
/// the chain's kinematics written out: P_k = P_{k-1} + l e, v_k = v_{k-1} +
/// l' e + l w x e, through a body from Q to Q2.
double chain_energy(const Model& m, const PhysicalState& s) {
  const double g = m.fluid.g;
  double E = 0;
  Vec3 P = s.r0, v = s.v0;
  for (int k = 0; k < m.cable.n(); ++k) {
    const Element& el = m.cable.elements[k];
    const double l = s.length[k], ld = s.length_rate[k];
    const Vec3 dd = ld * s.e[k] + l * s.w[k].cross(s.e[k]);
    // Rod: (m/2)(|v|^2 + v.d' + |d'|^2/3) + m g z_G + EA/(2L) (l - L)_+^2.
    E += 0.5 * el.mass * (v.squaredNorm() + v.dot(dd) + dd.squaredNorm() / 3);
    E += el.mass * g * (P.z() + 0.5 * l * s.e[k].z());
    if (el.axial_stiffness > 0 && l > el.length)
      E += 0.5 * el.axial_stiffness / el.length * (l - el.length) * (l - el.length);
    P += l * s.e[k];
    v += dd;
    for (const Attachment& a : m.cable.attachments)
      if (a.joint == k + 1) E += 0.5 * a.mass * v.squaredNorm() + a.mass * g * P.z();
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const Body& body = m.bodies[b];
      if (body_joint(m, body) != k + 1) continue;
      const Mat3 R = s.bodies[b].q.toRotationMatrix();
      const Vec3 w = s.bodies[b].w, rQ = R * body.link_point;
      const Vec3 O = P - rQ, vO = v - w.cross(rQ);
      const Vec3 rG = R * body.cg;
      E += 0.5 * body.mass * (vO + w.cross(rG)).squaredNorm() + 0.5 * w.dot(R * body.inertia_cg * R.transpose() * w) +
           body.mass * g * (O + rG).z();
      if (body.inline_body) {
        const Vec3 r2 = R * body.lower_link_point;
        P = O + r2;
        v = vO + w.cross(r2);
      }
    }
  }
  return E;
}

/// A body of mass mb with a diagonal inertia, CG and link points (vacuum: no fluid terms).
Body simple_body(double mb, const Vec3& link, const Vec3& lower, const Vec3& cg) {
  Body b;
  b.mass = mb;
  b.inertia_cg = Vec3(0.8, 2.0, 2.3).asDiagonal();
  b.cg = cg;
  b.link_point = link;
  b.lower_link_point = lower;
  return b;
}

/// Fixed-step RK4 from s (tests/support/physics.hpp).
PhysicalState integrate(const Model& m, const PhysicalState& s, double duration, double h,
                        const std::function<void(const PhysicalState&)>& each = {}) {
  return testing::integrate_state(m, s, duration, h, each);
}

TEST(ElasticEnergy, MixedChainInVacuumConservesEnergyAtFourthOrder) {
  CableSpec c;
  c.n = 3;
  c.length = 15;
  c.mass_per_length = 2.0;
  Model m = cable_model(c, 0.0);
  make_elastic(m, 4e4);
  // Link, CG and lower link on one vertical: the body hangs in equilibrium
  // (off it, it swings hard enough to jerk the light section below slack).
  m.bodies.push_back(simple_body(30, Vec3(0, 0, 0.2), Vec3(0, 0, -0.1), Vec3(0, 0, -0.05)));
  m.bodies.back().inline_body = true;
  m.bodies.back().joint = 3;
  m.bodies.back().name = "depressor";
  finalize_body(m.bodies.back(), m.fluid);
  for (int i = 0; i < 2; ++i)
    m.cable.elements.push_back(make_element(4.0, 1.0, 0.01, 1.2, 0.0, m.cable.tangential_law, 1.0, m.fluid));
  for (int i = 0; i < 3; ++i) {
    Element el = make_element(3.0, 0.8, 0.01, 1.2, 0.0, m.cable.tangential_law, 1.0, m.fluid);
    el.axial_stiffness = 2e4;
    m.cable.elements.push_back(el);
  }
  m.cable.attachments.push_back({4, 0, 5.0, 0, 0, 0});
  testing::add_sphere_body(m, 40.0, 0.1);  // heavy enough to keep the section below taut
  // Near hanging, swinging: elements tilted by ~5 deg with rates of
  // 0.1 rad/s, bodies tilted and turning, elastic elements at their static
  // stretch and stretching.
  std::mt19937 rng(3);
  std::normal_distribution<double> N(0.0, 1.0);
  auto rnd = [&] { return Vec3(N(rng), N(rng), N(rng)); };
  PhysicalState s = initial_state(m);  // hanging, elastic elements at their static stretch
  for (int k = 0; k < m.cable.n(); ++k) {
    s.e[k] = (-Vec3::UnitZ() + 0.05 * rnd()).normalized();
    const Vec3 w = 0.1 * rnd();
    s.w[k] = w - w.dot(s.e[k]) * s.e[k];
    if (is_elastic(m.cable.elements[k])) s.length_rate[k] = 0.005 * N(rng);
  }
  for (auto& b : s.bodies) b.q = Quat(Eigen::AngleAxisd(0.1, rnd().normalized())), b.w = 0.1 * rnd();
  const double E0 = chain_energy(m, s);
  // The elastic elements stay taut (checked below), so the energy is smooth
  // and RK4 keeps its order.
  double min_strain = 1;
  int slack_at = -1;
  auto taut = [&](const PhysicalState& p) {
    for (int k = 0; k < m.cable.n(); ++k)
      if (is_elastic(m.cable.elements[k])) {
        const double e = p.length[k] / m.cable.elements[k].length - 1;
        if (e < min_strain) min_strain = e, slack_at = k;
      }
  };
  const double dE1 = chain_energy(m, integrate(m, s, 1.0, 2e-3, taut)) - E0;
  EXPECT_GT(min_strain, 0.0) << "element " << slack_at + 1;
  const double dE2 = chain_energy(m, integrate(m, s, 1.0, 1e-3)) - E0;
  std::printf("energy drift: %.3e (h = 2 ms), %.3e (h = 1 ms), ratio %.1f; E0 = %.3f J\n", dE1, dE2, dE1 / dE2, E0);
  // RK4's energy error over a fixed time: O(h^4) in general, O(h^5) for a
  // near-linear oscillation (|R(i w h)|^2 = 1 - (w h)^6 / 72 per step): the
  // ratio when h halves is 16..32 (measured 32.0); 12..40 keeps a margin.
  // Wrong forces (a missing term, a wrong inertia) leave an O(1) drift.
  EXPECT_GT(std::abs(dE1 / dE2), 12.0);
  EXPECT_LT(std::abs(dE1 / dE2), 40.0);
  EXPECT_LT(std::abs(dE2), 1e-9 * std::abs(E0));
}

// --- 3. Static stretch ---------------------------------------------------------

TEST(ElasticStatics, HangingCableWithBodyStretchesByTheIntegralOfTOverEA) {
  CableSpec c;
  c.n = 20;
  c.length = 500;
  c.mass_per_length = 1.12;
  c.diameter = 0.0173;
  Model m = cable_model(c);
  const double EA = 1.27e7;
  make_elastic(m, EA);
  testing::add_sphere_body(m, 300.0, 0.3);
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  // Closed form: T(s) = W_b + w (L - s), elongation = int_0^L T/EA ds
  // = (W_b L + w L^2/2) / EA, w the apparent weight per metre.
  const double A = std::numbers::pi * c.diameter * c.diameter / 4, rho = m.fluid.rho, g = m.fluid.g;
  const double w = (c.mass_per_length - rho * A) * g;
  const Body& b = m.bodies[0];
  const double Wb = (b.mass - rho * b.displaced_volume) * g;
  const double expected = (Wb * c.length + 0.5 * w * c.length * c.length) / EA;
  double stretch = 0;
  for (int k = 0; k < c.n; ++k) stretch += r.state.length[k] - m.cable.elements[k].length;
  std::printf("static stretch %.9f m, closed form %.9f m\n", stretch, expected);
  // T is linear along the cable, so the element-centre tensions integrate it
  // exactly (midpoint rule): agreement to the fixed point's length tolerance.
  EXPECT_NEAR(stretch, expected, 1e-9 * expected);
  // The body hangs lower by exactly that much.
  EXPECT_NEAR(-r.sample.node_pos.back().z() - c.length, expected, 1e-9 * c.length);
  // `initial: hanging` starts from the same stretch (its own closed form).
  const PhysicalState s0 = initial_state(m);
  for (int k = 0; k < c.n; ++k) EXPECT_NEAR(s0.length[k], r.state.length[k], 1e-12 * c.length) << k;
}

TEST(ElasticStatics, TowedEquilibriumIsAnEquilibriumOfTheElasticDynamics) {
  CableSpec c;
  c.n = 15;
  c.length = 300;
  c.mass_per_length = 1.12;
  c.diameter = 0.0173;
  c.tangential = 0.02;
  Model m = cable_model(c);
  m.fluid.current_depth = {0, 200};
  m.fluid.current_velocity = {Vec3(0.3, 0.2, 0), Vec3(-0.1, 0, 0)};
  make_elastic(m, 2e5);  // soft: 1e-2 strains, so the geometry feels them
  testing::add_sphere_body(m, 200.0, 0.3);
  const Vec3 V(2.0, 0, 0);
  const StaticsResult r = solve_statics(m, V);
  ASSERT_TRUE(r.converged) << r.message;
  double max_strain = 0;
  for (int k = 0; k < c.n; ++k) max_strain = std::max(max_strain, r.state.length[k] / m.cable.elements[k].length - 1);
  EXPECT_GT(max_strain, 1e-3);
  // At the equilibrium, the elastic dynamics' own accelerations vanish:
  // angular (rad/s^2) and axial (m/s^2), relative to g.
  PhysicalState s = r.state;
  s.v0 = V;
  Workspace ws(m);
  m.tow.pieces.clear();
  forward_dynamics(m, s, 0.0, ws);
  for (int k = 0; k < c.n; ++k) {
    EXPECT_LT(ws.acc.alpha[k].norm(), 1e-8) << k;
    EXPECT_LT(std::abs(ws.acc.length_acc[k]), 1e-8 * m.fluid.g) << k;
  }
}

// --- 4. The tension wave: impedance and speed ----------------------------------
//
// A cable of L = 1000 m hangs at rest in vacuum at its static stretch (closed
// form); at t = 0 the tow point starts up at c_p = 1 m/s (a winch starting to
// haul in, or the reverse of a pay-out stopped dead: the same jump of the
// axial speed at the top). A tension step dT = c_p sqrt(EA m') runs down at
// c = sqrt(EA/m') (the 1-D wave equation; no added mass: the motion is
// axial). Upwards, so that the step adds tension and nothing goes slack.
TEST(ElasticWave, TowPointStartingUpSendsTheImpedanceStepAtTheWaveSpeed) {
  CableSpec c;
  c.n = 200;
  c.length = 1000;
  c.mass_per_length = 1.12;
  Model m = cable_model(c, 0.0);
  const double EA = 1.27e7, cp = 1.0, mp = c.mass_per_length, L0 = c.length / c.n, g = m.fluid.g;
  make_elastic(m, EA);
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitZ(), cp, 0.0));
  // Static stretch: element k carries T_k = m' g L0 (n - k + 1/2) at its centre.
  PhysicalState s = PhysicalState::hanging(m);
  std::vector<double> T0(c.n);
  for (int k = 0; k < c.n; ++k) {
    T0[k] = mp * g * L0 * (c.n - k - 0.5);
    s.length[k] = L0 * (1 + T0[k] / EA);
  }
  const double wave = std::sqrt(EA / mp), Z = std::sqrt(EA * mp), dT = cp * Z;
  const double h = 0.5 * rk4_axial_step_limit(m.cable.elements[0]);
  auto sys = make_system(m);
  StateVector y = sys->initial(s, 0.0);
  ASSERT_GT(sys->apply_tow_jump(y, 0.0), 0.0);
  boost::numeric::odeint::runge_kutta4<StateVector> rk4;
  const int probe = static_cast<int>(0.8 * c.n);  // element at 80 % of the length
  const double x_probe = (probe + 0.5) * L0;      // its centre [m]
  double t = 0, t_cross = -1, plateau = 0;
  int plateau_n = 0;
  const double t_end = 1.5 * c.length / wave;  // before the reflection returns to the top
  while (t < t_end) {
    rk4.do_step(sys->in_window({t, t + h}), y, t, h);
    t += h;
    sys->project(y, t);
    const PhysicalState p = sys->physical(y);
    auto dTk = [&](int k) { return element_tension(m.cable.elements[k], p.length[k], p.length_rate[k]) - T0[k]; };
    if (t_cross < 0 && dTk(probe) > 0.5 * dT) t_cross = t;
    if (t > 0.2 * c.length / wave && t < 1.4 * c.length / wave) plateau += dTk(0), ++plateau_n;
  }
  plateau /= plateau_n;
  std::printf("top step %.1f N (impedance %.1f N); probe crossing %.5f s (x/c = %.5f s)\n", plateau, dT, t_cross,
              x_probe / wave);
  // The bound: 5 %. Mean over the plateau (the discrete chain's
  // dispersion rings behind the front) and the front's half-height crossing.
  EXPECT_NEAR(plateau, dT, 0.05 * dT);
  EXPECT_NEAR(t_cross, x_probe / wave, 0.05 * x_probe / wave);
}

// The fixed RK4 step's bound for the axial mode (docs/theory.md §5.4): the
// consistent-mass chain's highest frequency is 2 sqrt(3) c / L (less by
// 0.2 % for 20 elements, fixed top, free end), RK4 is stable up to
// |h w| = 2 sqrt(2): h* = 0.8165 L / c. A hanging chain at its static
// stretch under a 500 kg end weight (strain >= 4e-4 everywhere), its highest
// mode seeded by alternating length perturbations of 1e-12: 5 % below h* the
// perturbation stays bounded, 5 % above it grows by |R(i h w)| ~ 1.38 per
// step (1e7 over 50 steps; still far from slack, which would clip it).
TEST(ElasticWave, Rk4AxialStepBoundIsSharp) {
  CableSpec c;
  c.n = 20;
  c.length = 200;
  c.mass_per_length = 1.12;
  Model m = cable_model(c, 0.0);
  make_elastic(m, 1.27e7);
  m.cable.attachments.push_back({c.n, c.length, 500.0, 0.0, 0.0, 0.0});
  constexpr double kSeed = 1e-12;
  PhysicalState s = initial_state(m);
  const std::vector<double> rest = s.length;
  for (int k = 0; k < c.n; ++k) s.length[k] += (k % 2 ? kSeed : -kSeed) * m.cable.elements[k].length;
  const double L = m.cable.elements[0].length, hstar = std::sqrt(2.0 / 3.0) * L / axial_wave_speed(m.cable.elements[0]);
  auto growth = [&](double h) {
    const PhysicalState p = integrate(m, s, 50 * h, h);
    double a = 0;
    for (int k = 0; k < c.n; ++k) a = std::max(a, std::abs(p.length[k] - rest[k]) / L / kSeed);
    return std::isfinite(a) ? a : 1e300;
  };
  const double below = growth(0.95 * hstar), above = growth(1.05 * hstar);
  std::printf("perturbation after 50 steps: x%.3g at 0.95 h*, x%.3g at 1.05 h*\n", below, above);
  EXPECT_LT(below, 2.0);  // no growth (the mode's energy is conserved or damped)
  EXPECT_GT(above, 1e4);  // unmistakable growth
  EXPECT_NEAR(rk4_axial_step_limit(m.cable.elements[0]), 0.98 * hstar, 0.01 * hstar);  // the refusal's margin
}

// --- 5. Slack under a heaving tow point ----------------------------------------

TEST(ElasticSlack, LightCableUnderHeaveGoesSlackWithZeroTension) {
  CableSpec c;
  c.n = 10;
  c.length = 50;
  c.mass_per_length = 0.3;
  c.diameter = 0.012;
  Model m = cable_model(c);
  make_elastic(m, 5e4, 50);
  m.cable.attachments.push_back({c.n, c.length, 2.0, 0.0, 0.0, 0.0});  // a 2 kg end weight (a free end whips)
  // 5.3 m/s^2 peak downwards against the 6.0 m/s^2 at which the vertical
  // cable sinks along itself (apparent weight over mass: no added mass, no
  // axial drag with f = 0): the tension drops to zero at the downstroke and
  // snaps back at the upstroke. (A harder heave piles a vertical slack
  // cable up onto the compression stop: HardHeaveFoldsNoElement below.)
  m.tow.pieces.push_back(testing::heave_piece(1.2, 3.0, 0.0));
  m.sim.duration = 12;
  m.sim.integrator = Integrator::DOPRI5;
  m.sim.tolerance = 1e-7;
  m.sim.time_step = 1e-3;
  m.sim.output_interval = 0.02;
  RunStats st;
  const std::vector<Sample> samples = testing::run(m, &st);
  EXPECT_GT(st.slack.episodes, 0);
  ASSERT_FALSE(st.slack.events().empty());
  const SlackEvent& ev = st.slack.events().front();
  std::printf("%ld slack episodes, %.2f s slack; first %.3f-%.3f s, elements %d-%d, snap %.1f N; peak %.1f N\n",
              st.slack.episodes, st.slack.slack_time, ev.start, ev.end, ev.first_element, ev.last_element,
              ev.snap_tension, st.slack.max_tension);
  EXPECT_GT(ev.end, ev.start);
  // No negative tension in any output: joint tensions are magnitudes, the
  // element tension (EA strain, from the strain column) is zero when slack.
  int slack_nodes = 0;
  for (const Sample& s : samples) {
    for (double T : s.tension) EXPECT_GE(T, 0.0);
    for (double e : s.strain) slack_nodes += e < -SlackRecord::kSlackStrain;
  }
  EXPECT_GT(slack_nodes, 0);
  // The snap after the first episode exceeds the static top tension.
  const double static_top = (c.mass_per_length - m.fluid.rho * std::numbers::pi / 4 * c.diameter * c.diameter) *
                            m.fluid.g * c.length;
  EXPECT_GT(st.slack.max_tension, static_top);
}

TEST(ElasticSlack, EpisodeSpanFollowsTheWinchTopLength) {
  // A winch over an elastic cable sets the top element's unstretched length
  // L_1 (here 14 m against the model's 10 m): the slack episode of element 2
  // lies from L_1 to L_1 + 10 m along the cable, not from the model's 10 m.
  CableSpec c;
  c.n = 3;
  c.length = 30;
  Model m = cable_model(c);
  make_elastic(m, 1e5);
  const double L1 = 14.0;
  // Lengths at the model's unstretched lengths (10 m each): element 2 at
  // strain -1e-3 (slack), the others taut.
  const std::vector<double> length{10.001, 9.99, 10.001}, rate(3, 0.0);
  SlackRecord r;
  r.update(m, length, rate, 1.0, L1);
  ASSERT_EQ(r.events().size(), 1U);
  const SlackEvent& ev = r.events().front();
  EXPECT_EQ(ev.first_element, 2);
  EXPECT_EQ(ev.last_element, 2);
  EXPECT_DOUBLE_EQ(ev.from, L1);  // exact: sums of the lengths given
  EXPECT_DOUBLE_EQ(ev.to, L1 + 10.0);
  // Without a winch length: the model's.
  SlackRecord plain;
  plain.update(m, length, rate, 1.0);
  EXPECT_DOUBLE_EQ(plain.events().front().from, 10.0);
}

TEST(ElasticSlack, HardHeaveFoldsNoElement) {
  // The harder heave of the note above (3 m, 3 s: 13 m/s^2 peak downwards,
  // twice the 6 m/s^2 at which the vertical cable sinks along itself): the
  // slack cable piles up; the compression stop (docs/theory.md §5.4) keeps
  // every element above its stop length, the run completes, and no output
  // shows a negative tension.
  CableSpec c;
  c.n = 10;
  c.length = 50;
  c.mass_per_length = 0.3;
  c.diameter = 0.012;
  Model m = cable_model(c);
  make_elastic(m, 5e4, 50);
  m.cable.attachments.push_back({c.n, c.length, 2.0, 0.0, 0.0, 0.0});
  m.tow.pieces.push_back(testing::heave_piece(3.0, 3.0, 0.0));
  m.sim.duration = 12;
  m.sim.integrator = Integrator::DOPRI5;
  m.sim.tolerance = 1e-7;
  m.sim.time_step = 1e-3;
  m.sim.output_interval = 0.02;
  RunStats st;
  const std::vector<Sample> samples = testing::run(m, &st);
  ASSERT_EQ(st.status, "ok") << st.message;
  double shortest = 1, Tmin = 1e300;
  for (const Sample& s : samples) {
    for (double T : s.tension) Tmin = std::min(Tmin, T);
    for (double e : s.strain) shortest = std::min(shortest, 1 + e);
  }
  std::printf(
      "hard heave: %ld slack episodes, shortest element %.3f of its length, min joint tension %.3g N, peak "
      "%.1f N\n",
      st.slack.episodes, shortest, Tmin, st.slack.max_tension);
  EXPECT_GE(Tmin, 0.0);
  EXPECT_GT(shortest, 0.05);  // the run's own failure threshold (kMinLength); measured 0.077
}

// --- 6. EA -> infinity: the inextensible cable --------------------------------

TEST(ElasticLimit, StiffElasticCableConvergesToTheInextensibleOne) {
  CableSpec c;
  c.n = 5;
  c.length = 100;
  Model rigid = cable_model(c);
  testing::add_sphere_body(rigid);
  rigid.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 2.0, 3.0));
  rigid.sim.duration = 6;
  rigid.sim.time_step = 2e-4;
  rigid.sim.output_interval = 0.05;
  const std::vector<Sample> ref = testing::run(rigid);
  std::vector<double> err;
  for (double EA : {1e6, 1e7, 1e8}) {
    Model m = rigid;
    make_elastic(m, EA);
    ASSERT_LT(m.sim.time_step, rk4_axial_step_limit(m.cable.elements[0]));
    const std::vector<Sample> el = testing::run(m);
    ASSERT_EQ(el.size(), ref.size());
    double e = 0;  // largest distance over the run (the unstretched start rings axially)
    for (std::size_t i = 0; i < el.size(); ++i) e = std::max(e, (el[i].bodies[0].pos - ref[i].bodies[0].pos).norm());
    err.push_back(e);
    std::printf("EA %.0e: body position differs by up to %.3e m\n", EA, err.back());
  }
  // Strain ~ T/EA: the difference falls tenfold per decade of EA (first
  // order); 5..20 allows the ringing's phase at the sample times.
  for (std::size_t i = 1; i < err.size(); ++i) {
    EXPECT_GT(err[i - 1] / err[i], 5.0);
    EXPECT_LT(err[i - 1] / err[i], 20.0);
  }
  // At EA = 1e8 the difference is the cable's stretch itself, T L / EA ~ 1e-3 m.
  EXPECT_LT(err.back(), 1e-3);
}

}  // namespace
}  // namespace towsim
