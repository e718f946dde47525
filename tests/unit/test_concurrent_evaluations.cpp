// simulation.threads (docs/performance.md "Concurrent step-end evaluations
//"): the rosenbrock step's two final evaluations on two threads
// give the same run, bit for bit, as on one; the worker hands exceptions
// back; the key's checks and its auto rule. The elements' loads split
// between the worker and the caller (compute_loads with a Fork)
// give the same loads and results, evaluation by evaluation and run by run.
//
// Exact comparisons (EXPECT_EQ on doubles) are right here: with a worker the
// same evaluations run on the same inputs in the same order of operations,
// only on another core and another Workspace of the same model; every
// evaluation rewrites what it reads of its Workspace. Any difference, even
// in the last bit, would mean state shared between the two evaluations.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/integrators/worker.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"

namespace {

using namespace towsim;

/// A built-in example with --set overrides, compiled.
Model example_model(const std::string& name, const std::vector<std::string>& sets) {
  const scenario::Example* e = scenario::find_example(name);
  EXPECT_NE(e, nullptr) << name;
  if (e == nullptr) return Model{};
  scenario::LoadedScenario sc = scenario::load_scenario_text(e->yaml, name + ".yaml", name, "", sets);
  EXPECT_TRUE(sc.ok()) << sc.diags.str();
  return sc.ok() ? *sc.model : Model{};
}

void push3(std::vector<double>& v, const Vec3& x) { v.insert(v.end(), {x.x(), x.y(), x.z()}); }

/// Every number of a sample, in a fixed order.
std::vector<double> flat(const Sample& s) {
  std::vector<double> v{
      s.t, s.deployed_length, s.payout_speed, s.contact_length, s.seabed_normal, s.seabed_friction, s.wave_elevation};
  push3(v, s.tow_pos), push3(v, s.tow_vel), push3(v, s.tow_force), push3(v, s.tow_wave);
  for (long id : s.node_id) v.push_back(static_cast<double>(id));
  for (const Vec3& x : s.node_pos) push3(v, x);
  for (const Vec3& x : s.node_vel) push3(v, x);
  for (const Vec3& x : s.node_seabed) push3(v, x);
  for (const auto* a : {&s.tension, &s.axial, &s.strain, &s.utilisation}) v.insert(v.end(), a->begin(), a->end());
  for (const BodySample& b : s.bodies) {
    for (const Vec3* x : {&b.pos, &b.vel, &b.rpy_deg, &b.omega, &b.link_force, &b.lower_link_force}) push3(v, *x);
    for (const ControlSample& c : b.controls) v.insert(v.end(), {c.deflection_deg, c.rate_deg_s, c.depth_error});
  }
  return v;
}

/// A scenario text, compiled.
Model text_model(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  scenario::LoadedScenario sc = scenario::load_scenario_text(yaml, "test.yaml", "test", "", sets);
  EXPECT_TRUE(sc.ok()) << sc.diags.str();
  return sc.ok() ? *sc.model : Model{};
}

/// The model run with simulation.threads = 1 and = 2: the same samples,
/// steps and evaluations; returns the serial run's statistics.
RunStats expect_same_runs(Model m) {
  m.sim.threads = 1;
  MemorySink one;
  const RunStats a = simulate(m, one);
  m.sim.threads = 2;
  MemorySink two;
  const RunStats b = simulate(m, two);
  EXPECT_EQ(a.threads, 1);
  EXPECT_EQ(b.threads, 2);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.rejected_steps, b.rejected_steps);
  EXPECT_EQ(a.rhs_evaluations, b.rhs_evaluations);
  EXPECT_EQ(a.error_estimate, b.error_estimate);
  EXPECT_EQ(a.force_error_estimate, b.force_error_estimate);
  EXPECT_EQ(one.samples.size(), two.samples.size());
  if (one.samples.size() != two.samples.size()) return a;
  for (std::size_t i = 0; i < one.samples.size(); ++i)
    EXPECT_EQ(flat(one.samples[i]), flat(two.samples[i])) << "sample " << i << " (t = " << one.samples[i].t << " s)";
  return a;
}

