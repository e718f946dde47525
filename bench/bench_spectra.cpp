// Cost of spectra.csv's spectral estimate (docs/performance.md "Sea states").
//
//   spectral_estimate/<N>   towsim::output::spectral_density_estimate of N random
//                           samples, bands of 5 bins: 54500 is a 3-hour
//                           storm's record at 0.2 s (factors 2^2 5^3 109), 54497
//                           a prime length, 54000 a length of 2, 3 and 5 only
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "towsim/output/sea_statistics.hpp"

namespace {

void spectral_estimate(benchmark::State& st) {
  std::mt19937_64 g(1);
  std::vector<double> x(static_cast<std::size_t>(st.range(0)));
  for (double& v : x) v = static_cast<double>(g() >> 11) * 0x1.0p-53;
  for (auto _ : st) benchmark::DoNotOptimize(towsim::output::spectral_density_estimate(x, 0.2, 5));
}
BENCHMARK(spectral_estimate)->Arg(54500)->Arg(54497)->Arg(54000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
