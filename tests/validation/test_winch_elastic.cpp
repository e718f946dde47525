// A winch paying out an elastic cable (docs/theory.md "Winch", §5.4): the
// winch sets the unstretched length L_1 of the top element, whose stretched
// length l_1 is its own state. Checks: the split and the removal keep the
// material (unstretched length, exactly), the strain and the velocities;
// the snap of a winch stopped dead (the impedance step c_p sqrt(EA m') at
// the wave speed sqrt(EA/m')) with RK4 and Rosenbrock-W; and a held winch's
// hanging cable and body at the closed-form stretch int T/EA ds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "../support/models.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/winch_events.hpp"

namespace towsim {
namespace {

/// A vertical cable of n elements of Le under a fixed tow point, every
/// element elastic (EA [N], damping c_a [N s]), in a fluid of density rho,
/// with an imposed-length winch (schedule set by the caller).
Model elastic_winch_model(int n, double Le, double mpl, double EA, double ca, double rho, double cd = 0) {
  testing::CableSpec c;
  c.n = n;
  c.length = n * Le;
  c.mass_per_length = mpl;
  c.diameter = 0.0173;
  c.cd = cd;
  Model m = testing::cable_model(c, rho);
  for (Element& el : m.cable.elements) el.axial_stiffness = EA, el.axial_damping = ca;
  m.cable.sections.push_back({"cable", 0, n, n * Le, 0});
  m.winch.mode = Winch::Mode::Imposed;
  m.winch.nominal_length = Le;
  m.winch.min_length = Le;
  return m;
}

/// Unstretched length of the chain of state s: the winch's L_1 and the
/// model's lengths below it [m].
double unstretched(const Model& m, const PhysicalState& s) {
  double L = s.top_unstretched;
  for (std::size_t k = 1; k < m.cable.elements.size(); ++k) L += m.cable.elements[k].length;
  return L;
}

// --- 1. Events keep the material -----------------------------------------------
//
// Split: the new joint is the material point at fraction (L_1 - L_e)/L_1 of
// the top element; both parts keep the old strain and strain rate, every
// joint below keeps its position and velocity, and the material velocity
// field is unchanged (the new joint moves as that material point did).
// Removal: the next element takes in the top one's material (L_1 + L_2).
TEST(ElasticWinch, SplitAndRemovalKeepMaterialStrainAndVelocities) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  Model m = elastic_winch_model(4, 10, 1.12, 1e6, 500, 1025, 1.2);
  m.winch.mode = Winch::Mode::Tension;  // L_1, L_1' free state
  m.winch.tension = 2000;
  m.winch.drum_inertia = 50;
  PhysicalState s = testing::random_state(m, rng);
  s.top_unstretched = 16.0;  // past split_at L_e = 15 m
  s.top_unstretched_rate = 0.8;
  for (std::size_t k = 0; k < s.length.size(); ++k) {
    const double L = k == 0 ? s.top_unstretched : m.cable.elements[k].length;
    s.length[k] = L * (1 + 0.002 * (1.5 + U(rng)));
    s.length_rate[k] = 0.05 * U(rng);
  }
  ASSERT_EQ(winch_event(m, s), WinchEvent::Split);
  const Model m2 = split_model(m);
  const PhysicalState s2 = split_state(m, s);
  // Round-off: sums of a few lengths of 10 m.
  constexpr double kTol = 1e-13;
  EXPECT_NEAR(unstretched(m2, s2), unstretched(m, s), kTol * 50);
  EXPECT_NEAR(s2.top_unstretched, 6.0, kTol * 50);
  Workspace w1(m), w2(m2);
  forward_dynamics(m, s, 0.0, w1);
  forward_dynamics(m2, s2, 0.0, w2);
  // Strain and tension of both parts: the old element's.
  const double strain = s.length[0] / s.top_unstretched - 1;
  EXPECT_NEAR(s2.length[0] / s2.top_unstretched - 1, strain, kTol);
  EXPECT_NEAR(s2.length[1] / m2.cable.elements[1].length - 1, strain, kTol);
  EXPECT_NEAR(w2.elastic[0].T, w1.elastic[0].T, kTol * w1.elastic[0].T);
  EXPECT_NEAR(w2.elastic[1].T, w1.elastic[0].T, kTol * w1.elastic[0].T);
  // Joints below: same positions and velocities.
  for (std::size_t k = 1; k < w1.P.size(); ++k) {
    EXPECT_LT((w2.P[k + 1] - w1.P[k]).norm(), kTol * 50) << k;
    EXPECT_LT((w2.vP[k + 1] - w1.vP[k]).norm(), kTol * 10) << k;
  }
  // The new joint moves as the material point at f = 6/16 did: linear field
  // from the sheave's material v_T = v_0 + (l_1/L_1) L_1' e_1 to P_1's.
  const double f = 6.0 / 16.0;
  const Vec3 v_mat = (1 - f) * w1.v_top + f * w1.vP[1];
  EXPECT_LT((w2.vP[1] - v_mat).norm(), kTol * 10);
  EXPECT_LT((w2.v_top - w1.v_top).norm(), kTol * 10);