/// y' = -y on 3 components with the exact stage solve, for the step-end
/// protocol of RosenbrockW: its side evaluation runs on a Worker, as
/// DefaultSystem's with threads 2, and throws when told; the calls are
/// recorded (s: start, f: finish, c: cancel).
class DecaySystem final : public System {
 public:
  bool side_throws = false;
  std::string calls;

  StateVector initial(const PhysicalState& /*s*/, double /*t*/) override { return StateVector(3, 1.0); }
  void derivative(const StateVector& y, StateVector& dy, double /*t*/, const StepWindow& /*window*/) override {
    ++rhs_evaluations;
    dy.resize(y.size());
    for (std::size_t q = 0; q < y.size(); ++q) dy[q] = -y[q];
  }
  void project(StateVector& /*y*/, double /*t*/) override {}
  double apply_tow_jump(StateVector& /*y*/, double /*t*/) override { return 0; }
  PhysicalState physical(const StateVector& /*y*/) const override { return {}; }
  const Workspace& evaluate(const StateVector& /*y*/, double /*t*/) override { throw std::logic_error("not used"); }
  std::string describe(std::size_t /*i*/) const override { return {}; }
  bool has_stage_solve() const override { return true; }
  void stage_solve(double hg, const StateVector& r, StateVector& k) override {
    k.resize(r.size());
    for (std::size_t q = 0; q < r.size(); ++q) k[q] = r[q] / (1 + hg);  // J = -I exactly
  }
  void start_side_forces(const StateVector& /*y_side*/, double /*t_side*/, const StepWindow& /*window*/,
                         EvaluationForces& /*side*/) override {
    calls += 's';
    worker_.start(side_throws ? &throwing_job : &quiet_job, this);
  }
  void finish_side_forces(const StateVector& y, StateVector& dy, double t, const StepWindow& window) override {
    calls += 'f';
    rhs_evaluations += 1;
    worker_.wait();  // the side's exception first, as serially
    derivative(y, dy, t, window);
  }
  void cancel_side_forces() noexcept override {
    calls += 'c';
    try {
      worker_.wait();
    } catch (...) {  // dropped, as DefaultSystem does
    }
  }

 private:
  static void throwing_job(void* /*self*/) { throw std::runtime_error("side evaluation failed"); }
  static void quiet_job(void* /*self*/) {}
  Worker worker_;
};

}  // namespace

// 200 elements and a 3 kg sphere in a turn (the turn from 5 s).
TEST(ConcurrentEvaluations, BodyInATurnIsBitIdentical) {
  const Model m = example_model("paper-3d-turn",
                                {"cable.elements=200", "simulation.duration=20", "simulation.tolerance=1e-4",
                                 "tow.motion=[{type: ramp, direction: [1, 0, 0], speed: 1.57, ramp_time: 5}, "
                                 "{type: turn, radius: 7.5, start_time: 5, side: port}]"});
  ASSERT_EQ(m.cable.n(), 200);
  expect_same_runs(m);
}

// An in-line depressor and an end fish: the link forces of two bodies in the
// force estimate (the turn from 5 s).
TEST(ConcurrentEvaluations, TwoBodiesAreBitIdentical) {
  const Model m = example_model("two-part-tow", {"simulation.duration=30",
                                                 "tow.motion=[{type: ramp, direction: [1, 0, 0], speed_kn: 5, "
                                                 "ramp_time: 0}, {type: turn, radius: 500, start_time: 5, "
                                                 "angle_deg: 90, side: starboard}]"});
  ASSERT_EQ(m.bodies.size(), 2u);
  expect_same_runs(m);
}

