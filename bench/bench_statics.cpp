// Cost of the steady solve (towsim statics, initial: steady) versus the
// number of elements n (docs/performance.md "Statics vs n"). A 1000 m cable
// (the benchmark cable's per-metre values, Pode f = 0.02) towed at 2 m/s:
//
//   statics/cable          uniform still water
//   statics/sphere         with the paper-5.2 sphere at the end
//   statics/sphere_shear   with the sphere, in a sheared current profile
//                          (0.5 m/s across the tow at the surface, 0 at 300 m):
//                          the sweeps repeat while the depths move
#include <benchmark/benchmark.h>

#include "models.hpp"  // tests/support: cable_model, paper52_cable, add_sphere_body
#include "towsim/sim/statics.hpp"

namespace {

using namespace towsim;

Model statics_model(int n, bool body, bool shear) {
  Model m = testing::cable_model(testing::paper52_cable(n, 1000, 0.02));
  if (body) testing::add_sphere_body(m);
  if (shear) {
    m.fluid.current_depth = {0, 300};
    m.fluid.current_velocity = {Vec3(0, 0.5, 0), Vec3::Zero()};
  }
  return m;
}

void BM_statics(benchmark::State& state, bool body, bool shear) {
  const int n = static_cast<int>(state.range(0));
  const Model m = statics_model(n, body, shear);
  int iterations = 0;
  bool converged = true;
  for (auto _ : state) {
    const StaticsResult r = solve_statics(m, Vec3(2.0, 0, 0));
    iterations = r.iterations;
    converged = converged && r.converged;
    benchmark::DoNotOptimize(r.tow_force);
  }
  if (!converged) state.SkipWithError("statics did not converge");
  state.counters["sweeps"] = iterations;
  state.SetComplexityN(n);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {100, 1000, 10000}) b->Arg(n);
  b->Complexity(benchmark::oN)->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  sizes(benchmark::RegisterBenchmark("statics/cable", BM_statics, false, false));
  sizes(benchmark::RegisterBenchmark("statics/sphere", BM_statics, true, false));
  sizes(benchmark::RegisterBenchmark("statics/sphere_shear", BM_statics, true, true));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
