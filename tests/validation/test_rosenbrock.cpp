// The linearly implicit integrator (Rosenbrock-W ROS34PW2, docs/theory.md
// §6.3) against independent references: its measured order, energy in
// vacuum, agreement with converged RK4 on the paper examples, stability and
// accuracy far beyond the RK4 stability limit; and the RK4 stability
// estimate (§6.4) against the measured limit.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "../support/rosenbrock.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"

namespace towsim {
namespace {

using testing::fixed_rosenbrock;

using testing::CableSpec;

constexpr double kG = 9.81;

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, (a[k] - b[k]).norm());
  return d;
}

/// A towed cable in water with a sphere, tow point on a smooth track (a
/// natural cubic spline: continuous acceleration, knots on whole seconds).
Model smooth_tow_model() {
  CableSpec spec;
  spec.n = 10;
  spec.length = 30;
  Model m = testing::cable_model(spec);
  testing::add_sphere_body(m, 20.0, 0.15);
  Track p;
  for (int i = -2; i <= 10; ++i) {
    const double t = i;
    p.time.push_back(t);
    p.pos.push_back(Vec3(1.5 * t + 0.3 * std::sin(t), 0.5 * std::sin(0.7 * t), 0.3 * std::sin(1.3 * t)));
  }
  m.tow.pieces.push_back(p);
  m.sim.duration = 6.0;
  m.sim.output_interval = 6.0;
  return m;
}

// ---------------------------------------------------------------------------
// 1. Order 3: the error at the end falls eightfold when the step halves.
// ---------------------------------------------------------------------------
class RosenbrockOrder : public ::testing::TestWithParam<double> {};

TEST_P(RosenbrockOrder, ErrorFallsEightfoldWhenStepHalves) {
  const double h = GetParam();
  const Model m = smooth_tow_model();
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 1e-3;  // RK4 error ~1e-11 m here: far below the errors measured
  const Sample r = testing::run(ref).back();
  const Sample a = testing::run(fixed_rosenbrock(m, h)).back();
  const Sample b = testing::run(fixed_rosenbrock(m, h / 2)).back();
  const double ea = max_distance(a.node_pos, r.node_pos), eb = max_distance(b.node_pos, r.node_pos);
  const double fa = (a.tow_force - r.tow_force).norm(), fb = (b.tow_force - r.tow_force).norm();
  std::cout << "[measured] Rosenbrock order, h = " << h << ": position err " << ea << " -> " << eb << " ratio "
            << ea / eb << "; tow force err " << fa << " -> " << fb << " N ratio " << fa / fb << "\n";
  EXPECT_GT(eb, 1e-9);  // truncation, far above round-off and the reference's error
  // Order 3: ratio -> 8. Accepted 6..10.5 (order 2.6..3.4): the O(h^4) term
  // still moves the ratio by tens of per cent at these steps. Measured 8.49
  // and 8.63 (positions), 8.38 and 8.55 (tow force) at h = 40 and 20 ms.
  EXPECT_GT(ea / eb, 6.0);
  EXPECT_LT(ea / eb, 10.5);
  EXPECT_GT(fa / fb, 6.0);
  EXPECT_LT(fa / fb, 10.5);
}

INSTANTIATE_TEST_SUITE_P(TowedCable, RosenbrockOrder, ::testing::Values(0.04, 0.02), [](const auto& info) {
  return "h" + std::to_string(static_cast<int>(info.param * 1000)) + "ms";
});

// ---------------------------------------------------------------------------
// 1b. Dense output: outputs between step ends come from the method's
// continuous extension (no step lands on them). At fixed steps h with
// outputs every 10 ms, the outputs at multiples of h are step ends (the
// step-landing values), the others dense. The continuous extension's
// local error is O(h^3) for a W-method (O(h^4) with the exact Jacobian),
// the same order as the global error at the step ends: the dense outputs
// must be as accurate as the step ends and converge at order 3 (ratio -> 8
// when h halves). Measured at h = 80, 40, 20 ms: tow force error at dense
// outputs / at step ends 0.81, 0.87, 0.89; positions 1.001, 1.001, 0.999.
// Bound 1.25: dense outputs no worse than the step-landing values (whose
// error is the method's global error) beyond a quarter.
// ---------------------------------------------------------------------------
struct DenseErrors {
  double end = 0, dense = 0;          // max tow force error [N]: at step ends, at dense outputs
  double end_pos = 0, dense_pos = 0;  // max node position error [m]
};