// A winch paying out 60 m: two split events, each a new system (and worker).
TEST(ConcurrentEvaluations, WinchEventsAreBitIdentical) {
  const Model m = example_model("fish-depth-change", {"simulation.duration=60",
                                                      "winch.rate=[[0, 0], [2, 0], [9, 1.4], [45, 1.4], [52, 0]]"});
  ASSERT_TRUE(m.winch.active());
  MemorySink sink;
  Model m2 = m;
  m2.sim.threads = 2;
  const RunStats st = simulate(m2, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_GT(sink.samples.back().deployed_length, sink.samples.front().deployed_length + 59);  // two 30 m splits
  expect_same_runs(m);
}

// A failing run (a tow at 1e150 m/s: the step size collapses) fails the same way.
TEST(ConcurrentEvaluations, FailureIsTheSame) {
  const Model m = example_model("paper-3d-turn", {"cable.elements=200", "simulation.duration=1",
                                                  "tow.motion=[{type: ramp, direction: [1, 0, 0], speed: 1e150, "
                                                  "ramp_time: 1}]"});
  Model serial = m;
  serial.sim.threads = 1;
  MemorySink sink;
  const RunStats st = simulate(serial, sink);
  ASSERT_EQ(st.status, "failed");
  EXPECT_NE(st.message.find("numerical failure at t = "), std::string::npos) << st.message;
  expect_same_runs(m);
}

// A non-finite embedded solution (what makes the force estimate reject the
// step) gives the same non-finite forces on the worker, and f(y1) the same.
TEST(ConcurrentEvaluations, NonFiniteSideEvaluationMatchesSerial) {
  Model m = example_model("paper-3d-turn", {"cable.elements=200"});
  m.sim.threads = 1;
  const auto serial = make_system(m);
  m.sim.threads = 2;
  const auto concurrent = make_system(m);
  ASSERT_EQ(serial->threads(), 1);
  ASSERT_EQ(concurrent->threads(), 2);
  const StateVector y = serial->initial(initial_state(m), 0.0);
  StateVector y_nan = y;
  y_nan[6 + 3 * 7] = std::numeric_limits<double>::quiet_NaN();  // element 8's e_x
  for (int pass = 0; pass < 2; ++pass) {                        // the worker's second job too
    StateVector dy1, dy2;
    EvaluationForces f1, f2;
    serial->derivative_with_side_forces(y, dy1, 0.5, y_nan, 0.5, StepWindow{}, f1);
    concurrent->derivative_with_side_forces(y, dy2, 0.5, y_nan, 0.5, StepWindow{}, f2);
    EXPECT_EQ(dy1, dy2);
    EXPECT_TRUE(std::isnan(f1.tow_force.norm()));
    EXPECT_TRUE(std::isnan(f2.tow_force.norm()));
    ASSERT_EQ(f1.link_force.size(), 1u);
    ASSERT_EQ(f2.link_force.size(), 1u);
    EXPECT_EQ(std::isnan(f1.link_force[0].norm()), std::isnan(f2.link_force[0].norm()));
    EXPECT_EQ(serial->last_accelerations()->tow_force, concurrent->last_accelerations()->tow_force);
  }
  EXPECT_EQ(serial->rhs_evaluations, 4);
  EXPECT_EQ(concurrent->rhs_evaluations, 4);
}

// Steps rejected after the speculative side evaluation started (dropped
// with threads 2, never run with threads 1): the same run. Rejections by
// the state error (the side evaluation started before it is known) and by
// the force error.
TEST(ConcurrentEvaluations, RejectedStepsAreBitIdentical) {
  const Model m = example_model("paper-3d-turn",
                                {"cable.elements=200", "simulation.duration=10", "simulation.tolerance=1e-3",
                                 "tow.motion=[{type: ramp, direction: [1, 0, 0], speed: 1.57, ramp_time: 2}, "
                                 "{type: turn, radius: 7.5, start_time: 2, side: port}]"});
  const RunStats serial = expect_same_runs(m);
  EXPECT_EQ(serial.status, "ok") << serial.message;
  EXPECT_GT(serial.rejected_steps, 0);
}

// A cancelled side evaluation leaves nothing behind: not counted, the next
// pair the same as serially (the worker takes the next job).
TEST(ConcurrentEvaluations, CancelledSideEvaluationLeavesNoTrace) {
  Model m = example_model("paper-3d-turn", {"cable.elements=200"});
  m.sim.threads = 1;
  const auto serial = make_system(m);
  m.sim.threads = 2;
  const auto concurrent = make_system(m);
  const StateVector y = serial->initial(initial_state(m), 0.0);
  StateVector y_nan = y;
  y_nan[6 + 3 * 7] = std::numeric_limits<double>::quiet_NaN();
  StateVector dy1, dy2;
  EvaluationForces f1, f2;
  for (System* sys : {serial.get(), concurrent.get()}) {
    EvaluationForces dropped;
    sys->start_side_forces(y_nan, 0.5, StepWindow{}, dropped);
    sys->cancel_side_forces();
    EXPECT_EQ(sys->rhs_evaluations, 0);
  }
  serial->derivative_with_side_forces(y, dy1, 0.5, y, 0.25, StepWindow{}, f1);
  concurrent->derivative_with_side_forces(y, dy2, 0.5, y, 0.25, StepWindow{}, f2);
  EXPECT_EQ(dy1, dy2);
  EXPECT_EQ(f1.tow_force, f2.tow_force);
  EXPECT_EQ(f1.link_force, f2.link_force);
  EXPECT_EQ(serial->rhs_evaluations, 2);
  EXPECT_EQ(concurrent->rhs_evaluations, 2);
}

// The step-end protocol: the side evaluation starts before the step's error
// is known; a rejected step cancels it and what it threw is dropped (as
// serially, where a rejected step never evaluates it); an accepted step
// finishes it and its exception comes out of try_step.
TEST(ConcurrentEvaluations, SpeculativeSideExceptionOnlyWhenAccepted) {
  DecaySystem sys;
  sys.side_throws = true;
  RosenbrockW ros(sys, 1e-6, 1.0);
  StateVector y = sys.initial(PhysicalState{}, 0.0);
  double t = 0, h = 1.0;  // far too large for tol 1e-6: rejected by the state error
  EXPECT_FALSE(ros.try_step(y, t, h));
  EXPECT_EQ(sys.calls, "sc");
  EXPECT_EQ(t, 0.0);
  EXPECT_LT(h, 1.0);
  h = 1e-3;  // local error ~1e-10: accepted, so the side evaluation is finished and throws
  EXPECT_THROW(ros.try_step(y, t, h), std::runtime_error);
  EXPECT_EQ(sys.calls, "scsf");
  sys.side_throws = false;  // the worker takes the next job
  h = 1e-3;
  EXPECT_TRUE(ros.try_step(y, t, h));
  EXPECT_EQ(sys.calls, "scsfsf");
  EXPECT_EQ(t, 1e-3);
}

// An exception in the worker's job comes out of wait(), on the caller's
// thread; the worker takes the next job.
TEST(Worker, CarriesExceptionsAndGoesOn) {
  Worker w;
  int ran = 0;
  w.start([](void*) { throw std::runtime_error("side evaluation failed"); }, nullptr);
  try {
    w.wait();
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "side evaluation failed");
  }
  for (int i = 0; i < 5000; ++i) {  // many hand-offs: a lost wake-up would hang here
    w.start([](void* c) { ++*static_cast<int*>(c); }, &ran);
    w.wait();
  }
  EXPECT_EQ(ran, 5000);
}

