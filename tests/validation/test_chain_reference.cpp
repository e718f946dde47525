// The O(n) recursion on every topology of the chain (sections, an in-line
// body, attachments, an end body, rigid and elastic elements, a winch's
// paid-out top element) against a slow, independent reference: the parts'
// Newton-Euler equations with one Lagrange multiplier per ball joint,
// assembled into one dense KKT system and solved by full-pivot LU
// (tests/support/kkt_reference.hpp). Both use the same load models
// (compute_loads, the axial force laws); they differ in everything else, so
// agreement to round-off proves the recursion's algebra on the new topology.
// Trees of lines: test_tree_reference.cpp.
#include <gtest/gtest.h>

#include <cstdio>

#include "../support/kkt_reference.hpp"
#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/elastic.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

using testing::KktReference;

/// The winch over the top element in a test case.
enum class WinchCase { None, Imposed, Tension };

struct ChainCase {
  int n_top, n_low;
  bool current;
  double EI = 0;             // bending stiffness of every element [N m^2] (joint springs: couples in ws.Mom)
  bool elastic_top = false;  // upper section elastic
  bool elastic_low = false;  // lower section elastic
  WinchCase winch = WinchCase::None;
};

class ChainReference : public ::testing::TestWithParam<ChainCase> {};

// Every acceleration and joint force of the recursion, and every length and
// pay-out acceleration, equals the KKT solution. Tolerance 1e-9 relative to
// the largest force (and to the largest angular and length acceleration):
// the dense LU of a system of up to ~350 unknowns with condition numbers
// ~1e6 loses ~1e-10 (the axial springs are loads, not inertia: they add no
// stiffness to the system); a wrong inertia, load or pay-out term shows at
// 1e-5 or more.
TEST_P(ChainReference, RecursionEqualsDenseMultiplierSolution) {
  const ChainCase c = GetParam();
  Model m = testing::two_part_model(c.n_top, c.n_low);
  if (c.current) {
    m.fluid.current_depth = {0, 40, 300};
    m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.4, 0.1, 0), Vec3(0.1, 0, 0)};
  }
  for (Element& el : m.cable.elements) el.bending_stiffness = c.EI;
  // Axial stiffness EA [N] and damping c_a [N s] of the elastic sections.
  for (int k = 0; k < m.cable.n(); ++k) {
    Element& el = m.cable.elements[static_cast<std::size_t>(k)];
    const bool top = k < c.n_top;
    if (top ? c.elastic_top : c.elastic_low) el.axial_stiffness = top ? 2e6 : 3e5, el.axial_damping = top ? 4e3 : 900;
  }
  if (c.winch == WinchCase::Imposed) {
    // Pay-out speed ramping from 0.2 to 1.2 m/s over 10 s: L'' = 0.1 m/s^2.
    m.winch.mode = Winch::Mode::Imposed;
    m.winch.nominal_length = m.cable.elements[0].length;
    m.winch.schedule = schedule_from_rate({0, 10}, {0.2, 1.2}, 200.0, 0, m.winch.max_length);
  } else if (c.winch == WinchCase::Tension) {
    m.winch.mode = Winch::Mode::Tension;
    m.winch.nominal_length = m.cable.elements[0].length;
    m.winch.tension = 1500;     // [N]
    m.winch.drum_inertia = 80;  // [kg]
    m.winch.damping = 300;      // [N s/m]
  }
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  std::mt19937 rng(77 + c.n_top);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Workspace ws(m);
  double worst_f = 0, worst_a = 0, worst_l = 0;
  for (int trial = 0; trial < 4; ++trial) {
    PhysicalState s = testing::random_state(m, rng);
    // Element lengths [m] and rates [m/s]: strains from -0.3 % (slack) to
    // +0.7 %, one trial with an element on its compression stop; the winch's
    // top element between 0.6 and 1.4 of its nominal length.
    for (std::size_t k = 0; k < s.length.size(); ++k) {
      const Element& el = m.cable.elements[k];
      if (!is_elastic(el)) continue;
      s.length[k] = el.length * (1.002 + 0.005 * U(rng));
      s.length_rate[k] = 0.3 * U(rng);
    }
    if (trial == 3 && is_elastic(m.cable.elements.back())) s.length.back() = 0.05 * m.cable.elements.back().length;
    if (m.winch.active()) {
      const double L1 = m.cable.elements[0].length * (1.0 + 0.4 * U(rng));
      if (is_elastic(m.cable.elements[0])) {
        s.top_unstretched = L1, s.top_unstretched_rate = 0.8 * U(rng);
        s.length[0] = L1 * (1.002 + 0.005 * U(rng));
      } else {
        s.length[0] = L1;
      }
      s.length_rate[0] = 0.8 * U(rng);
    }
    const auto k = tow_kinematics(m.tow, 4.2);
    s.r0 = k.pos, s.v0 = k.vel;
    forward_dynamics(m, s, 4.2, ws);
    const KktReference ref(m, s, ws, k.acc, 4.2);
    const Accelerations& acc = ws.acc;
    double fs = 1, as = 1, ls = 1;
    for (const Vec3& f : acc.joint_force) fs = std::max(fs, f.norm());
    for (const Vec3& a : acc.alpha) as = std::max(as, a.norm());
    for (const double a : acc.length_acc) ls = std::max(ls, std::abs(a));
    double ef = (acc.tow_force - ref.force(ref.joint_of_node[0][0])).norm(), ea = 0, el = 0;
    for (std::size_t j = 1; j < acc.joint_force.size(); ++j)
      ef = std::max(ef, (acc.joint_force[j] - ref.force(ref.joint_of_node[0][j])).norm());
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      ef = std::max(ef, (acc.link_force[b] - ref.force(ref.upper_link[0][b])).norm());
      if (m.bodies[b].inline_body)
        ef = std::max(ef, (acc.lower_link_force[b] - ref.force(ref.lower_link[0][b])).norm());
      ea = std::max(ea, (acc.alpha_b[b] - ref.alpha_body(b)).norm());
    }
    for (std::size_t e = 0; e < acc.alpha.size(); ++e) {
      ea = std::max(ea, (acc.alpha[e] - ref.alpha(e)).norm());
      el = std::max(el, std::abs(acc.length_acc[e] - ref.length_acc(e)));
    }
    // The winch's pay-out acceleration (drum's l_1'' or L_1'').
    if (m.winch.active()) el = std::max(el, std::abs(acc.top_length_acc - ref.pay_acc()));
    worst_f = std::max(worst_f, ef / fs);
    worst_a = std::max(worst_a, ea / as);
    worst_l = std::max(worst_l, el / ls);
  }
  std::printf(
      "[measured] chain %d+body+%d+sphere, 2 attachments%s%s%s%s: force rel err %.2e, alpha rel err %.2e, length acc "
      "rel err %.2e\n",
      c.n_top, c.n_low, c.current ? ", sheared current" : "", c.elastic_top ? ", elastic top section" : "",
      c.elastic_low ? ", elastic lower section" : "",
      c.winch == WinchCase::Imposed   ? ", imposed winch"
      : c.winch == WinchCase::Tension ? ", tension winch"
                                      : "",
      worst_f, worst_a, worst_l);
  EXPECT_LT(worst_f, 1e-9);
  EXPECT_LT(worst_a, 1e-9);
  EXPECT_LT(worst_l, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Topologies, ChainReference,
                         ::testing::Values(ChainCase{3, 4, false}, ChainCase{3, 4, true}, ChainCase{1, 1, false},
                                           ChainCase{12, 20, true}, ChainCase{3, 4, true, 500.0},
                                           ChainCase{3, 4, true, 0.0, true, true},
                                           ChainCase{12, 20, true, 500.0, true, true},
                                           ChainCase{3, 4, true, 0.0, false, true},
                                           ChainCase{3, 4, true, 500.0, true, false},
                                           ChainCase{3, 4, true, 0.0, false, false, WinchCase::Imposed},
                                           ChainCase{3, 4, true, 0.0, false, false, WinchCase::Tension},
                                           ChainCase{3, 4, true, 0.0, true, true, WinchCase::Imposed},
                                           ChainCase{3, 4, true, 500.0, true, false, WinchCase::Tension}),
                         [](const auto& i) {
                           const ChainCase& c = i.param;
                           return "top" + std::to_string(c.n_top) + "_low" + std::to_string(c.n_low) +
                                  (c.current ? "_current" : "_still") + (c.EI > 0 ? "_bending" : "") +
                                  (c.elastic_top ? "_elastictop" : "") + (c.elastic_low ? "_elasticlow" : "") +
                                  (c.winch == WinchCase::Imposed   ? "_winchimposed"
                                   : c.winch == WinchCase::Tension ? "_winchtension"
                                                                   : "");
                         });

}  // namespace
}  // namespace towsim