DenseErrors dense_errors(const Model& m, const std::vector<Sample>& ref, double h) {
  RunStats st;
  const auto b = testing::run(fixed_rosenbrock(m, h), &st);
  EXPECT_EQ(b.size(), ref.size());
  DenseErrors e;
  for (std::size_t i = 0; i < std::min(b.size(), ref.size()); ++i) {
    const double k = b[i].t / h;
    const bool at_end = std::abs(k - std::round(k)) < 1e-6;
    const double ef = (b[i].tow_force - ref[i].tow_force).norm(), ep = max_distance(b[i].node_pos, ref[i].node_pos);
    (at_end ? e.end : e.dense) = std::max(at_end ? e.end : e.dense, ef);
    (at_end ? e.end_pos : e.dense_pos) = std::max(at_end ? e.end_pos : e.dense_pos, ep);
  }
  std::cout << "[measured] dense output, h = " << h << " s (" << st.steps << " steps): tow force err at step ends "
            << e.end << " N, at dense outputs " << e.dense << " N; positions " << e.end_pos << " m, " << e.dense_pos
            << " m\n";
  return e;
}

TEST(RosenbrockDenseOutput, AsAccurateAsTheStepEndsAndOrderThree) {
  Model m = smooth_tow_model();
  m.sim.output_interval = 0.01;
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 1e-3;  // RK4 error ~1e-11 m: far below the errors measured
  const auto r = testing::run(ref);
  const DenseErrors a = dense_errors(m, r, 0.08), b = dense_errors(m, r, 0.04), c = dense_errors(m, r, 0.02);
  for (const DenseErrors* e : {&a, &b, &c}) {
    EXPECT_LT(e->dense, 1.25 * e->end);
    EXPECT_LT(e->dense_pos, 1.25 * e->end_pos);
  }
  std::cout << "[measured] dense output tow force error ratios " << a.dense / b.dense << ", " << b.dense / c.dense
            << "\n";
  // Order 3: ratio 8; accepted 6..10.5 as in RosenbrockOrder (O(h^4) terms).
  EXPECT_GT(a.dense / b.dense, 6.0);
  EXPECT_LT(a.dense / b.dense, 10.5);
  EXPECT_GT(b.dense / c.dense, 6.0);
  EXPECT_LT(b.dense / c.dense, 10.5);
}

// ---------------------------------------------------------------------------
// 2. Energy in vacuum: a pinned chain released from horizontal. The method
// is not symplectic: the drift is its global error, O(h^3).
// ---------------------------------------------------------------------------
Model vacuum_chain() {
  CableSpec spec;
  spec.n = 6;
  spec.length = 3.0;
  spec.mass_per_length = 1.0;
  Model m = testing::cable_model(spec, /*rho=*/0.0, kG);
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3::UnitX();
  m.sim.duration = 0.6;  // before the whip (rates ~50 rad/s after it)
  m.sim.output_interval = 0.01;
  return m;
}

double energy_drift(const Model& m) {
  const auto samples = testing::run(m);
  const double scale = 1.0 * 3.0 * kG * 3.0 / 2;  // M g L / 2: potential energy of the fall
  const double E0 = testing::cable_energy(m, samples.front()).total();
  double drift = 0;
  for (const Sample& s : samples) drift = std::max(drift, std::abs(testing::cable_energy(m, s).total() - E0) / scale);
  return drift;
}

