// Cost of the wave kinematics and of the dynamics in waves (issue 14).
//
//   wave_point/<depth>       velocity + acceleration at one point, 200 JONSWAP
//                            harmonics (Hs 3 m, Tp 9 s): the cut-off skips the
//                            harmonics that have decayed at that depth
//   tow_point/raos           the vessel's RAO motion and the tow point (200
//                            harmonics x 6 dofs)
//   forward_dynamics_waves/n one evaluation of the dynamics of n 10 m elements
//                            hanging from the surface, with and without waves
#include <benchmark/benchmark.h>

#include <memory>

#include "models.hpp"  // tests/support
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/waves/vessel.hpp"

namespace {

using namespace towsim;

std::shared_ptr<const WaveField> sea() {
  return std::make_shared<const WaveField>(
      make_irregular_sea(3.0, 9.0, 3.3, 200, 1, Vec3(-1, 0, 0), std::numeric_limits<double>::infinity(), 9.81));
}

void wave_point(benchmark::State& st) {
  const auto w = sea();
  const double z = -static_cast<double>(st.range(0));
  double t = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(w->velocity(Vec3(3, 1, z), t));
    benchmark::DoNotOptimize(w->acceleration(Vec3(3, 1, z), t));
    t += 0.01;
  }
}
BENCHMARK(wave_point)->Arg(0)->Arg(10)->Arg(50)->Arg(150)->Arg(400);

void tow_point(benchmark::State& st) {
  RaoTable t;
  t.periods = {3, 30};
  t.headings = {0, 90, 180};
  t.amplitude.assign(36, 1.0);
  t.phase_deg.assign(36, 10.0);
  Tow tow;
  tow.pieces.push_back(Ramp{Vec3::UnitX(), 2.0, 0.0});
  tow.vessel = std::make_shared<const Vessel>(Vec3(-30, 0, 5), 0.0, sea(), t);
  double time = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(tow_kinematics(tow, time));
    time += 0.01;
  }
}
BENCHMARK(tow_point);

void forward_dynamics_waves(benchmark::State& st) {
  testing::CableSpec spec;
  spec.n = static_cast<int>(st.range(0));
  spec.length = 10.0 * spec.n;
  Model m = testing::cable_model(spec);
  if (st.range(1)) m.fluid.waves = sea();
  PhysicalState s = PhysicalState::hanging(m);
  Workspace ws(m);
  double t = 0;
  for (auto _ : st) {
    forward_dynamics(m, s, t, ws);
    benchmark::DoNotOptimize(ws.acc.tow_force);
    t += 0.01;
  }
  st.SetLabel(st.range(1) ? "waves" : "calm");
}
BENCHMARK(forward_dynamics_waves)->Args({10, 0})->Args({10, 1})->Args({30, 0})->Args({30, 1});

}  // namespace

BENCHMARK_MAIN();
