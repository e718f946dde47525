// Properties that MuJoCo's and Pinocchio's suites check and that every
// evaluation here must have: determinism (in one process and across two),
// evaluations that leave their inputs unchanged, a derivative that depends
// on its arguments only, a reused workspace that gives what a fresh one
// gives, and the impulsive response to a tow-velocity jump against the
// dense formula of docs/theory.md 6.1, dq'_a = -M_aa^-1 M_a0 dv, from the
// paper formulation's mass matrix.
//
// States and results are compared through the flatten() helpers below, the
// one place that lists their fields.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../support/cli.hpp"
#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/paper.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim {
namespace {

// --- flattening, for bitwise comparison ---------------------------------------

void put(std::vector<double>& out, const Vec3& v) { out.insert(out.end(), v.data(), v.data() + 3); }
void put(std::vector<double>& out, const std::vector<Vec3>& vs) {
  for (const Vec3& v : vs) put(out, v);
}
void put(std::vector<double>& out, const Eigen::VectorXd& v) { out.insert(out.end(), v.data(), v.data() + v.size()); }

std::vector<double> flatten(const PhysicalState& s) {
  std::vector<double> out;
  put(out, s.r0), put(out, s.v0), put(out, s.e), put(out, s.w);
  for (const BodyState& b : s.bodies) {
    put(out, b.w);
    out.insert(out.end(), b.q.coeffs().data(), b.q.coeffs().data() + 4);
  }
  return out;
}

std::vector<double> flatten(const Accelerations& a) {
  std::vector<double> out;
  put(out, a.a0), put(out, a.alpha), put(out, a.alpha_b), put(out, a.tow_force), put(out, a.link_force);
  put(out, a.lower_link_force);
  put(out, a.joint_force);
  return out;
}

/// The results of one default-formulation evaluation: kinematics and accelerations.
std::vector<double> flatten(const Workspace& ws) {
  std::vector<double> out = flatten(ws.acc);
  put(out, ws.P), put(out, ws.vP), put(out, ws.G), put(out, ws.vG);
  for (const BodyWork& b : ws.body) put(out, b.O), put(out, b.vO);
  return out;
}

std::vector<double> flatten(const PaperState& p) {
  std::vector<double> out;
  put(out, p.r0), put(out, p.v0), put(out, p.q), put(out, p.qd);
  for (const Mat3& c : p.chart) out.insert(out.end(), c.data(), c.data() + 9);
  out.insert(out.end(), p.body_chart.data(), p.body_chart.data() + 9);
  return out;
}

std::vector<double> flatten(const Sample& s) {
  std::vector<double> out{s.t};
  put(out, s.tow_pos), put(out, s.tow_vel), put(out, s.tow_force), put(out, s.node_pos), put(out, s.node_vel);
  out.insert(out.end(), s.tension.begin(), s.tension.end());
  out.insert(out.end(), s.axial.begin(), s.axial.end());
  for (const BodySample& b : s.bodies) {
    put(out, b.pos), put(out, b.vel), put(out, b.rpy_deg), put(out, b.omega);
    put(out, b.link_force), put(out, b.lower_link_force);
  }
  return out;
}

/// Bitwise equality (NaN equals itself, -0 differs from 0).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// --- the models -----------------------------------------------------------------

/// A 6-element cable with tangential friction in a sheared current, towed by
/// a ramp and a heave that starts at full speed (a velocity jump at t = 1 s),
/// with the body of every load model or none.
Model anchor_model(bool body, Formulation f = Formulation::Default, Integrator i = Integrator::RK4) {
  testing::CableSpec spec;
  spec.n = 6;
  spec.length = 60;
  spec.tangential = 0.02;
  Model m = testing::cable_model(spec);
  m.fluid.current_depth = {0, 30};
  m.fluid.current_velocity = {Vec3(0.4, 0.1, 0), Vec3(0.1, 0, 0)};
  if (body) testing::add_rich_body(m);
  m.tow.pieces = {testing::ramp_piece(Vec3(1, 0, 0), 1.5, 2.0), testing::heave_piece(0.5, 4.0, 1.0)};
  m.sim.duration = 3;
  m.sim.output_interval = 0.25;
  m.sim.formulation = f;
  m.sim.integrator = i;
  return m;
}

/// A random state with the tow point where the tow law puts it at t.
PhysicalState state_at(const Model& m, std::mt19937& rng, double t) {
  PhysicalState s = testing::random_state(m, rng);
  const TowKinematics k = tow_kinematics(m.tow, t);
  s.r0 = k.pos, s.v0 = k.vel;
  return s;
}

std::string with_body_name(const ::testing::TestParamInfo<bool>& info) { return info.param ? "Body" : "NoBody"; }

// --- determinism: the same run twice in one process -----------------------------

class Determinism : public ::testing::TestWithParam<testing::RunCase> {};

TEST_P(Determinism, SameRunTwiceIsBitwiseIdentical) {
  const auto c = GetParam();
  const Model m = anchor_model(true, c.formulation, c.integrator);
  RunStats st1, st2;
  const auto first = testing::run(m, &st1);
  (void)testing::run(anchor_model(false, c.formulation, c.integrator));  // another model in between
  const auto second = testing::run(m, &st2);
  ASSERT_EQ(first.size(), second.size());
  ASSERT_EQ(first.size(), 13u);  // t = 0, 0.25, ..., 3
  for (std::size_t i = 0; i < first.size(); ++i)
    EXPECT_TRUE(same_bits(flatten(first[i]), flatten(second[i]))) << "sample " << i << " (t = " << first[i].t << ")";
  EXPECT_EQ(st1.steps, st2.steps);
  EXPECT_EQ(st1.rejected_steps, st2.rejected_steps);
  EXPECT_EQ(st1.rhs_evaluations, st2.rhs_evaluations);
  EXPECT_TRUE(same_bits({st1.end_time, st1.max_element_drift}, {st2.end_time, st2.max_element_drift}));
}

INSTANTIATE_TEST_SUITE_P(Anchors, Determinism, ::testing::ValuesIn(testing::all_run_cases()),
                         testing::run_case_param_name);

// --- determinism: two processes through the program -----------------------------

class CliDeterminism : public testing::TempDirTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(CliDeterminism, TwoProcessesWriteIdenticalFiles) {
  const std::string args = "run --example paper-3d-turn --set simulation.duration=3 --set simulation.formulation=" +
                           GetParam() + " --quiet --out ";
  for (const char* out : {"a", "b"}) {
    const auto r = testing::run_towsim(args + testing::quoted(dir_ / out));
    ASSERT_EQ(r.status, 0) << r.out;
  }
  for (const char* f : {"timeseries.csv", "nodes.csv"}) {
    const std::string a = testing::slurp(dir_ / "a" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == testing::slurp(dir_ / "b" / f)) << f << " differs between two runs";
  }
  // summary.json: identical but for the wall-clock time.
  auto ja = nlohmann::json::parse(testing::slurp(dir_ / "a" / "summary.json"));
  auto jb = nlohmann::json::parse(testing::slurp(dir_ / "b" / "summary.json"));
  ja.erase("wall_seconds"), jb.erase("wall_seconds");
  EXPECT_EQ(ja.dump(), jb.dump());
}

INSTANTIATE_TEST_SUITE_P(Anchors, CliDeterminism, ::testing::Values("default", "paper"),
                         [](const auto& info) { return info.param; });

// --- evaluations leave their inputs unchanged -----------------------------------

class NoMutation : public ::testing::TestWithParam<bool> {};

TEST_P(NoMutation, DynamicsLeaveTheStateUnchanged) {
  const Model m = anchor_model(GetParam());
  std::mt19937 rng(7);
  Workspace ws(m);
  PaperWorkspace pw(m);
  for (int trial = 0; trial < 4; ++trial) {
    const PhysicalState s = state_at(m, rng, 0.6);
    const auto before = flatten(s);
    forward_dynamics(m, s, 0.6, ws);
    EXPECT_TRUE(same_bits(flatten(s), before)) << "forward_dynamics";
    tow_velocity_jump(m, s, Vec3(0.1, -0.2, 0.3), ws);
    EXPECT_TRUE(same_bits(flatten(s), before)) << "tow_velocity_jump";
    const PaperState p = to_paper(m, s);
    const auto p_before = flatten(p);
    paper_dynamics(m, p, 0.6, pw);
    EXPECT_TRUE(same_bits(flatten(p), p_before)) << "paper_dynamics";
  }
}

TEST_P(NoMutation, SystemEvaluationsLeaveTheStateVectorUnchanged) {
  for (Formulation f : {Formulation::Default, Formulation::Paper}) {
    const Model m = anchor_model(GetParam(), f);
    const auto sys = make_system(m);
    std::mt19937 rng(11);
    const StateVector y = sys->initial(state_at(m, rng, 0.6), 0.6);
    const StateVector y0 = y;
    const auto s0 = flatten(sys->physical(y));
    // The window of the step being taken (as simulate() gives it).
    const StepWindow window{0.5, 0.7};
    StateVector dy1, dy2;
    sys->derivative(y, dy1, 0.6, window);
    EXPECT_TRUE(same_bits(y, y0)) << testing::formulation_name(f) << ": derivative";
    EXPECT_TRUE(same_bits(flatten(sys->physical(y)), s0)) << testing::formulation_name(f) << ": derivative";
    sys->evaluate(y, 0.6);
    EXPECT_TRUE(same_bits(y, y0)) << testing::formulation_name(f) << ": evaluate";
    EXPECT_TRUE(same_bits(flatten(sys->physical(y)), s0)) << testing::formulation_name(f) << ": evaluate";
    // An evaluation leaves nothing behind that changes the next one.
    sys->derivative(y, dy2, 0.6, window);
    EXPECT_TRUE(same_bits(dy1, dy2)) << testing::formulation_name(f);
  }
}

INSTANTIATE_TEST_SUITE_P(Anchors, NoMutation, ::testing::Bool(), with_body_name);

// --- derivative() is a function of its arguments --------------------------------

/// A built-in example with --set overrides, compiled.
Model example(const std::string& name, const std::vector<std::string>& sets = {}) {
  const scenario::Example* e = scenario::find_example(name);
  EXPECT_NE(e, nullptr) << name;
  if (e == nullptr) return Model{};
  scenario::LoadedScenario sc = scenario::load_scenario_text(e->yaml, name + ".yaml", name, "", sets);
  EXPECT_TRUE(sc.ok()) << sc.diags.str();
  return sc.ok() ? *sc.model : Model{};
}

/// Models with every kind of block in the flat state, the paper's and a
/// worker thread; each with its name.
std::vector<std::pair<std::string, Model>> block_models() {
  std::vector<std::pair<std::string, Model>> v;
  v.emplace_back("cable", anchor_model(false));
  v.emplace_back("body", anchor_model(true));
  v.emplace_back("paper, body", anchor_model(true, Formulation::Paper));
  v.emplace_back("imposed winch", example("fish-depth-change"));
  Model tension = example("fish-depth-change");
  tension.winch.mode = Winch::Mode::Tension;
  tension.winch.tension = 2e4, tension.winch.drum_inertia = 200, tension.winch.damping = 500;
  v.emplace_back("tension winch", tension);
  v.emplace_back("depth controllers", example("fish-depth-control"));
  v.emplace_back("elastic", example("cable-tow", {"cable.axial_stiffness=1e7"}));
  v.emplace_back("two bodies", example("two-part-tow"));
  v.emplace_back("worker thread", example("paper-3d-turn", {"simulation.threads=2"}));
  return v;
}

/// Every call of the System's interface once, at the state `y` [t = 2.2 s,
/// window 2.0-2.5 s]: what may come between two evaluations of a run.
void call_everything(System& sys, const StateVector& y) {
  const StepWindow elsewhere{2.0, 2.5};
  StateVector dy, k, x = y;
  EvaluationForces side;
  PhysicalState view;
  sys.derivative(y, dy, 2.2, elsewhere);
  if (sys.has_stage_solve()) {
    sys.prepare_stage_solve(2.2, elsewhere);
    sys.stage_solve(0.01, dy, k);
    sys.derivative_time_shift(y, dy, 2.3, elsewhere);
  }
  sys.derivative_with_side_forces(y, dy, 2.2, y, 2.4, elsewhere, side);
  sys.derivative(y, dy, 2.2);
  (void)sys.evaluate(y, 2.2);
  sys.physical_into(y, view);
  sys.project(x, 2.2);
  x = y;
  (void)sys.apply_tow_jump(x, 1.0);
}

// MuJoCo's determinism check: derivative() twice with the same arguments,
// every other call between at another state, time and window, gives the same
// bits, and the same as a fresh System's.
TEST(PureDerivative, SameArgumentsSameBitsWhateverCameBetween) {
  for (const auto& [name, m] : block_models()) {
    const auto sys = make_system(m), fresh = make_system(m);
    std::mt19937 rng(17);
    const StateVector y = sys->initial(state_at(m, rng, 0.6), 0.6);
    const StateVector other = sys->initial(state_at(m, rng, 2.2), 2.2);
    const StepWindow window{0.5, 0.7};
    StateVector dy1, dy2, dy_fresh, shifted;
    sys->derivative(y, dy1, 0.6, window);
    call_everything(*sys, other);
    sys->derivative(y, dy2, 0.6, window);
    fresh->derivative(y, dy_fresh, 0.6, window);
    EXPECT_TRUE(same_bits(dy1, dy2)) << name;
    EXPECT_TRUE(same_bits(dy1, dy_fresh)) << name;
    // The time shift (a cache of the Jacobian point's inertias) is the same function.
    call_everything(*sys, other);
    sys->derivative_time_shift(y, shifted, 0.6, window);
    EXPECT_TRUE(same_bits(dy1, shifted)) << name << ": time shift";
    // The window is an argument: another window, another law time.
    sys->derivative(y, dy2, 0.6, StepWindow::after(0.6));
    fresh->derivative(y, dy_fresh, 0.6, StepWindow::after(0.6));
    EXPECT_TRUE(same_bits(dy2, dy_fresh)) << name << ": right limit";
  }
}

// Evaluating for output changes nothing observable: the same outputs, row
// names, physical states, projections and jumps as a fresh System's, and no
// evaluation counted (derivative() counts one).
TEST(PureDerivative, EvaluatingChangesNothingObservable) {
  for (const auto& [name, m] : block_models()) {
    const auto sys = make_system(m), fresh = make_system(m);
    std::mt19937 rng(19);
    const StateVector y = sys->initial(state_at(m, rng, 0.6), 0.6);
    const StateVector other = sys->initial(state_at(m, rng, 2.2), 2.2);
    const std::vector<double> out = flatten(sys->evaluate(y, 0.6));
    call_everything(*sys, other);
    EXPECT_TRUE(same_bits(flatten(sys->evaluate(y, 0.6)), out)) << name;
    EXPECT_TRUE(same_bits(flatten(fresh->evaluate(y, 0.6)), out)) << name;
    const long n = sys->rhs_evaluations;
    (void)sys->evaluate(y, 0.6);
    EXPECT_EQ(sys->rhs_evaluations, n) << name;
    StateVector dy;
    sys->derivative(y, dy, 0.6);
    EXPECT_EQ(sys->rhs_evaluations, n + 1) << name;
    PhysicalState view;
    sys->physical_into(y, view);
    EXPECT_TRUE(same_bits(flatten(view), flatten(fresh->physical(y)))) << name;
    EXPECT_TRUE(same_bits(flatten(sys->physical(y)), flatten(fresh->physical(y)))) << name;
    for (std::size_t i = 0; i < y.size(); ++i) EXPECT_EQ(sys->describe(i), fresh->describe(i)) << name;
    StateVector a = y, b = y;
    sys->project(a, 0.6), fresh->project(b, 0.6);
    EXPECT_TRUE(same_bits(a, b)) << name << ": project";
    a = y, b = y;
    EXPECT_EQ(sys->apply_tow_jump(a, 1.0), fresh->apply_tow_jump(b, 1.0)) << name;
    EXPECT_TRUE(same_bits(a, b)) << name << ": apply_tow_jump";
  }
}

// --- a reused workspace gives what a fresh one gives ---------------------------

class ReusedWorkspace : public ::testing::TestWithParam<bool> {};

TEST_P(ReusedWorkspace, StateAThenBThenAEqualsFresh) {
  const Model m = anchor_model(GetParam());
  std::mt19937 rng(3);
  const PhysicalState a = state_at(m, rng, 0.6), b = state_at(m, rng, 0.6);
  const Vec3 dv(0.3, 0.1, -0.2);
  // Default formulation: forward_dynamics and tow_velocity_jump.
  Workspace used(m), fresh(m);
  forward_dynamics(m, a, 0.6, used);
  forward_dynamics(m, b, 0.6, used);
  tow_velocity_jump(m, b, dv, used);
  forward_dynamics(m, a, 0.6, used);
  forward_dynamics(m, a, 0.6, fresh);
  EXPECT_TRUE(same_bits(flatten(used), flatten(fresh))) << "forward_dynamics";
  tow_velocity_jump(m, a, dv, used);
  Workspace fresh_jump(m);
  tow_velocity_jump(m, a, dv, fresh_jump);
  EXPECT_TRUE(same_bits(flatten(used.acc), flatten(fresh_jump.acc))) << "tow_velocity_jump";
  // Paper formulation: its coordinates carry their charts, so A is the same input again.
  const PaperState pa = to_paper(m, a), pb = to_paper(m, b);
  PaperWorkspace pused(m), pfresh(m);
  paper_dynamics(m, pa, 0.6, pused);
  paper_dynamics(m, pb, 0.6, pused);
  paper_dynamics(m, pa, 0.6, pused);
  paper_dynamics(m, pa, 0.6, pfresh);
  EXPECT_TRUE(same_bits(flatten(pused.acc), flatten(pfresh.acc))) << "paper_dynamics";
  EXPECT_TRUE(same_bits(std::vector<double>(pused.qdd.data(), pused.qdd.data() + pused.qdd.size()),
                        std::vector<double>(pfresh.qdd.data(), pfresh.qdd.data() + pfresh.qdd.size())));
}

// A System keeps its workspace between calls: A, B, A gives what a fresh
// System gives for A (the paper System's charts are in its state vector).
TEST_P(ReusedWorkspace, SystemAThenBThenAEqualsFresh) {
  for (Formulation f : {Formulation::Default, Formulation::Paper}) {
    const Model m = anchor_model(GetParam(), f);
    std::mt19937 rng(5);
    const auto used = make_system(m);
    const StateVector ya = used->initial(state_at(m, rng, 0.6), 0.6);
    const StateVector yb = used->initial(state_at(m, rng, 0.6), 0.6);
    StateVector dy_used, dy_fresh, scratch;
    const StepWindow window{0.5, 0.7};
    used->derivative(ya, scratch, 0.6, window);
    used->derivative(yb, scratch, 0.6, window);
    used->derivative(ya, dy_used, 0.6, window);
    const auto fresh = make_system(m);
    fresh->derivative(ya, dy_fresh, 0.6, window);
    EXPECT_TRUE(same_bits(dy_used, dy_fresh)) << testing::formulation_name(f);
    used->evaluate(yb, 0.6);
    EXPECT_TRUE(same_bits(flatten(used->evaluate(ya, 0.6)), flatten(fresh->evaluate(ya, 0.6))))
        << testing::formulation_name(f);
  }
}

INSTANTIATE_TEST_SUITE_P(Anchors, ReusedWorkspace, ::testing::Bool(), with_body_name);

// --- tow_velocity_jump against the dense formula --------------------------------

/// Angular-velocity jumps [rad/s, R_g] from dq'_a = -M_aa^-1 M_a0 dv, with
/// M the paper formulation's generalized mass (Kane's form, assembled
/// densely in paper.cpp, independently of the O(n) recursion): the rates
/// move by dq'_a in the state's own charts, and from_paper() turns both
/// rate vectors into angular velocities. Element k at [k], the body last.
std::vector<Vec3> dense_jump(const Model& m, const PhysicalState& s, const Vec3& dv) {
  PaperWorkspace pw(m);
  const PaperState p = to_paper(m, s);
  paper_dynamics(m, p, 0.0, pw);  // M depends on the configuration only
  const int na = static_cast<int>(pw.M.rows()) - 3;
  const Eigen::MatrixXd Maa = pw.M.bottomRightCorner(na, na);
  const Eigen::MatrixXd Ma0 = pw.M.bottomLeftCorner(na, 3);
  PaperState after = p;
  after.qd += Maa.fullPivLu().solve(-Ma0 * dv);
  const PhysicalState s0 = from_paper(m, p), s1 = from_paper(m, after);
  std::vector<Vec3> out;
  for (int k = 0; k < m.cable.n(); ++k) out.push_back(s1.w[k] - s0.w[k]);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) out.push_back(s1.bodies[b].w - s0.bodies[b].w);
  return out;
}

