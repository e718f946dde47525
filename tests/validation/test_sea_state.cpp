// Sea-state runs through the whole pipeline (YAML -> Model -> simulate):
// the tow point carried by the vessel's wave motion as written in the
// samples, the encounter frequency measured from the run's own output, and a
// cable in waves staying sound (MODEL.md 9, INTERFACE.md "Ship motion from waves").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"

namespace {

using towsim::MemorySink;
using towsim::Sample;

std::vector<Sample> run(const std::string& yaml) {
  const auto s = towsim::scenario::load_scenario_text(yaml, "sea.yaml", "sea", "");
  EXPECT_TRUE(s.ok()) << s.diags.str();
  if (!s.ok()) return {};
  MemorySink sink;
  const auto st = towsim::simulate(*s.model, sink);
  EXPECT_EQ(st.status, "ok") << st.message;
  return sink.samples;
}

std::string scenario(double speed, double heading, const std::string& extra = "") {
  return "cable: {length: 50, elements: 5, mass_per_length: 1.5, diameter: 0.02}\n"
         "tow:\n  motion: [{type: ramp, direction: [1, 0, 0], speed: " +
         std::to_string(speed) +
         ", ramp_time: 0}]\n"
         "initial: steady\n"
         "waves:\n  regular: {height: 2, period: 8, heading_deg: " +
         std::to_string(heading) +
         "}\n"
         "vessel:\n  tow_point: [-30, 0, 5]\n"
         "  raos: [[2, 0, heave, 1, 0], [30, 0, heave, 1, 0], [2, 180, heave, 1, 0], [30, 180, heave, 1, 0]]\n"
         "simulation: {duration: 120, time_step: 0.01, output_interval: 0.05}\n" +
         extra;
}

// Unit heave RAO at zero speed: the written tow point heave equals the
// written wave elevation at the RAO origin, and the tow_wave displacement is
// that heave alone. Tolerance 2e-10 m: the sample's tow point is the tow law
// evaluated inside the last step's window, at t moved by a relative 1e-12
// (System::law_time), i.e. up to 1.2e-10 s at t = 120 s, times the heave
// velocity a omega = 0.79 m/s: 1e-10 m.
TEST(SeaState, TowPointHeaveIsTheWaveInARun) {
  const auto samples = run(scenario(0.0, 180));
  ASSERT_FALSE(samples.empty());
  double worst = 0, amp = 0;
  for (const auto& s : samples) {
    worst = std::max(worst, std::abs(s.tow_pos.z() - 5 - s.wave_elevation));
    worst = std::max(worst, std::abs(s.tow_wave.z() - s.wave_elevation));
    amp = std::max(amp, std::abs(s.wave_elevation));
  }
  std::printf("[measured] run: max |tow heave - eta| %.2e m, wave amplitude %.6f m\n", worst, amp);
  EXPECT_LE(worst, 2e-10);
  EXPECT_NEAR(amp, 1.0, 1e-3);  // sampled at 0.05 s of an 8 s period: cos error < 2e-4
}

/// Mean up-crossing period of z - mean(z) over the samples after t0.
double crossing_period(const std::vector<Sample>& ss, double t0) {
  double mean = 0;
  int n = 0;
  for (const auto& s : ss)
    if (s.t >= t0) mean += s.tow_pos.z(), ++n;
  mean /= n;
  double first = -1, last = 0;
  int c = 0;
  for (std::size_t i = 1; i < ss.size(); ++i) {
    if (ss[i - 1].t < t0) continue;
    const double a = ss[i - 1].tow_pos.z() - mean, b = ss[i].tow_pos.z() - mean;
    if (a < 0 && b >= 0) {
      const double tc = ss[i - 1].t + (ss[i].t - ss[i - 1].t) * a / (a - b);
      if (first < 0) first = tc;
      last = tc, ++c;
    }
  }
  return (last - first) / (c - 1);
}

// Encounter frequency measured from the run's output: at 2 m/s the 8 s wave
// is met at omega + k U (head seas) and omega - k U (following seas); the
// mean crossing period over ~110 s matches 2 pi / omega_e within 0.2 %
// (crossings interpolated linearly on 0.05 s samples: < 1e-3 s each, two
// crossings bound ~15 periods).
TEST(SeaState, EncounterPeriodFromTheOutput) {
  const double w = 2 * std::numbers::pi / 8, k = w * w / 9.81, U = 2.0;
  for (double heading : {180.0, 0.0}) {
    const auto samples = run(scenario(U, heading));
    const double we = w - k * U * std::cos(heading * std::numbers::pi / 180);
    const double Te = crossing_period(samples, 5.0);
    std::printf("[measured] heading %3.0f: crossing period %.5f s, 2 pi / omega_e %.5f s\n", heading, Te,
                2 * std::numbers::pi / we);
    EXPECT_NEAR(Te, 2 * std::numbers::pi / we, 2e-3 * Te);
  }
}

// A cable towed in a JONSWAP sea with wave kinematics on it: the run stays
// sound (elements keep their length to 1e-6) and the tow tension varies.
TEST(SeaState, CableInIrregularSeaRuns) {
  std::string y = scenario(1.5, 180);
  y.replace(y.find("regular: {height: 2, period: 8, heading_deg: 180.000000}"),
            std::string("regular: {height: 2, period: 8, heading_deg: 180.000000}").size(),
            "spectrum: {type: jonswap, hs: 3, tp: 9, components: 100, seed: 4}");
  const auto s = towsim::scenario::load_scenario_text(y, "sea.yaml", "sea", "");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  MemorySink sink;
  const auto st = towsim::simulate(*s.model, sink);
  ASSERT_EQ(st.status, "ok") << st.message;
  EXPECT_LT(st.max_element_drift, 1e-6);
  double tmin = 1e300, tmax = 0;
  for (const auto& x : sink.samples)
    tmin = std::min(tmin, x.tow_force.norm()), tmax = std::max(tmax, x.tow_force.norm());
  EXPECT_GT(tmax - tmin, 0.1 * tmax) << "waves must modulate the tow tension";
}

}  // namespace