// A wait for a job that runs long after the owner got there is a stall
// (what DefaultSystem counts to do without a worker that has no core); a
// wait for a job already done is not. The slow job sleeps 20 ms, 20 times
// kStallWait (1 ms): a stall whatever the machine's load. The owner gets to
// the quick job's wait (an increment) after sleeping 50 ms itself: more than
// a scheduler's latency with a few runnable threads per core (~12 ms), so
// the helper has run it by then.
TEST(Worker, CountsWaitsAndStalls) {
  Worker w;
  EXPECT_EQ(w.waits(), 0);
  EXPECT_EQ(w.stalls(), 0);
  w.start([](void*) { std::this_thread::sleep_for(std::chrono::milliseconds(20)); }, nullptr);
  w.wait();
  EXPECT_EQ(w.waits(), 1);
  EXPECT_EQ(w.stalls(), 1);
  int ran = 0;
  w.start([](void* c) { ++*static_cast<int*>(c); }, &ran);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  w.wait();
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(w.waits(), 2);
  EXPECT_EQ(w.stalls(), 1);
}

// auto: a worker from kAutoThreadsElements elements (two hardware threads),
// only with rosenbrock; an explicit count >= 2 runs as 2.
TEST(ConcurrentEvaluations, AutoRule) {
  Model m = example_model("paper-3d-turn", {"cable.elements=1000"});
  ASSERT_EQ(m.sim.threads, 0);  // absent: auto
  ASSERT_EQ(m.sim.integrator, Integrator::Rosenbrock);
  const int hw = std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  EXPECT_EQ(evaluation_threads(m), hw);
  EXPECT_EQ(evaluation_threads(example_model("paper-3d-turn", {"cable.elements=299"})), 1);
  EXPECT_EQ(evaluation_threads(example_model("paper-3d-turn", {})), 1);  // 10 elements
  m.sim.threads = 8;
  EXPECT_EQ(evaluation_threads(m), 2);
  m.sim.integrator = Integrator::RK4;
  EXPECT_EQ(evaluation_threads(m), 1);
}

