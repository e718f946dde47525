// Networks of lines (docs/performance.md "Networks"): the cost of one
// evaluation of a tree against the chain of as many elements, and the
// whole run of a four-line rig of 4000 elements.
//
//   network/tree_evaluation/N    four lines of N/4 elements (a root to a
//                                junction, a free line and a line to a
//                                sphere below it, a free line from the
//                                sphere's bottom to a small sphere): tree_forward_dynamics
//   network/chain_evaluation/N   one chain of N elements: forward_dynamics
//   network/rig_run              the rig below, 600 s towed at 2 m/s
//                                (rosenbrock at its default tolerance), once; the
//                                counter x_real_time = simulated / wall time
//   network/rig_part_run/P       a part of the rig towed alone, the same way:
//                                P = 0 the main line, 1 the line to the 200 kg
//                                sphere, 2 that line with its tail (the steps
//                                each part needs on its own)
//
// The rig: a 1200 m main tow (1200 elements of 1 m, the km-cable-1000
// cable) to a 300 kg junction (a depressor's shackle), an 800 m sensor
// line (800 elements) to the paper-5.2 sphere, a 1000 m line to a 200 kg
// sphere (1000 elements), and a 1000 m tail from the sphere's bottom to
// another paper-5.2 sphere; hanging at rest, then towed at 2 m/s (reached
// in 30 s) for 600 s.
#include <benchmark/benchmark.h>

#include <chrono>

#include "models.hpp"  // tests/support: cable_model, paper52_cable, add_sphere_body
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/tree.hpp"
#include "towsim/integrators/network_system.hpp"
#include "towsim/sim/simulate_network.hpp"

namespace {

using namespace towsim;

/// The rig with line lengths (and element counts, 1 m elements) n0..n3.
Network rig(int n0, int n1, int n2, int n3) {
  const auto line = [](int n) { return testing::cable_model(testing::paper52_cable(n, n)); };
  Model main = line(n0);
  Attachment junction;
  junction.joint = n0, junction.at = n0, junction.mass = 300, junction.volume = 0.04, junction.drag_area = 0.3;
  main.cable.attachments.push_back(junction);
  main.tow.pieces.push_back(Ramp{Vec3::UnitX(), 2.0, 30});
  Model fish = line(n2);
  testing::add_sphere_body(fish, 200, 0.3);
  // The sensor line and the tail end in small spheres (a free end of light
  // 1 m elements whips: steps of milliseconds, docs/performance.md "Networks").
  Model sensor = line(n1), tail = line(n3);
  testing::add_sphere_body(sensor);
  testing::add_sphere_body(tail);
  Network net;
  net.name = "rig";
  net.tree.lines = {main, sensor, fish, tail};
  net.tree.tops = {LineTop{}, LineTop{0, -1, Vec3::Zero()}, LineTop{0, -1, Vec3::Zero()},
                   LineTop{2, 0, Vec3(0, 0, -0.3)}};
  net.line_names = {"main", "sensor", "fish", "tail"};
  for (Model& m : net.tree.lines) {
    m.sim.integrator = Integrator::Rosenbrock;
    m.sim.tolerance = default_tolerance(Integrator::Rosenbrock);
    m.sim.duration = 600;
    m.sim.output_interval = 1;
    m.sim.max_step = std::numeric_limits<double>::infinity();
  }
  return net;
}

void BM_tree_evaluation(benchmark::State& state) {
  const int q = static_cast<int>(state.range(0)) / 4;
  const Network net = rig(q, q, q, q);
  const TreeState s = network_initial_state(net);
  TreeWorkspace ws(net.tree);
  for (auto _ : state) {
    tree_forward_dynamics(net.tree, s, 1.0, ws);
    benchmark::DoNotOptimize(ws.lines.front().acc.tow_force);
  }
  state.SetComplexityN(state.range(0));
}

void BM_chain_evaluation(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = testing::cable_model(testing::paper52_cable(n, n));
  testing::add_sphere_body(m);
  const PhysicalState s = PhysicalState::hanging(m);
  Workspace ws(m);
  for (auto _ : state) {
    forward_dynamics(m, s, 1.0, ws);
    benchmark::DoNotOptimize(ws.acc.tow_force);
  }
  state.SetComplexityN(n);
}

/// Keeps only the count of samples.
struct CountingSink : NetworkSink {
  long samples = 0;
  void write(const NetworkSample&) override { ++samples; }
  void flush() override {}
};

/// The network's run once, its counters into `state`.
void run_once(benchmark::State& state, const Network& net) {
  RunStats stats;
  double wall = 0;
  for (auto _ : state) {
    CountingSink sink;
    const auto t0 = std::chrono::steady_clock::now();
    stats = simulate_network(net, sink);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (stats.status != "ok") state.SkipWithError(stats.message.c_str());
  state.counters["x_real_time"] = net.settings().sim.duration / wall;
  state.counters["steps"] = static_cast<double>(stats.steps);
  state.counters["rhs_evaluations"] = static_cast<double>(stats.rhs_evaluations);
}

void BM_rig_run(benchmark::State& state) { run_once(state, rig(1200, 800, 1000, 1000)); }

/// Part P of the rig alone (see the header), towed as the rig's main line is.
void BM_rig_part_run(benchmark::State& state) {
  const Network full = rig(1200, 800, 1000, 1000);
  Network part = full;
  const Tow& tow = full.tree.lines[0].tow;
  switch (state.range(0)) {
    case 0:  // the main line (its junction at its end)
      part.tree.lines = {full.tree.lines[0]};
      part.tree.tops = {LineTop{}};
      break;
    case 1:  // the line to the 200 kg sphere
      part.tree.lines = {full.tree.lines[2]};
      part.tree.tops = {LineTop{}};
      break;
    default:  // that line with its tail
      part.tree.lines = {full.tree.lines[2], full.tree.lines[3]};
      part.tree.tops = {LineTop{}, LineTop{0, 0, full.tree.tops[3].point}};
      break;
  }
  part.tree.lines[0].tow = tow;
  part.line_names.resize(part.tree.lines.size());
  run_once(state, part);
}

}  // namespace

int main(int argc, char** argv) {
  for (auto* b : {benchmark::RegisterBenchmark("network/tree_evaluation", BM_tree_evaluation),
                  benchmark::RegisterBenchmark("network/chain_evaluation", BM_chain_evaluation)})
    b->Arg(400)->Arg(4000)->Complexity(benchmark::oN)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("network/rig_run", BM_rig_run)->Iterations(1)->Unit(benchmark::kSecond);
  benchmark::RegisterBenchmark("network/rig_part_run", BM_rig_part_run)
      ->DenseRange(0, 2)
      ->Iterations(1)
      ->Unit(benchmark::kSecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
