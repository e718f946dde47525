// Steady consistency of statics and dynamics (docs/validation.md §5): a run started from
// the statics equilibrium (initial: steady) stays there, and a run started
// hanging settles to it; the paper's 5.1 and 5.2 models with a straight tow.
// docs/validation.md section 5.
#include <gtest/gtest.h>

#include <iomanip>
#include <iostream>

#include "../support/pode.hpp"
#include "../support/steady.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

struct SteadyCase {
  std::string example;
  double V;  // straight tow speed [m/s] (the example's final speed)
  Formulation formulation;
  Integrator integrator;
};
void PrintTo(const SteadyCase& c, std::ostream* os) { *os << c.example << " V=" << c.V; }

std::string case_name(const SteadyCase& c) {
  return std::string(c.example == "paper-planar-a" ? "paper51" : "paper52") + "_" +
         (c.formulation == Formulation::Paper ? "paper" : "default") + "_" +
         (c.integrator == Integrator::RK4 ? "rk4" : "dopri5");
}

std::vector<SteadyCase> steady_cases() {
  std::vector<SteadyCase> out;
  for (auto [ex, V] : {std::pair<const char*, double>{"paper-planar-a", 2.0}, {"paper-3d-turn", 1.57}})
    for (Formulation f : {Formulation::Default, Formulation::Paper})
      for (Integrator i : {Integrator::RK4, Integrator::DOPRI5}) out.push_back({ex, V, f, i});
  return out;
}

/// Largest change of the joints relative to the tow point (over the cable
/// length) and of the tow force (over its initial magnitude) along a run.
struct Drift {
  double position = 0, force = 0;
};
Drift drift(const std::vector<Sample>& ss, double length) {
  Drift d;
  const Sample& s0 = ss.front();
  for (const Sample& s : ss) {
    for (std::size_t k = 0; k < s.node_pos.size(); ++k)
      d.position = std::max(d.position, ((s.node_pos[k] - s.tow_pos) - (s0.node_pos[k] - s0.tow_pos)).norm() / length);
    d.force = std::max(d.force, (s.tow_force - s0.tow_force).norm() / s0.tow_force.norm());
  }
  return d;
}

class StaticsSteadyRun : public ::testing::TestWithParam<SteadyCase> {};

// ---------------------------------------------------------------------------
// initial: steady, tow at speed from t = 0 (ramp_time 0): nothing moves
// relative to the tow point for 60 s.
// ---------------------------------------------------------------------------
TEST_P(StaticsSteadyRun, StartedSteadyStaysStill) {
  const SteadyCase c = GetParam();
  Model m = validation::example_model(c.example);
  validation::straight_tow(m, c.V);
  m.initial.kind = Initial::Kind::Steady;
  m.sim.duration = 60;
  m.sim.output_interval = 1;
  m.sim.formulation = c.formulation;
  m.sim.integrator = c.integrator;
  m.sim.time_step = 0.01;
  m.sim.tolerance = 1e-9;
  MemorySink sink;
  const RunStats rs = simulate(m, sink);
  ASSERT_EQ(rs.status, "ok") << rs.message;
  const Drift d = drift(sink.samples, m.cable.total_length());
  const Sample& s0 = sink.samples.front();
  const StaticsResult st = solve_statics(m, Vec3(c.V, 0, 0));
  const double dF0 = (s0.tow_force - st.tow_force).norm() / st.tow_force.norm();
  std::cout << "[measured] steady start " << case_name(c) << ": over 60 s max|dP|/L=" << d.position
            << ", max|dF_R|/|F_R|=" << d.force << "; F_R(0)=" << s0.tow_force.transpose() << " N vs statics (rel "
            << dF0 << "), " << rs.steps << " steps\n";
  // 1e-6 relative (docs/validation.md §5): the statics equilibrium leaves |alpha| < 1e-10
  // rad/s^2, a drift of 1/2 alpha t^2 ~ 2e-7 rad over 60 s at worst, and a
  // fixed point of the equations is one of RK4 and DOPRI5 too. Measured far
  // below (see the output line).
  EXPECT_LT(d.position, 1e-6);
  EXPECT_LT(d.force, 1e-6);
  EXPECT_LT(dF0, 1e-9);  // the run's first tow force is the statics one
}