using ThreadsKey = towsim::testing::ScenarioFiles;

TEST_F(ThreadsKey, ParsedAndChecked) {
  using towsim::testing::kCable;
  using towsim::testing::kSim;
  EXPECT_EQ(load(kCable + kSim).model->sim.threads, 0);
  EXPECT_EQ(load(kCable + kSim + "  threads: auto\n").model->sim.threads, 0);
  EXPECT_EQ(load(kCable + kSim + "  threads: 3\n").model->sim.threads, 3);
  auto s = load(kCable + kSim + "  threads: two\n");
  EXPECT_EQ(s.diags.str(), at("8:12: simulation.threads: expected an integer >= 1 or auto (got 'two')"));
  s = load(kCable + kSim + "  threads: 0\n");
  EXPECT_EQ(s.diags.str(), at("8:12: simulation.threads: expected an integer >= 1 or auto (got '0')"));
  s = load(kCable + kSim, {"simulation.threads=-2"});
  EXPECT_EQ(s.diags.str(), "--set:1:20: simulation.threads: expected an integer >= 1 or auto (got '-2')\n");
}

// ---- Loads split between the worker and the caller ---------

namespace {

/// Models of every kind of part with kSplitLoadsElements or more elements
/// (the split runs): a sphere in a turn, an elastic cable in a current, an
/// imposed winch, an in-line body with attachments, a seabed.
std::vector<std::pair<std::string, Model>> split_cases() {
  constexpr int kN = 240;  // elements [-]: >= kSplitLoadsElements, odd halves (120, 120) not required
  std::vector<std::pair<std::string, Model>> out;
  towsim::testing::CableSpec spec;
  spec.n = kN;
  spec.length = 300;
  spec.mass_per_length = 0.14;
  spec.diameter = 0.010;
  spec.cd = 1.9;
  {
    Model m = towsim::testing::cable_model(spec);
    towsim::testing::add_sphere_body(m);
    m.tow.pieces.push_back(towsim::testing::ramp_piece(Vec3::UnitX(), 1.57, 15));
    m.tow.pieces.push_back(towsim::testing::turn_piece(7.5, 15));
    out.emplace_back("sphere in a turn", m);
  }
  {
    Model m = towsim::testing::cable_model(spec);
    for (Element& el : m.cable.elements) el.axial_stiffness = 2e5, el.axial_damping = 1e3;
    towsim::testing::add_sphere_body(m);
    m.fluid.current_depth = {0.0, 10.0, 50.0};
    m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.5, 0.1, 0), Vec3(0.1, -0.2, 0)};
    m.tow.pieces.push_back(towsim::testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.emplace_back("elastic cable", m);
  }
  {
    Model m = towsim::testing::cable_model(spec);
    towsim::testing::add_sphere_body(m);
    towsim::testing::impose_winch(m, spec.n, spec.length, {0.0}, {0.5});
    m.tow.pieces.push_back(towsim::testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.emplace_back("winch", m);
  }
  {
    Model m = towsim::testing::two_part_model(kN / 2, kN / 2);
    m.tow.pieces.push_back(towsim::testing::ramp_piece(Vec3::UnitX(), 1.5, 30));
    out.emplace_back("in-line body and attachments", m);
  }
  {
    Model m = towsim::testing::cable_model(spec);
    m.seabed = Seabed::flat(2.0, 1e5, 1e3, 0.5);  // random states cross it
    m.tow.pieces.push_back(towsim::testing::ramp_piece(Vec3::UnitX(), 0.5, 0));
    out.emplace_back("seabed", m);
  }
  return out;
}

/// Every load and result of two evaluations equal bit for bit.
void expect_same_evaluation(const Workspace& a, const Workspace& b) {
  for (std::size_t k = 0; k < a.F.size(); ++k) {
    ASSERT_EQ(a.F[k], b.F[k]) << "element " << k;
    ASSERT_EQ(a.Mom[k], b.Mom[k]) << "element " << k;
    ASSERT_EQ(a.Mt[k], b.Mt[k]) << "element " << k;
    ASSERT_EQ(a.elastic[k].T, b.elastic[k].T) << "element " << k;
    ASSERT_EQ(a.acc.alpha[k], b.acc.alpha[k]) << "element " << k;
    ASSERT_EQ(a.acc.length_acc[k], b.acc.length_acc[k]) << "element " << k;
  }
  for (std::size_t k = 0; k < a.Fa.size(); ++k) {
    ASSERT_EQ(a.Fa[k], b.Fa[k]) << "joint " << k;
    ASSERT_EQ(a.Fs[k], b.Fs[k]) << "joint " << k;
    ASSERT_EQ(a.acc.joint_force[k], b.acc.joint_force[k]) << "joint " << k;
  }
  for (std::size_t q = 0; q < a.body.size(); ++q) {
    EXPECT_EQ(a.body[q].Fb, b.body[q].Fb);
    EXPECT_EQ(a.body[q].Mb, b.body[q].Mb);
    EXPECT_EQ(a.acc.alpha_b[q], b.acc.alpha_b[q]);
    EXPECT_EQ(a.acc.link_force[q], b.acc.link_force[q]);
    EXPECT_EQ(a.acc.lower_link_force[q], b.acc.lower_link_force[q]);
  }
  EXPECT_EQ(a.acc.a0, b.acc.a0);
  EXPECT_EQ(a.acc.tow_force, b.acc.tow_force);
  EXPECT_EQ(a.acc.top_length_acc, b.acc.top_length_acc);
}

}  // namespace