TEST(RosenbrockEnergy, DriftFallsToTheMethodsOrder) {
  const double da = energy_drift(fixed_rosenbrock(vacuum_chain(), 4e-3));
  const double db = energy_drift(fixed_rosenbrock(vacuum_chain(), 2e-3));
  const double dd = energy_drift(fixed_rosenbrock(vacuum_chain(), 1e-3));
  std::cout << "[measured] Rosenbrock energy drift/(MgL/2): h = 4 ms " << da << ", 2 ms " << db << ", 1 ms " << dd
            << ", ratios " << da / db << ", " << db / dd << "\n";
  // Order 3 in the energy: ratio -> 8 as h -> 0. Accepted 5.5..11 (the
  // O(h^4) term still matters at 4 ms). Measured 6.0 then 7.7.
  EXPECT_GT(da / db, 5.5);
  EXPECT_LT(da / db, 11.0);
  EXPECT_GT(db / dd, 5.5);
  EXPECT_LT(db / dd, 11.0);
  // And small in absolute terms: measured 1.5e-7 at 2 ms; bound 1e-6.
  EXPECT_LT(db, 1e-6);
  // With error control at tolerance 1e-8 the drift is of that order
  // (local errors relative to 1 + |y| accumulate over ~100 steps): bound 1e-6.
  // Measured 5.9e-10.
  Model m = vacuum_chain();
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-8;
  const double dc = energy_drift(m);
  std::cout << "[measured] Rosenbrock energy drift at tolerance 1e-8: " << dc << "\n";
  EXPECT_LT(dc, 1e-6);
}

// ---------------------------------------------------------------------------
// 2b. Imposed tow force (the tow point is a free coordinate of the stage
// solves): a chain in vacuum pulled sideways by a constant force. Its centre
// of mass follows c0 + (F/M - g z) t^2 / 2 exactly, whatever the swing.
// ---------------------------------------------------------------------------
TEST(RosenbrockForceMode, CentreOfMassFollowsTheParabola) {
  CableSpec spec;
  spec.n = 7;
  spec.length = 7;
  spec.mass_per_length = 1.0;
  Model m = testing::cable_model(spec, /*rho=*/0.0, kG);
  m.tow.mode = Tow::Mode::Force;
  const Vec3 F(20, 0, 5);  // [N]: the 7 kg chain swings up and sideways
  m.tow.force_value = {F};
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-8;
  m.sim.duration = 2.0;
  m.sim.output_interval = 0.05;
  RunStats st;
  const auto samples = testing::run(m, &st);
  const double M = 7.0;
  auto centre = [&](const Sample& s) {
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < m.cable.n(); ++k) c += 0.5 * (s.node_pos[k] + s.node_pos[k + 1]) / m.cable.n();
    return c;
  };
  const Vec3 c0 = centre(samples.front()), a = F / M - kG * Vec3::UnitZ();
  double err = 0;
  bool swung = false;  // the chain left the vertical (cos < 0.9)
  for (const Sample& s : samples) {
    err = std::max(err, (centre(s) - (c0 + 0.5 * a * s.t * s.t)).norm());
    swung = swung || (s.node_pos.back() - s.node_pos.front()).normalized().dot(-Vec3::UnitZ()) < 0.9;
  }
  std::cout << "[measured] rosenbrock, imposed tow force: max |c - c_exact| over 2 s = " << err << " m (" << st.steps
            << " steps)\n";
  EXPECT_TRUE(swung);
  // Local errors of 1e-8 relative to 1 + |y| over ~100 steps, on a fall of
  // ~20 m: bound 1e-5 m. Measured 1.0e-7 m (6761 steps).
  EXPECT_LT(err, 1e-5);
}

TEST(RosenbrockForceMode, PaperFormulationIsRefused) {
  CableSpec spec;
  Model m = testing::cable_model(spec);
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.formulation = Formulation::Paper;
  m.sim.duration = 1;
  MemorySink sink;
  const RunStats st = simulate(m, sink);
  EXPECT_EQ(st.status, "failed");
  EXPECT_EQ(st.message, "rosenbrock needs formulation: default (its stage solves use the O(n) recursion)");
}

// ---------------------------------------------------------------------------
// 3. The paper examples: the same results as converged RK4.
// ---------------------------------------------------------------------------
class RosenbrockExamples : public ::testing::TestWithParam<std::string> {};