/// Largest |a_i - b_i| over the largest |b_i|.
double rel_diff(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0, scale = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    d = std::max(d, (a[i] - b[i]).norm());
    scale = std::max(scale, b[i].norm());
  }
  return d / scale;
}

// Both sides solve the same linear system exactly, one by the O(n) recursion
// and one by a dense LU of M_aa, so they differ by round-off times M_aa's
// condition number: measured 7e-15 (no body) and 2e-14 (body) over these
// random states. 1e-10 leaves four orders for other states and compilers and
// still catches any missing or wrong term (those are O(1) relative).
constexpr double kJumpTol = 1e-10;

class VelocityJump : public ::testing::TestWithParam<bool> {};

TEST_P(VelocityJump, RecursionMatchesDenseFormula) {
  Model m = anchor_model(GetParam());
  std::mt19937 rng(2024);
  std::normal_distribution<double> N(0.0, 1.0);
  Workspace ws(m);
  double worst = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const PhysicalState s = testing::random_state(m, rng);
    const Vec3 dv(N(rng), N(rng), N(rng));
    tow_velocity_jump(m, s, dv, ws);
    std::vector<Vec3> fast = ws.acc.alpha;
    for (const Vec3& a : ws.acc.alpha_b) fast.push_back(a);
    const double d = rel_diff(fast, dense_jump(m, s, dv));
    worst = std::max(worst, d);
    EXPECT_LT(d, kJumpTol) << "trial " << trial;
  }
  std::printf("[measured] tow_velocity_jump vs dense, %s: max relative difference %.2e\n",
              GetParam() ? "body" : "no body", worst);
}