// forward_dynamics and forward_dynamics_time_shift with the worker as their
// Fork against the same without (nullptr): every load and result the same,
// on random states (elements anywhere, the seabed crossed); and with a job
// of the owner's pending, the pair runs on the caller alone, the same.
TEST(ConcurrentEvaluations, SplitLoadsEqualSerialEvaluation) {
  std::mt19937 rng(21);
  Worker worker;
  constexpr double kT = 20, kDt = 1e-4;  // on the turn; f_t's shift [s]
  for (auto& [name, m] : split_cases()) {
    SCOPED_TRACE(name);
    ASSERT_GE(m.cable.elements.size(), kSplitLoadsElements);
    for (int r = 0; r < 3; ++r) {
      PhysicalState s = towsim::testing::random_state(m, rng);
      if (m.winch.active()) s.length[0] = 0.7 * m.cable.elements[0].length;
      Workspace serial(m), split(m), shifted(m), shifted_split(m);
      forward_dynamics(m, s, kT, serial);
      forward_dynamics(m, s, kT, split, &worker);
      expect_same_evaluation(serial, split);
      forward_dynamics_time_shift(m, s, kT + kDt, serial, shifted);
      forward_dynamics_time_shift(m, s, kT + kDt, serial, shifted_split, &worker);
      expect_same_evaluation(shifted, shifted_split);
      // The worker busy with a job of its owner's: both halves here.
      int ran = 0;
      worker.start([](void* c) { ++*static_cast<int*>(c); }, &ran);
      Workspace busy(m);
      forward_dynamics(m, s, kT, busy, &worker);
      worker.wait();
      EXPECT_EQ(ran, 1);
      expect_same_evaluation(serial, busy);
    }
  }
}