INSTANTIATE_TEST_SUITE_P(StaticsPaper, StaticsSteadyRun, ::testing::ValuesIn(steady_cases()),
                         [](const auto& info) { return case_name(info.param); });

// ---------------------------------------------------------------------------
// Started hanging at rest with the tow at speed from t = 0: after the
// transient the run settles to the statics configuration. Adaptive DOPRI5 at
// a tight tolerance (the settled state is a fixed point; the tolerance only
// bounds how well the run reaches it).
// ---------------------------------------------------------------------------
struct SettleCase {
  std::string example;
  double V;
  double settle_time;  // [s]
};
void PrintTo(const SettleCase& c, std::ostream* os) { *os << c.example << " V=" << c.V; }
class StaticsSettling : public ::testing::TestWithParam<SettleCase> {};

TEST_P(StaticsSettling, RunFromHangingSettlesToStatics) {
  const SettleCase c = GetParam();
  Model m = validation::example_model(c.example);
  validation::straight_tow(m, c.V);
  m.initial.kind = Initial::Kind::Hanging;
  m.sim.duration = c.settle_time;
  m.sim.output_interval = c.settle_time / 60;
  m.sim.integrator = Integrator::DOPRI5;
  m.sim.tolerance = 1e-9;
  m.sim.max_step = 0.5;
  MemorySink sink;
  const RunStats rs = simulate(m, sink);
  ASSERT_EQ(rs.status, "ok") << rs.message;
  const StaticsResult st = solve_statics(m, Vec3(c.V, 0, 0));
  ASSERT_TRUE(st.converged) << st.message;
  const auto P = validation::joints(m, st.state);
  const double Ltot = m.cable.total_length();
  auto out = validation::data_file("validation_settling_" + std::string(c.example) + ".dat");
  if (out) *out << "# t [s]  max|P_k - P_k(statics)|/L  |F_R - F_R(statics)|/|F_R(statics)| (relative to tow point)\n";
  double dP = 0, dF = 0;
  for (const Sample& s : sink.samples) {
    dP = 0;
    for (std::size_t k = 0; k < P.size(); ++k)
      dP = std::max(dP, ((s.node_pos[k] - s.tow_pos) - (P[k] - P[0])).norm() / Ltot);
    dF = (s.tow_force - st.tow_force).norm() / st.tow_force.norm();
    if (out) *out << s.t << " " << dP << " " << dF << "\n";
  }
  double dPb = 0;
  if (!m.bodies.empty()) {
    const Mat3 R = st.state.bodies[0].q.toRotationMatrix();
    const Vec3 O = P.back() - R * m.bodies[0].link_point;
    const Sample& s = sink.samples.back();
    dPb = ((s.bodies[0].pos - s.tow_pos) - (O - P[0])).norm() / Ltot;
  }
  std::cout << "[measured] settling " << c.example << " at " << c.V << " m/s: after " << c.settle_time
            << " s max|dP|/L=" << dP << ", body |dO|/L=" << dPb << ", |dF_R|/|F_R|=" << dF << " (" << rs.steps
            << " steps, " << rs.rhs_evaluations << " evaluations)\n";
  // 1e-7 relative: the transient decays exponentially (measured time
  // constants ~19 s for 5.1 and ~32 s for 5.2, after a first swing-up of
  // ~100-250 s; docs/validation.md), so the settling times leave ~1e-9; the
  // steady state is a fixed point of DOPRI5, so its tolerance does not add
  // a floor.
  EXPECT_LT(dP, 1e-7);
  EXPECT_LT(dPb, 1e-7);
  EXPECT_LT(dF, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(StaticsPaper, StaticsSettling,
                         ::testing::Values(SettleCase{"paper-planar-a", 2.0, 400},
                                           SettleCase{"paper-3d-turn", 1.57, 800}),
                         [](const auto& info) {
                           return info.param.example == "paper-planar-a" ? "paper51" : "paper52";
                         });

}  // namespace
}  // namespace towsim