TEST_P(RosenbrockExamples, AgreeWithConvergedRk4) {
  const scenario::Example* ex = scenario::find_example(GetParam());
  ASSERT_NE(ex, nullptr);
  scenario::LoadedScenario sc = scenario::load_scenario_text(ex->yaml, GetParam() + ".yaml", GetParam(), ".");
  ASSERT_TRUE(sc.ok());
  Model m = *sc.model;
  m.sim.duration = 40;  // the ramp, and the start of the heave (planar-b) or of the turn (3d-turn)
  m.sim.output_interval = 1.0;
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 2.5e-3;  // RK4 at a quarter of the shipped step: error ~1e-10 of the force
  const auto a = testing::run(ref);
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-6;
  RunStats st;
  const auto b = testing::run(m, &st);
  ASSERT_EQ(a.size(), b.size());
  double fmax = 0, dF = 0, dP = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    fmax = std::max(fmax, a[i].tow_force.norm());
    dF = std::max(dF, (a[i].tow_force - b[i].tow_force).norm());
    for (const auto& bs : a[i].bodies) fmax = std::max(fmax, bs.link_force.norm());
    for (std::size_t j = 0; j < a[i].bodies.size(); ++j)
      dF = std::max(dF, (a[i].bodies[j].link_force - b[i].bodies[j].link_force).norm());
    dP = std::max(dP, max_distance(a[i].node_pos, b[i].node_pos));
  }
  std::cout << "[measured] " << GetParam() << " rosenbrock tol 1e-6 vs rk4: max |dF| " << dF << " N (of " << fmax
            << " N), max joint distance " << dP << " m; " << st.steps << " steps, " << st.rhs_evaluations
            << " evaluations; error estimate " << st.error_estimate << "\n";
  // Tolerance 1e-6 on local errors relative to 1 + |y| (positions of ~100 m:
  // 1e-4 m per step at most), accumulated over a few hundred steps: bounds
  // 1e-4 of the peak force and 1 cm in joint position. Measured: force
  // differences 5e-6 to 1.5e-5 of the peak, joints 0.13 to 1.6 mm.
  EXPECT_LT(dF, 1e-4 * fmax);
  EXPECT_LT(dP, 1e-2);
  EXPECT_GE(st.error_estimate, 0.0);
  EXPECT_LE(st.error_estimate, 1e-6);  // accepted steps only: never above the tolerance
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, RosenbrockExamples,
                         ::testing::Values("paper-planar-a", "paper-planar-b", "paper-3d-turn", "cable-tow"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

// ---------------------------------------------------------------------------
// 4. km-cable-1000 (bench/scenarios): stable and accurate at 10x and more the
// RK4 stability limit (0.0157 s).
// ---------------------------------------------------------------------------
Model km_cable() {
  Model m = testing::paper52_turn(1000, 1000);
  m.sim.duration = 12;
  m.sim.output_interval = 1;
  return m;
}

TEST(RosenbrockKmCable, StableAndAccurateAtTenTimesTheRk4Limit) {
  const Model m = km_cable();
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 0.0125;  // the scenario's step: tow force error ~1e-8 (docs/performance.md)
  const auto a = testing::run(ref);
  for (const double h : {0.16, 0.32}) {  // 10x and 20x the RK4 limit
    RunStats st;
    const auto b = testing::run(fixed_rosenbrock(m, h), &st);
    ASSERT_EQ(a.size(), b.size());
    double e = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      e = std::max(e, (a[i].tow_force - b[i].tow_force).norm() / a[i].tow_force.norm());
    std::cout << "[measured] km-cable-1000, 12 s, rosenbrock fixed h = " << h << " s: max relative tow force error "
              << e << " (" << st.steps << " steps)\n";
    // Measured 1.86e-4 (0.16 s) and 9.83e-4 (0.32 s; outputs every 1 s read
    // from the dense output, order 3: ratio 5.3). Bounds: 1e-3 at 10x, the
    // accuracy issue 10 asks of the tow force; 2e-3 at 20x (twice the
    // measured error, well under the 8e-3 order 3 would allow from 1e-3).
    EXPECT_LT(e, h < 0.2 ? 1e-3 : 2e-3);
  }
}

// The force error estimate is honest at large steps: in km-cable-1000's ramp
// the state error lets the steps grow to 0.3-0.66 s, where the tow force
// reads the stiff components (rocking of the top elements) directly. The
// estimate compares the forces at y1 and at the embedded solution itself;
// with the embedded solution filtered by (I - hg W)^-1 (as the state error
// is) their error was divided by ~hg |lambda| and the tow force came out
// 1.7e-3 off at tolerance 1e-4 (docs/performance.md, "Force error estimate").
TEST(RosenbrockKmCable, ForceErrorEstimateIsHonestAtLargeSteps) {
  Model m = km_cable();
  m.sim.output_interval = 0.1;  // dense outputs inside the large steps too
  Model ref = m;
  ref.sim.integrator = Integrator::RK4;
  ref.sim.time_step = 0.0125;  // tow force error ~1e-8 (docs/performance.md)
  const auto a = testing::run(ref);
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-4;
  RunStats st;
  const auto b = testing::run(m, &st);
  ASSERT_EQ(a.size(), b.size());
  double e = 0, peak = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e = std::max(e, (a[i].tow_force - b[i].tow_force).norm());
    peak = std::max(peak, a[i].tow_force.norm());
  }
  std::cout << "[measured] km-cable-1000, 12 s, rosenbrock tol 1e-4: max tow force error / peak " << e / peak << " ("
            << st.steps << " steps)\n";
  // Measured 7.8e-4 in 61 steps (filtered force estimate: 1.7e-3 in 50):
  // bound 1e-3, the accuracy issue 10 asks of the tow force at this tolerance.
  EXPECT_LT(e / peak, 1e-3);
}

