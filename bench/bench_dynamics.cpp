// Cost of one evaluation of the dynamics versus the number of elements n
// (docs/performance.md "Cost of one evaluation vs n").
//
//   forward_dynamics/{cable,sphere}  the default O(n) recursion
//   paper_dynamics/{cable,sphere}    the paper's dense Lagrange form (n <= 300:
//                                    its assembly is O(n^3) and 1000 elements
//                                    take seconds per evaluation)
//   stage_factor/{cable,sphere}      the rosenbrock integrator's factorisation
//                                    of M + hg C + hg^2 K (implicit_factor: the
//                                    backward pass with modified inertias), once
//                                    per step, hg = 0.1 s
//   stage_solve/{cable,sphere}       one linear stage solve with it
//                                    (implicit_stage_solve), 5 per step
//   baseline_step/cable              one step of the earlier formulation
//                                    (bench/baseline: Cartesian joints,
//                                    multipliers, central differences)
//
// "sphere" = with the paper-5.2 towed body (3 kg sphere, r 0.05 m, link on
// its surface). States are random (unit vectors anywhere, rates 0.5 rad/s),
// the tow point on its imposed motion at t = 3.7 s. The fitted exponent of
// cost vs n over 100..1000 is computed by bench/fit_exponent.py from this
// program's JSON output.
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "baseline/cartesian.hpp"
#include "models.hpp"  // tests/support: cable_model, add_sphere_body, random_state
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/paper.hpp"

namespace {

using namespace towsim;

constexpr double kTime = 3.7;

/// The benchmark cable: paper 5.2 per-metre values, 10 m elements, Pode f = 0.02.
Model bench_model(int n, bool body) {
  Model m = testing::cable_model(testing::paper52_cable(n, 10.0 * n, 0.02));
  if (body) testing::add_sphere_body(m);
  m.tow.pieces.push_back(Ramp{Vec3(1, 0, 0), 1.57, 15.0});
  return m;
}

PhysicalState bench_state(const Model& m) {
  std::mt19937 rng(42);
  PhysicalState s = testing::random_state(m, rng);
  const TowKinematics k = tow_kinematics(m.tow, kTime);
  s.r0 = k.pos;
  s.v0 = k.vel;
  return s;
}

void BM_forward(benchmark::State& state, bool body) {
  const int n = static_cast<int>(state.range(0));
  const Model m = bench_model(n, body);
  const PhysicalState s = bench_state(m);
  Workspace ws(m);
  for (auto _ : state) {
    forward_dynamics(m, s, kTime, ws);
    benchmark::DoNotOptimize(ws.acc.tow_force.data());
    benchmark::ClobberMemory();
  }
  state.SetComplexityN(n);
  state.counters["s_per_element"] = benchmark::Counter(static_cast<double>(n),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

void BM_paper(benchmark::State& state, bool body) {
  const int n = static_cast<int>(state.range(0));
  const Model m = bench_model(n, body);
  const PaperState p = to_paper(m, bench_state(m));
  PaperWorkspace pw(m);
  for (auto _ : state) {
    paper_dynamics(m, p, kTime, pw);
    benchmark::DoNotOptimize(pw.acc.tow_force.data());
    benchmark::ClobberMemory();
  }
  state.SetComplexityN(n);
  state.counters["s_per_element"] = benchmark::Counter(static_cast<double>(n),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

void BM_stage(benchmark::State& state, bool body, bool factor) {
  const int n = static_cast<int>(state.range(0));
  const Model m = bench_model(n, body);
  const PhysicalState s = bench_state(m);
  Workspace ws(m);
  forward_dynamics(m, s, kTime, ws);
  ImplicitWorkspace iw(m);
  local_jacobian(m, s, ws, kTime, iw.jac);
  StageRhs r;  // an arbitrary right-hand side
  r.dv0 = Vec3(0.1, 0, 0);
  for (int k = 0; k < n; ++k) r.dw.push_back(0.01 * s.w[k]), r.rot.push_back(0.001 * s.w[k]);
  r.dwb.assign(m.bodies.size(), Vec3(0.01, 0, 0));
  r.rotb.assign(m.bodies.size(), Vec3(0.001, 0, 0));
  implicit_factor(m, s, ws, 0.1, iw);
  for (auto _ : state) {
    if (factor)
      implicit_factor(m, s, ws, 0.1, iw);
    else
      implicit_stage_solve(m, s, ws, 0.1, r, iw);
    benchmark::DoNotOptimize(iw.alpha.data());
    benchmark::ClobberMemory();
  }
  state.SetComplexityN(n);
  state.counters["s_per_element"] = benchmark::Counter(static_cast<double>(n),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

/// One explicit step of the earlier formulation (assembly of loads and the
/// consistent mass, the O(n) saddle-point solve, the update). Restarted from
/// the hanging cable every 256 steps (h = 1 ms) so the state stays physical.
void BM_baseline(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = bench_model(n, false);
  m.cable.added_mass_model = AddedMassModel::Morison;
  const baseline::Chain chain = baseline::cable_chain(m);
  std::vector<Vec3> x0(n + 1, Vec3::Zero());
  for (int k = 1; k <= n; ++k) x0[k] = x0[k - 1] - m.cable.elements[k - 1].length * Vec3::UnitZ();
  baseline::CentralDifference cd(chain, 1e-3);
  cd.start(x0);
  long i = 0;
  for (auto _ : state) {
    if ((++i & 255) == 0) cd.start(x0);
    benchmark::DoNotOptimize(cd.step());
  }
  state.SetComplexityN(n);
  state.counters["s_per_element"] = benchmark::Counter(static_cast<double>(n),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

void sizes(benchmark::internal::Benchmark* b, int max_n) {
  for (int n : {10, 30, 100, 300, 1000})
    if (n <= max_n) b->Arg(n);
  b->Complexity(benchmark::oAuto)->Unit(benchmark::kNanosecond);
}

}  // namespace

int main(int argc, char** argv) {
  sizes(benchmark::RegisterBenchmark("forward_dynamics/cable", BM_forward, false), 1000);
  sizes(benchmark::RegisterBenchmark("forward_dynamics/sphere", BM_forward, true), 1000);
  sizes(benchmark::RegisterBenchmark("paper_dynamics/cable", BM_paper, false), 300);
  sizes(benchmark::RegisterBenchmark("paper_dynamics/sphere", BM_paper, true), 300);
  sizes(benchmark::RegisterBenchmark("stage_factor/cable", BM_stage, false, true), 1000);
  sizes(benchmark::RegisterBenchmark("stage_factor/sphere", BM_stage, true, true), 1000);
  sizes(benchmark::RegisterBenchmark("stage_solve/cable", BM_stage, false, false), 1000);
  sizes(benchmark::RegisterBenchmark("stage_solve/sphere", BM_stage, true, false), 1000);
  sizes(benchmark::RegisterBenchmark("baseline_step/cable", BM_baseline), 1000);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
