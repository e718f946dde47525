// simulation.threads (docs/performance.md "Concurrent step-end evaluations
// (h-pareval)"): the rosenbrock step's two final evaluations on two threads
// give the same run, bit for bit, as on one; the worker hands exceptions
// back; the key's checks and its auto rule.
//
// Exact comparisons (EXPECT_EQ on doubles) are right here: with a worker the
// same evaluations run on the same inputs in the same order of operations,
// only on another core and another Workspace of the same model; every
// evaluation rewrites what it reads of its Workspace. Any difference, even
// in the last bit, would mean state shared between the two evaluations.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "../support/scenario_files.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/integrators/worker.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"

namespace {

using namespace towsim;

/// A built-in example with --set overrides, compiled.
Model example_model(const std::string& name, const std::vector<std::string>& sets) {
  const io::Example* e = io::find_example(name);
  EXPECT_NE(e, nullptr) << name;
  if (e == nullptr) return Model{};
  io::LoadedScenario sc = io::load_scenario_text(e->yaml, name + ".yaml", name, "", sets);
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
  void derivative(const StateVector& y, StateVector& dy, double /*t*/) override {
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
  void start_side_forces(const StateVector& /*y_side*/, double /*t_side*/, EvaluationForces& /*side*/) override {
    calls += 's';
    worker_.start(side_throws ? &throwing_job : &quiet_job, this);
  }
  void finish_side_forces(const StateVector& y, StateVector& dy, double t) override {
    calls += 'f';
    rhs_evaluations += 1;
    worker_.wait();  // the side's exception first, as serially
    derivative(y, dy, t);
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
    serial->derivative_with_side_forces(y, dy1, 0.5, y_nan, 0.5, f1);
    concurrent->derivative_with_side_forces(y, dy2, 0.5, y_nan, 0.5, f2);
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
    sys->start_side_forces(y_nan, 0.5, dropped);
    sys->cancel_side_forces();
    EXPECT_EQ(sys->rhs_evaluations, 0);
  }
  serial->derivative_with_side_forces(y, dy1, 0.5, y, 0.25, f1);
  concurrent->derivative_with_side_forces(y, dy2, 0.5, y, 0.25, f2);
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

// auto: a worker from kAutoThreadsElements elements (two hardware threads),
// only with rosenbrock; an explicit count >= 2 runs as 2.
TEST(ConcurrentEvaluations, AutoRule) {
  Model m = example_model("paper-3d-turn", {"cable.elements=1000"});
  ASSERT_EQ(m.sim.threads, 0);  // absent: auto
  ASSERT_EQ(m.sim.integrator, Integrator::Rosenbrock);
  const int hw = std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  EXPECT_EQ(evaluation_threads(m), hw);
  EXPECT_EQ(evaluation_threads(example_model("paper-3d-turn", {"cable.elements=999"})), 1);
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