// ---------------------------------------------------------------------------
// 5. The RK4 stability estimate: against the measured limit, and the run's
// warning and refusal.
// ---------------------------------------------------------------------------
/// 30 elements of 1 m under the tension of a heavy sphere, towed: the RK4
/// limit is the rocking of the short elements.
Model tense_cable() {
  CableSpec spec;
  spec.n = 30;
  spec.length = 30;
  spec.mass_per_length = 0.2;
  spec.diameter = 0.01;
  Model m = testing::cable_model(spec);
  testing::add_sphere_body(m, 200.0, 0.2);
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.0, 2));
  m.sim.duration = 4;
  m.sim.output_interval = 0.5;
  return m;
}

/// 20 elements of 10 m towed at 3 m/s (6 kn) from a steady start, with a
/// heavy sphere: normal drag damps the fast modes as fast as they rock
/// (the km-turn-100 bench case in short).
Model fast_tow() {
  CableSpec spec;
  spec.n = 20;
  spec.length = 200;
  spec.mass_per_length = 1.12;
  spec.diameter = 0.0173;
  spec.cd = 1.5;
  Model m = testing::cable_model(spec);
  testing::add_sphere_body(m, 1135.0, 0.368, 0.77);
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 3.084, 0));
  m.initial.kind = Initial::Kind::Steady;
  m.sim.duration = 4;
  m.sim.output_interval = 0.5;
  return m;
}

bool rk4_survives(Model m, double h) {
  m.sim.integrator = Integrator::RK4;
  m.sim.time_step = h;
  m.sim.duration = 20;  // long enough for an unstable mode to grow from round-off
  m.sim.output_interval = 20;
  MemorySink sink;
  const RunStats st = simulate(m, sink);
  // "failed" by divergence; the refusal (h > 1.5 x estimate) is not reached in the bisection range below.
  return st.status == "ok" && st.message.empty();
}

struct LimitCase {
  std::string name;
  Model (*model)();
};

class Rk4StabilityEstimate : public ::testing::TestWithParam<LimitCase> {};