// Whole runs with threads 1 and 2, the loads split at every evaluation with
// no side evaluation pending: an elastic cable with a sled in a turn, a
// cable dragged on the bottom with an attachment, an in-line depressor with
// attachments, a winch paying out (the split events' new systems).
TEST(ConcurrentEvaluations, SplitLoadsRunsAreBitIdentical) {
  const std::string sled = R"(name: elastic-sled
environment: {water_density: 1025, gravity: 9.81}
cable:
  length: 1000
  elements: 200
  mass_per_length: 1.12
  diameter: 0.0173
  normal_drag: 1.5
  tangential_drag: {law: skin, ct: 0.01}
  added_mass: 1.0
  axial_stiffness: 1.27e7
body:
  mass: 1135
  inertia: [61.5, 61.5, 61.5]
  link_point: [0, 0, 0.368]
  volume: 0.2336
  spheres:
    - {center: [0, 0, 0], radius: 0.368, drag: 0.77, added_mass: 0.5}
tow:
  mode: motion
  motion:
    - {type: ramp, direction: [1, 0, 0], speed: 3.084, ramp_time: 0}
    - {type: turn, radius: 294.5, start_time: 1, angle_deg: 360, side: port}
initial: steady
simulation: {duration: 3, time_step: 0.01, integrator: rosenbrock, tolerance: 1.0e-4, output_interval: 0.5}
)";
  expect_same_runs(text_model(sled));
  const std::string dragged = R"(name: dragged
environment:
  water_density: 1025
  gravity: 9.81
  seabed: {depth: 110, stiffness: 1.0e5, damping: 1.0e3, friction: 0.5}
cable:
  length: 400
  elements: 200
  mass_per_length: 1.5
  diameter: 0.019
  normal_drag: 1.8
  tangential_drag: {law: pode, f: 0.0}
  added_mass: 1.0
  added_mass_model: ideal_fluid
  attachments:
    - {at: 100, mass: 50, volume: 0.005, drag_area: 0.1, added_mass: 10}
tow:
  mode: motion
  motion:
    - {type: ramp, direction: [1, 0, 0], speed: 0.5, ramp_time: 0}
    - {type: turn, radius: 100, start_time: 0.5, angle_deg: 90, side: port}
initial: steady
simulation: {duration: 2, time_step: 0.01, integrator: rosenbrock, tolerance: 1.0e-4, output_interval: 0.5}
)";
  const Model seabed = text_model(dragged);
  ASSERT_TRUE(seabed.seabed.has_value());
  ASSERT_EQ(seabed.cable.attachments.size(), 1u);
  expect_same_runs(seabed);
  // two-part-tow's sections at 150 and 60 elements.
  const scenario::Example* ex = scenario::find_example("two-part-tow");
  ASSERT_NE(ex, nullptr);
  std::string two_yaml = ex->yaml;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"elements: 30,", "elements: 150,"},
                                 std::pair<std::string, std::string>{"elements: 10,", "elements: 60,"}}) {
    const std::size_t at = two_yaml.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    two_yaml.replace(at, from.size(), to);
  }
  const std::size_t cable = two_yaml.find("\ncable:\n");
  ASSERT_NE(cable, std::string::npos);
  two_yaml.insert(cable + 8,
                  "  attachments:\n    - {at: 300, mass: 50, volume: 0.005, drag_area: 0.1, added_mass: 10}\n"
                  "    - {at: 1000, mass: 20, volume: 0.01, drag_area: 0.05, added_mass: 5}\n");
  const Model two = text_model(two_yaml, {"simulation.duration=4",
                                          "tow.motion=[{type: ramp, direction: [1, 0, 0], speed_kn: 5, ramp_time: 0}, "
                                          "{type: turn, radius: 500, start_time: 1, angle_deg: 90, side: starboard}]"});
  ASSERT_GE(two.cable.elements.size(), kSplitLoadsElements);
  ASSERT_EQ(two.cable.attachments.size(), 2u);
  expect_same_runs(two);
  const Model winch = example_model("fish-depth-change", {"cable.elements=200", "simulation.duration=10",
                                                          "winch.rate=[[0, 0], [1, 0], [7, 1.2], [10, 1.2]]"});
  ASSERT_TRUE(winch.winch.active());
  expect_same_runs(winch);
}