// The impulse applied by each System at a breakpoint (a heave starting at
// full speed at t = 1 s) is the dense formula's, in both formulations.
TEST_P(VelocityJump, BothSystemsApplyTheDenseJump) {
  for (Formulation f : {Formulation::Default, Formulation::Paper}) {
    const Model m = anchor_model(GetParam(), f);
    std::mt19937 rng(99);
    const PhysicalState s = state_at(m, rng, 1.0);
    const auto sys = make_system(m);
    StateVector y = sys->initial(s, 1.0);
    const PhysicalState before = sys->physical(y);
    const double size = sys->apply_tow_jump(y, 1.0);
    const Vec3 dv = Vec3(0, 0, 2 * std::numbers::pi * 0.5 / 4.0);  // heave: A 2 pi / T, upwards
    EXPECT_NEAR(size, dv.norm(), 1e-7 * dv.norm());                // found by +-1e-9 s differences (see below)
    const PhysicalState after = sys->physical(y);
    std::vector<Vec3> applied;
    for (int k = 0; k < m.cable.n(); ++k) applied.push_back(after.w[k] - before.w[k]);
    for (std::size_t b = 0; b < m.bodies.size(); ++b) applied.push_back(after.bodies[b].w - before.bodies[b].w);
    // The Systems measure the tow's velocity jump by differences across the
    // breakpoint (+-1e-9 s), so dv carries an error of order 1e-9 s times the
    // tow acceleration over |dv| (measured 1.5e-9 here): 1e-7 allows for that;
    // the recursion itself is checked to 1e-10 above.
    const double d = rel_diff(applied, dense_jump(m, before, dv));
    std::printf("[measured] %s System jump vs dense, %s: relative difference %.2e\n",
                testing::formulation_name(f).c_str(), GetParam() ? "body" : "no body", d);
    EXPECT_LT(d, 1e-7) << testing::formulation_name(f);
  }
}

INSTANTIATE_TEST_SUITE_P(Anchors, VelocityJump, ::testing::Bool(), with_body_name);

}  // namespace
}  // namespace towsim