TEST_P(Rk4StabilityEstimate, WithinTenPerCentOfTheMeasuredLimit) {
  Model m = GetParam().model();
  // The estimate from a run well inside the limit (its smallest over the samples).
  m.sim.integrator = Integrator::RK4;
  m.sim.time_step = 1e-3;
  RunStats st;
  testing::run(m, &st);
  const double est = st.rk4_step_limit;
  ASSERT_GT(est, 0);
  EXPECT_TRUE(st.warnings.empty());
  // The measured limit, by bisection between 0.8 and 1.45 times the estimate.
  double lo = 0.8 * est, hi = 1.45 * est;
  ASSERT_TRUE(rk4_survives(m, lo));
  ASSERT_FALSE(rk4_survives(m, hi));
  for (int i = 0; i < 8; ++i) {
    const double mid = 0.5 * (lo + hi);
    (rk4_survives(m, mid) ? lo : hi) = mid;
  }
  std::cout << "[measured] RK4 stability, " << GetParam().name << ": estimate " << est << " s, measured limit " << lo
            << " s (ratio " << lo / est << ")\n";
  // The estimate: the rocking mode of one element between fixed joints,
  // shifted by its drag damping (docs/theory.md 6.4). Bound: within 10 %,
  // so that a step above 1.5x the estimate is surely unstable (the
  // refusal) and one below 0.9x it stable. Measured ratios (measured limit
  // / estimate): see the [measured] lines; on the bench cases
  // km-cable-1000 0.0157 / 0.01458 = 1.08, km-turn-100 0.071 / 0.0747 = 0.95.
  EXPECT_NEAR(lo / est, 1.0, 0.10);
}

INSTANTIATE_TEST_SUITE_P(Chains, Rk4StabilityEstimate,
                         ::testing::Values(LimitCase{"tense_cable", tense_cable}, LimitCase{"fast_tow", fast_tow}),
                         [](const auto& info) { return info.param.name; });

TEST(Rk4StabilityLimit, WarnsAboveAndRefusesFarAbove) {
  Model m = tense_cable();
  m.sim.integrator = Integrator::RK4;
  m.sim.time_step = 1e-3;
  RunStats st;
  testing::run(m, &st);
  const double est = st.rk4_step_limit;
  // Just above: the run goes on, with a warning naming the limit and the fix.
  m.sim.duration = 0.5;
  m.sim.time_step = 1.1 * est;
  MemorySink sink;
  const RunStats w = simulate(m, sink);
  ASSERT_FALSE(w.warnings.empty());
  EXPECT_NE(w.warnings.front().find("above 0.9 times the estimated stability limit"), std::string::npos)
      << w.warnings.front();
  EXPECT_NE(w.warnings.front().find("integrator: rosenbrock"), std::string::npos);
  // Far above: refused (status failed), before any step when the start already shows it.
  m.sim.time_step = 2.0 * est;
  MemorySink sink2;
  const RunStats r = simulate(m, sink2);
  EXPECT_EQ(r.status, "failed");
  EXPECT_NE(r.message.find("refused: rk4 time_step"), std::string::npos) << r.message;
}

TEST(Rk4StabilityLimit, ShippedExamplesDoNotWarn) {
  // Every built-in example at its own time step (30 s of it) with rk4: no
  // warning. The examples that run the default integrator (rosenbrock, their
  // time_step its first step) ran rk4 at that step before it became the
  // default, and `integrator: rk4` must still run them; an example that
  // names rosenbrock itself (fish-depth-change: stiff for rk4) is skipped.
  for (const auto& ex : scenario::examples()) {
    scenario::LoadedScenario sc = scenario::load_scenario_text(ex.yaml, ex.name + ".yaml", ex.name, ".");
    ASSERT_TRUE(sc.ok()) << ex.name;
    if (sc.spec.simulation.integrator.given && sc.spec.simulation.integrator.value != "rk4") continue;
    Model m = *sc.model;
    m.sim.integrator = Integrator::RK4;
    m.sim.duration = std::min(m.sim.duration, 30.0);
    m.sim.write_nodes = false;
    RunStats st;
    testing::run(m, &st);
    std::cout << "[measured] " << ex.name << ": time_step " << m.sim.time_step << " s, estimated rk4 limit "
              << st.rk4_step_limit << " s\n";
    EXPECT_TRUE(st.warnings.empty()) << ex.name << ": " << st.warnings.front();
  }
}

}  // namespace
}  // namespace towsim