  // Removal: shrink the top element below remove_at L_e and remove it.
  PhysicalState r = s2;
  r.top_unstretched = 0.5;
  r.length[0] = 0.5 * (1 + strain);
  ASSERT_EQ(winch_event(m2, r), WinchEvent::Remove);
  Workspace w3(m2);
  forward_dynamics(m2, r, 0.0, w3);
  const Removal rem = remove_top(m2, r, 0.0, r.top_unstretched_rate);
  EXPECT_NEAR(unstretched(rem.model, rem.state), unstretched(m2, r), kTol * 50);
  EXPECT_EQ(rem.state.top_unstretched, 0.5 + m2.cable.elements[1].length);
  EXPECT_EQ(rem.impulse.norm(), 0.0);
  Workspace w4(rem.model);
  forward_dynamics(rem.model, rem.state, 0.0, w4);
  for (std::size_t k = 1; k < w4.P.size(); ++k) {
    EXPECT_LT((w4.P[k] - w3.P[k + 1]).norm(), kTol * 50) << k;
    EXPECT_LT((w4.vP[k] - w3.vP[k + 1]).norm(), kTol * 10) << k;
  }
}

// --- 2. Snap: the winch stopped dead ----------------------------------------------
//
// A cable of 200 m (20 elements of 10 m, EA 1.27e7 N, m' = 1.12 kg/m in
// vacuum: no drag, no added mass; along the axis there is none in water
// either) hangs from a fixed sheave at its static stretch. The winch ramps
// up to c_p = 1 m/s (over four fundamental periods: no ringing left), pays
// out at c_p (one split) and stops dead at t_s = 7 s. The material
// at the top stops: a tension step dT = c_p sqrt(EA m') (m' the mass per
// unstretched length) runs down at c = sqrt(EA/m') per unit unstretched
// length (the 1-D wave equation). Measured: the plateau of the top tension
// before the reflection returns (2 L/c) and the half-height crossing at a
// node at 80 % of the length.
void snap(Integrator integ) {
  const double Le = 10, mpl = 1.12, EA = 1.27e7, cp = 1.0, ts = 7.0;
  // The ramp: four periods 4 L/c of the fixed-free cable's fundamental (its
  // overtones: odd fractions of it), so that the waves its start excites are
  // cancelled by those its end excites (a ramp of any other length leaves
  // the cable ringing at ~ (c_p/t_r) L/c, 6 % of c_p for 1 s).
  const double tr = 16 * 200.25 / std::sqrt(EA / mpl);
  Model m = elastic_winch_model(20, Le, mpl, EA, 0, 0.0);
  const double L0 = 200, Ls = L0 + 0.5 * cp * tr + cp * (ts - tr);  // deployed at the stop [m]
  m.winch.schedule = {{0, L0, 0, cp / tr}, {tr, L0 + 0.5 * cp * tr, cp, 0}, {ts, Ls, 0, 0}};
  const double c = std::sqrt(EA / mpl), Z = std::sqrt(EA * mpl), dT = cp * Z;
  m.sim.integrator = integ;
  m.sim.duration = ts + 1.5 * Ls / c;
  // RK4: below its axial bound 0.8 L/c for the shortest top element (5 m after the split).
  m.sim.time_step = 5e-4;
  m.sim.tolerance = 1e-7;
  m.sim.output_interval = 5e-4;
  MemorySink sink;
  const RunStats st = simulate(m, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_EQ(st.winch_splits, 1);
  // Unstretched length in the water, sum of |P_k - P_{k-1}| / (1 + strain_k),
  // against L_0 + the integral of the pay-out speed (the schedule), across
  // the split: round-off (1e-12 relative: 21 lengths from summed positions).
  double worst = 0;
  for (const Sample& s : sink.samples) {
    double L = 0;
    for (std::size_t k = 1; k < s.node_pos.size(); ++k)
      L += (s.node_pos[k] - s.node_pos[k - 1]).norm() / (1 + s.strain[k]);
    worst = std::max(worst, std::abs(L - winch_kinematics(m.winch, s.t).length) / L);
  }
  std::printf("unstretched length against the paid-out length: within %.2e\n", worst);
  EXPECT_LT(worst, 1e-12);
  // The last sample before the stop: the tensions the step adds to.
  std::size_t i0 = 0;
  while (i0 + 1 < sink.samples.size() && sink.samples[i0 + 1].t < ts - 1e-9) ++i0;
  const Sample& pre = sink.samples[i0];
  // The probe: the node nearest 80 % of the deployed length.
  std::size_t probe = 0;
  for (std::size_t k = 0; k < pre.node_pos.size(); ++k)
    if (std::abs(-pre.node_pos[k].z() - 0.8 * Ls) < std::abs(-pre.node_pos[probe].z() - 0.8 * Ls)) probe = k;
  const double x_probe = -pre.node_pos[probe].z();  // stretched; strain < 2e-4 [m]
  double plateau = 0, t_cross = -1;
  int plateau_n = 0;
  for (std::size_t i = i0 + 1; i < sink.samples.size(); ++i) {
    const Sample& s = sink.samples[i];
    const double tau = s.t - ts;
    if (tau > 0.2 * Ls / c && tau < 1.4 * Ls / c) plateau += s.tension[0] - pre.tension[0], ++plateau_n;
    if (t_cross < 0 && s.tension[probe] - pre.tension[probe] > 0.5 * dT) t_cross = tau;
  }
  ASSERT_GT(plateau_n, 50);
  plateau /= plateau_n;
  std::printf("%s: top step %.1f N (impedance %.1f N); probe at %.1f m crossing %.5f s (x/c = %.5f s)\n",
              integ == Integrator::RK4 ? "rk4" : "rosenbrock", plateau, dT, x_probe, t_cross, x_probe / c);
  // The bound: 5 %. Mean over the plateau (the discrete chain's
  // dispersion rings behind the front) and the front's half-height crossing.
  EXPECT_NEAR(plateau, dT, 0.05 * dT);
  EXPECT_NEAR(t_cross, x_probe / c, 0.05 * x_probe / c);
}

TEST(ElasticWinch, SnapWhenTheWinchStopsRk4) { snap(Integrator::RK4); }
TEST(ElasticWinch, SnapWhenTheWinchStopsRosenbrock) { snap(Integrator::Rosenbrock); }

// --- 3. Held winch: the static stretch ------------------------------------------
//
// 100 m of cable (EA 1e6 N, in water) with a 300 kg sphere, paid out to
// 120 m (one split... two: 20 m of 10 m elements), then held; axial damping
// settles the stretch. Closed form: T(s) = W_b + w (L - s),
// stretch = int_0^L T/EA ds = (W_b L + w L^2/2) / EA (w, W_b apparent
// weights), L the paid-out unstretched length = the schedule's.
TEST(ElasticWinch, HeldWinchHangsAtTheClosedFormStretch) {
  const double Le = 10, mpl = 1.12, EA = 1e6, ca = 2e5, rho = 1025;
  Model m = elastic_winch_model(10, Le, mpl, EA, ca, rho, 1.2);
  testing::add_sphere_body(m, 300.0, 0.3);
  // Up to 1 m/s in 1 s, 19 s at it, down in 1 s: 120 m; held to 60 s.
  m.winch.schedule = {{0, 100, 0, 1}, {1, 100.5, 1, 0}, {20, 119.5, 1, -1}, {21, 120, 0, 0}};
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-8;
  m.sim.duration = 60;
  m.sim.output_interval = 1;
  MemorySink sink;
  const RunStats st = simulate(m, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_EQ(st.winch_splits, 2);
  const double L = 120, A = std::numbers::pi * 0.0173 * 0.0173 / 4, g = m.fluid.g;
  const double w = (mpl - rho * A) * g;
  const Body& b = m.bodies[0];
  const double Wb = (b.mass - rho * b.displaced_volume) * g;
  const double expected = (Wb * L + 0.5 * w * L * L) / EA;
  const Sample& end = sink.samples.back();
  const double stretch = end.deployed_length - L;
  std::printf("held winch: stretch %.9f m, closed form %.9f m\n", stretch, expected);
  // T is linear along the cable: the element-centre tensions integrate it
  // exactly (midpoint rule), so what is left is the settling (damped by
  // e^-80 over the 39 s held) and the integrator's tolerance (1e-8 relative
  // on lengths of 100 m: 1e-6 m, 4e-6 of the stretch; 1e-10 m seen).
  EXPECT_NEAR(stretch, expected, 1e-5 * expected);
  EXPECT_NEAR(end.tow_force.z(), Wb + w * L, 1e-6 * (Wb + w * L));
}

// --- 4. Tension control: the drum holds the top element's tension -------------
//
// A 500 kg load on 30 m of elastic cable (EA 1e7 N, m' 2 kg/m) in vacuum,
// the drum (M_d = 300 kg) holding T_set = 4000 N: cable and load fall with
// the drum as one axial mass, (M_d + m' L + M) L'' = (m' L + M) g - T_set
// for the unstretched length L (integrated here apart, RK4 1e-3 s), and the
// tension at the sheave is T_set + M_d L''. Axial damping settles the
// ringing the start excites (t > 3 s compared).
TEST(ElasticWinch, TensionControlHoldsTheTopElementsTension) {
  const double g = 9.81, Le = 10, mpl = 2.0, M = 500, Md = 300, Tset = 4000;
  Model m = elastic_winch_model(3, Le, mpl, 1e7, 3e5, 0.0);
  m.cable.attachments.push_back({3, 3 * Le, M, 0, 0, 0});
  m.winch.mode = Winch::Mode::Tension;
  m.winch.tension = Tset;
  m.winch.drum_inertia = Md;
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-6;
  m.sim.duration = 6;
  m.sim.output_interval = 0.5;
  MemorySink sink;
  const RunStats st = simulate(m, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_GT(st.winch_splits, 0);
  auto f = [&](double L) { return ((mpl * L + M) * g - Tset) / (Md + mpl * L + M); };
  double L = 3 * Le, v = 0, t = 0, worst_v = 0, worst_T = 0;
  const double h = 1e-3;
  for (const Sample& s : sink.samples) {
    while (t < s.t - 1e-9) {
      const double k1L = v, k1v = f(L);
      const double k2L = v + h / 2 * k1v, k2v = f(L + h / 2 * k1L);
      const double k3L = v + h / 2 * k2v, k3v = f(L + h / 2 * k2L);
      const double k4L = v + h * k3v, k4v = f(L + h * k3L);
      L += h / 6 * (k1L + 2 * k2L + 2 * k3L + k4L);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t += h;
    }
    if (s.t < 3) continue;
    worst_v = std::max(worst_v, std::abs(s.payout_speed - v) / v);
    worst_T = std::max(worst_T, std::abs(s.tow_force.norm() - (Tset + Md * f(L))) / Tset);
  }
  std::printf("tension control: pay-out speed within %.2e, sheave tension within %.2e of the rigid-body law\n", worst_v,
              worst_T);
  // What is left: the stretch's slow change (strain ~ 5e-4 varying with
  // the tension as L grows) and the damped ringing; 1e-3 bounds both.
  EXPECT_LT(worst_v, 1e-3);
  EXPECT_LT(worst_T, 1e-3);
}

// --- 5. Pay-out and haul-in of an elastic cable: fish-depth-change --------------
//
// The built-in example (600 -> 900 -> 600 m at 1 m/s, 10 splits and 10
// removals) with EA 1.27e7 N (c_a 2000 N s) against the inextensible run.
// Away from the ramps' corners (+-5 s: there the rigid cable's tension
// jumps with the acceleration, the elastic one's follows over the axial
// wave's travel time), the tow tension agrees within 0.5 % (measured
// 0.22 %) and the stretch stays within its bound L T_max / EA = 0.28 m:
// the deployed (stretched) length exceeds the schedule's by 0..0.28 m and
// the fish rides at most that much deeper.
TEST(ElasticWinch, FishDepthChangeAgreesWithTheInextensibleRun) {
  const scenario::Example* ex = scenario::find_example("fish-depth-change");
  ASSERT_NE(ex, nullptr);
  scenario::LoadedScenario sc = scenario::load_scenario_text(ex->yaml, "fish-depth-change.yaml", "fish-depth-change",
                                                             ".");
  ASSERT_TRUE(sc.ok()) << sc.diags.str();
  const Model rigid = *sc.model;
  Model elastic = rigid;
  for (Element& el : elastic.cable.elements) el.axial_stiffness = 1.27e7, el.axial_damping = 2000;
  MemorySink a, b;
  const RunStats sa = simulate(rigid, a), sb = simulate(elastic, b);
  ASSERT_EQ(sb.status, "ok") << sb.message;
  EXPECT_EQ(sb.winch_splits, 10);
  EXPECT_EQ(sb.winch_removals, 10);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  const double bound = 900 * 4000 / 1.27e7;  // L T_max / EA [m]
  double worst_T = 0;
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    const Sample &x = a.samples[i], &y = b.samples[i];
    bool corner = false;
    for (double c : {60, 70, 360, 370, 700, 710, 1000, 1010}) corner = corner || std::abs(x.t - c) <= 5;
    if (corner) continue;
    worst_T = std::max(worst_T, std::abs(y.tow_force.norm() - x.tow_force.norm()) / x.tow_force.norm());
    EXPECT_GE(y.deployed_length - x.deployed_length, 0.0) << "t = " << x.t;
    EXPECT_LE(y.deployed_length - x.deployed_length, bound) << "t = " << x.t;
    EXPECT_LE(std::abs(y.bodies.back().pos.z() - x.bodies.back().pos.z()), bound) << "t = " << x.t;
  }
  std::printf("fish-depth-change elastic: tow tension within %.2e of the inextensible run (%ld steps against %ld)\n",
              worst_T, sb.steps, sa.steps);
  EXPECT_LT(worst_T, 5e-3);
}

}  // namespace
}  // namespace towsim
