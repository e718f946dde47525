// The worker thread of simulation.threads (docs/performance.md "Concurrent
// step-end evaluations").
//
//   worker_round_trip        start() + wait() of an empty job: the hand-off's
//                            latency (both sides spin first, then block)
//   step_end_pair/<n>/<th>   System::derivative_with_side_forces at n elements
//                            (a hanging cable with a sphere, a tow at 1.5 m/s):
//                            th = 1 the two evaluations one after the other,
//                            th = 2 the side one on the worker
//   evaluation/<n>/<fork>    forward_dynamics at n elements (the same cable):
//                            fork = 0 serial, 1 with the worker as its Fork
//                            (half of the elements' loads on it from
//                            kSplitLoadsElements elements; docs/performance.md
//                            "Loads on two threads")
#include <benchmark/benchmark.h>

#include "models.hpp"   // tests/support
#include "physics.hpp"  // tests/support
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/integrators/worker.hpp"

namespace {

using namespace towsim;

void worker_round_trip(benchmark::State& st) {
  Worker w;
  int jobs = 0;
  for (auto _ : st) {
    w.start([](void* c) { ++*static_cast<int*>(c); }, &jobs);
    w.wait();
  }
  benchmark::DoNotOptimize(jobs);
}
BENCHMARK(worker_round_trip)->UseRealTime();

/// A hanging cable of n 1 m elements with a 100 kg sphere, towed at 1.5 m/s.
Model towed_cable(int n) {
  towsim::testing::CableSpec spec;
  spec.n = n;
  spec.length = static_cast<double>(spec.n);
  Model m = towsim::testing::cable_model(spec);
  towsim::testing::add_sphere_body(m, 100.0, 0.3, 0.5);
  m.tow.pieces.push_back(towsim::testing::ramp_piece(Vec3::UnitX(), 1.5, 0));
  m.sim.integrator = Integrator::Rosenbrock;
  return m;
}

void step_end_pair(benchmark::State& st) {
  Model m = towed_cable(static_cast<int>(st.range(0)));
  m.sim.threads = static_cast<int>(st.range(1));
  const auto sys = make_system(m);
  const StateVector y = sys->initial(initial_state(m), 0.0);
  StateVector y_side = y, dy;
  for (std::size_t i = 6; i < y_side.size(); ++i) y_side[i] *= 1 + 1e-9;  // another state
  EvaluationForces side;
  for (auto _ : st) {
    sys->derivative_with_side_forces(y, dy, 1.0, y_side, 1.0, StepWindow{}, side);
    benchmark::DoNotOptimize(dy.data());
  }
  st.counters["threads"] = sys->threads();
}
BENCHMARK(step_end_pair)->ArgsProduct({{50, 200, 1000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMicrosecond);

void evaluation(benchmark::State& st) {
  const Model m = towed_cable(static_cast<int>(st.range(0)));
  const PhysicalState s = initial_state(m);
  Workspace ws(m);
  Worker worker;
  Fork* fork = st.range(1) != 0 ? &worker : nullptr;
  for (auto _ : st) {
    forward_dynamics(m, s, 1.0, ws, fork);
    benchmark::DoNotOptimize(ws.acc.tow_force.data());
  }
}
BENCHMARK(evaluation)->ArgsProduct({{100, 200, 300, 500, 1000}, {0, 1}})->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