namespace towsim {
namespace {

// Steady tow of the whole chain (sections, in-line body, attachments, end
// body) in a sheared current: the statics solve converges and the tow force
// equals minus the sum of every part's fluid and gravity loads (the MODEL's
// cross-check of all formulations; nothing accelerates, so no inertia).
// Tolerance 1e-9 of the tow force: the solve stops at angular accelerations
// below 1e-12 rad/s^2; the balance is then exact to round-off.
TEST(ChainStatics, TowForceBalancesEveryLoad) {
  Model m = testing::two_part_model(6, 5);
  // A depressor the solve can settle: a heavy sphere jointed top and bottom
  // (the rich body of the dynamics test has a fin and no stable attitude).
  Body& dep = m.bodies[0];
  const double r = 0.2, mass = 150;
  dep.mass = mass;
  dep.inertia_cg = 0.4 * mass * r * r * Mat3::Identity();
  dep.cg = Vec3::Zero();
  dep.volume = 0, dep.added_mass.setZero(), dep.linear_damping.setZero(), dep.quadratic_damping.setZero();
  dep.link_point = Vec3(0, 0, r);
  dep.lower_link_point = Vec3(0, 0, -r);
  dep.spheres = {{Vec3::Zero(), r, 0.5, 0.5}};
  dep.cylinders.clear();
  dep.surfaces.clear();
  finalize_body(dep, m.fluid);
  m.fluid.current_depth = {0, 40, 300};
  m.fluid.current_velocity = {Vec3(0.3, 0.2, 0), Vec3(0.1, 0.1, 0), Vec3(0, 0, 0)};
  const Vec3 V(2.0, 0.5, 0);
  const StaticsResult res = solve_statics(m, V);
  ASSERT_TRUE(res.converged) << res.message;
  Workspace ws(m);
  PhysicalState s = res.state;
  compute_kinematics(m, s, ws);
  compute_loads(m, s, 0.0, ws);
  Vec3 sum = res.tow_force;
  for (const Vec3& F : ws.F) sum += F;
  for (const Vec3& F : ws.Fa) sum += F;
  for (const BodyWork& bw : ws.body) sum += bw.Fb;
  std::printf("[measured] chain statics: |F_R + sum of loads| / |F_R| = %.2e (%d iterations)\n",
              sum.norm() / res.tow_force.norm(), res.iterations);
  EXPECT_LT(sum.norm(), 1e-9 * res.tow_force.norm());
  // The in-line body is in equilibrium between its two links and its loads.
  const Vec3 body_sum = res.link_force[0] - res.body_force[0] + ws.body[0].Fb;
  EXPECT_LT(body_sum.norm(), 1e-9 * res.tow_force.norm());
}

}  // namespace
}  // namespace towsim
