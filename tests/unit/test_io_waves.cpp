// The waves: and vessel: sections: compiled values and exact error texts
// (docs/scenario.md "waves", "vessel"), and the sea-state statistics.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include "../support/models.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/output/sea_statistics.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/waves/vessel.hpp"

namespace {

using ScenarioFile = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;

// Lines 8-9: a tow at 2 m/s along +y (course 90 deg).
const std::string kTow =
    "tow:\n"
    "  motion: [{type: ramp, direction: [0, 1, 0], speed: 2, ramp_time: 0}]\n";

// waves.stretching: none (default) or wheeler.
TEST_F(ScenarioFile, WaveStretchingChoice) {
  auto s = load(kCable + kSim + "waves:\n  regular: {height: 2, period: 8}\n  stretching: wheeler\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_TRUE(s.model->fluid.waves->wheeler);
  s = load(kCable + kSim + "waves:\n  regular: {height: 2, period: 8}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_FALSE(s.model->fluid.waves->wheeler);
  s = load(kCable + kSim + "waves:\n  regular: {height: 2, period: 8}\n  stretching: wheel\n");
  EXPECT_EQ(s.diags.str(), at("10:15: waves.stretching: expected one of none, wheeler (got 'wheel'; did you mean "
                              "'wheeler'?)"));
}

// spectrum.spreading: s > 0 makes the sea short-crested; absent: long-crested.
TEST_F(ScenarioFile, SpectrumSpreading) {
  auto s = load(kCable + kSim + "waves:\n  spectrum: {type: jonswap, hs: 3, tp: 9, spreading: 4}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_TRUE(s.model->fluid.waves->spread);
  s = load(kCable + kSim + "waves:\n  spectrum: {type: jonswap, hs: 3, tp: 9}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_FALSE(s.model->fluid.waves->spread);
  s = load(kCable + kSim + "waves:\n  spectrum: {type: jonswap, hs: 3, tp: 9, spreading: 0}\n");
  EXPECT_EQ(s.diags.str(), at("9:54: waves.spectrum.spreading: must be > 0 (got 0)"));
}

TEST_F(ScenarioFile, WavesAndVesselCompile) {
  const auto s = load(
      kCable + kSim + kTow +
      "waves:\n"
      "  regular: {height: 2, period: 8, heading_deg: 180}\n"
      "  water_depth: 60\n"
      "vessel:\n"
      "  tow_point: [-30, 0, 5]\n"
      "  raos: [[5, 0, heave, 1, 0], [5, 180, heave, 0.9, 10], [12, 0, heave, 1, 0], [12, 180, heave, 1, 5]]\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& m = *s.model;
  ASSERT_TRUE(m.fluid.waves);
  ASSERT_TRUE(m.tow.vessel);
  // Head seas on a course along +y: the waves travel along -y.
  EXPECT_NEAR(m.fluid.waves->direction.y(), -1.0, 1e-15);
  EXPECT_NEAR(m.fluid.waves->direction.x(), 0.0, 1e-15);
  EXPECT_EQ(m.fluid.waves->depth, 60.0);
  ASSERT_EQ(m.fluid.waves->components.size(), 1u);
  EXPECT_DOUBLE_EQ(m.fluid.waves->components[0].amplitude, 1.0);
  // The sheave 30 m astern of the RAO origin: at -y on this course, 5 m up (+ wave motion).
  const towsim::TowKinematics k = towsim::tow_kinematics(m.tow, 0.0);
  EXPECT_NEAR(k.pos.x(), 0.0, 1e-12);
  EXPECT_NEAR(k.pos.y(), -30.0, 1e-12);
  EXPECT_DOUBLE_EQ(towsim::statistics_start(m), 5.0);  // half the 10 s duration
}

TEST_F(ScenarioFile, SpectrumCompilesWithDefaults) {
  const auto s = load(kCable + kSim +
                      "waves:\n  spectrum: {type: pierson_moskowitz, hs: 2, tp: 8}\n  statistics_start: 3\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_EQ(s.model->fluid.waves->components.size(), 200u);
  EXPECT_NEAR(4 * std::sqrt(s.model->fluid.waves->variance()), 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.model->sim.statistics_start, 3.0);
  // Default heading 180 with the default course +x: waves travel along -x.
  EXPECT_NEAR(s.model->fluid.waves->direction.x(), -1.0, 1e-15);
}

TEST_F(ScenarioFile, WavesNeedExactlyOneKind) {
  const auto s = load(kCable + kSim + "waves:\n  water_depth: 50\n");
  EXPECT_EQ(s.diags.str(), at("9:3: waves: give exactly one of 'regular' or 'spectrum'"));
}

TEST_F(ScenarioFile, WavesSpectrumErrors) {
  auto s = load(kCable + kSim + "waves:\n  spectrum: {type: jonswap, hs: 3, tp: 9, gama: 2}\n");
  EXPECT_EQ(s.diags.str(), at("9:43: waves.spectrum.gama: unknown key (did you mean 'gamma'?)"));
  s = load(kCable + kSim + "waves:\n  spectrum: {type: jonswap, hs: 3, tp: 9, gamma: 0.5}\n");
  EXPECT_EQ(s.diags.str(), at("9:50: waves.spectrum.gamma: must be >= 1 (got 0.5)"));
  s = load(kCable + kSim + "waves:\n  regular: {height: -1, period: 8}\n");
  EXPECT_EQ(s.diags.str(), at("9:21: waves.regular.height: must be > 0 (got -1)"));
}

TEST_F(ScenarioFile, VesselErrors) {
  auto s = load(kCable + kSim + "vessel:\n  raos: [[5, 0, heave, 1, 0]]\n");
  EXPECT_EQ(s.diags.str(), at("9:9: vessel.raos: RAOs need a waves: section"));
  s = load(kCable + kSim + "waves:\n  regular: {height: 1, period: 8}\nvessel:\n  tow_point: [0, 0, 1]\n");
  EXPECT_EQ(s.diags.str(), at("11:3: vessel: give exactly one of 'raos' or 'motions'"));
  s = load(kCable + kSim + "waves:\n  regular: {height: 1, period: 8}\nvessel:\n  raos: [[5, 0, heav, 1, 0]]\n");
  EXPECT_EQ(s.diags.str(),
            at("11:17: vessel.raos.0: unknown dof 'heav' (expected surge, sway, heave, roll, pitch or yaw)"));
  s = load(kCable + kSim +
           "waves:\n  regular: {height: 1, period: 8}\nvessel:\n"
           "  raos: [[5, 0, heave, 1, 0], [9, 90, heave, 1, 0]]\n");
  EXPECT_EQ(s.diags.str(), at("11:9: vessel.raos: no row for heave at period 5, heading 90 "
                              "(each dof given needs every period x heading of the table)"));
}

TEST_F(ScenarioFile, VesselRotations) {
  const std::string head = kCable + kSim +
                           "waves:\n  regular: {height: 1, period: 8}\nvessel:\n  raos: [[5, 180, heave, 1, 0]]\n";
  EXPECT_TRUE(load(head + "  rotations: exact\n").ok());
  const auto s = load(head + "  rotations: exakt\n");
  EXPECT_EQ(s.diags.str(),
            at("12:14: vessel.rotations: expected one of small_angle, exact (got 'exakt'; did you mean 'exact'?)"));
}

TEST_F(ScenarioFile, RaoCsvFileAndItsErrors) {
  write("period,heading_deg,dof,amplitude,phase_deg\n5,180,heave,1,0\n12,180,heave,1,0\n", "raos.csv");
  const std::string head = kCable + kSim + "waves:\n  regular: {height: 1, period: 8}\nvessel:\n  raos: raos.csv\n";
  auto s = load(head);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_TRUE(s.model->tow.vessel);
  write("period,heading_deg,dof,amplitude,phase_deg\n5,180,heave,1\n", "raos.csv");
  s = load(head);
  EXPECT_EQ(s.diags.str(), in("raos.csv",
                              "2:1: vessel.raos: expected 5 values "
                              "period,heading_deg,dof,amplitude,phase_deg (got 4)"));
  write("5,180,heave,x,0\n", "raos.csv");
  s = load(head);
  EXPECT_EQ(s.diags.str(), in("raos.csv", "1:13: vessel.raos: expected a number (got 'x')"));
  write("5,400,heave,1,0\n", "raos.csv");
  s = load(head);
  EXPECT_EQ(s.diags.str(), in("raos.csv", "1:1: vessel.raos: heading_deg must be in [-360, 360] (got 400)"));
  // Headings are taken modulo 360 (a 360 row beside a 0 row is the same heading), dofs in any case.
  write("5,0,Heave,1,0\n5,360,heave,1,0\n5,-90,HEAVE,0.5,0\n", "raos.csv");
  s = load(head);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  write("5,0,heave,1,0\n5,0,heave,1,0\n", "raos.csv");
  s = load(head);
  EXPECT_EQ(s.diags.str(), in("raos.csv", "2:1: vessel.raos: duplicate row for heave at period 5, heading 0"));
  s = load(kCable + kSim + "waves:\n  regular: {height: 1, period: 8}\nvessel:\n  raos: none.csv\n");
  EXPECT_EQ(s.diags.str(), at("11:9: vessel.raos: cannot open the RAO file '" + (dir_ / "none.csv").string() + "'"));
}

// The built-in example's inline RAOs are the shipped CSV's rows.
TEST_F(ScenarioFile, SeaStateExampleUsesTheShippedRaos) {
  const auto* ex = towsim::scenario::find_example("sea-state-tow");
  ASSERT_NE(ex, nullptr);
  const auto a = towsim::scenario::load_scenario_text(ex->yaml, "x.yaml", "x", "");
  ASSERT_TRUE(a.ok()) << a.diags.str();
  const auto b = towsim::scenario::load_scenario_text(ex->yaml, "x.yaml", "x", "",
                                                      {"vessel.raos=" TOWSIM_SOURCE_DIR "/scenarios/generic-raos.csv"});
  ASSERT_TRUE(b.ok()) << b.diags.str();
  const towsim::TowKinematics ka = towsim::tow_kinematics(a.model->tow, 123.4);
  const towsim::TowKinematics kb = towsim::tow_kinematics(b.model->tow, 123.4);
  EXPECT_EQ(ka.pos, kb.pos);
  EXPECT_EQ(ka.acc, kb.acc);
}

// Statistics of x = m + A sin(2 pi t / T) sampled finely over whole periods:
// mean m, std A / sqrt 2, Tz = T, mpm = m + std sqrt(2 ln(10800 / T)).
// Sampling at T/1000 over 20 periods: std exact to the sampling (1e-9), Tz to
// the interpolation of crossings (1e-6 s).
TEST(SeaStatistics, SineHasClosedFormStatistics) {
  const double m = 5, A = 2, T = 8;
  std::vector<double> t, x;
  for (int i = 0; i < 20000; ++i) {
    t.push_back(i * T / 1000);
    x.push_back(m + A * std::sin(2 * std::numbers::pi * t.back() / T));
  }
  const auto s = towsim::output::signal_stats(t, x);
  EXPECT_NEAR(s.mean, m, 1e-9);
  EXPECT_NEAR(s.std, A / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(s.max, m + A, 1e-9);
  EXPECT_NEAR(s.zero_crossing_period, T, 1e-6);
  EXPECT_NEAR(s.mpm, m + A / std::sqrt(2.0) * std::sqrt(2 * std::log(10800 / T)), 1e-6);
}

}  // namespace

namespace {

// Spectral estimate: Parseval (the estimates sum to the variance when the band
// divides N/2, to round-off 1e-12 relative) and a sine's energy lands in the
// band holding its frequency (a Fourier frequency, so no leakage).
TEST(SeaStatistics, SpectralEstimateParsevalAndPeak) {
  const double dt = 0.2;
  const std::size_t N = 1000;  // N/2 = 500 = 100 bands of 5
  const double w0 = 2 * std::numbers::pi * 37 / (N * dt);
  std::vector<double> x(N);
  std::mt19937_64 g(3);
  double var = 0, mean = 0;
  for (std::size_t n = 0; n < N; ++n) x[n] = 2 * std::cos(w0 * n * dt) + 0.3 * ((g() >> 11) * 0x1.0p-53 - 0.5);
  for (double v : x) mean += v / N;
  for (double v : x) var += (v - mean) * (v - mean) / N;
  const auto S = towsim::output::spectral_density_estimate(x, dt, 5);
  ASSERT_EQ(S.size(), 100u);
  const double dw = 2 * std::numbers::pi / (N * dt);
  double sum = 0, best = 0, wbest = 0;
  for (const auto& [w, s] : S) {
    sum += s * 5 * dw;
    if (s > best) best = s, wbest = w;
  }
  EXPECT_NEAR(sum, var, 1e-12 * var);
  EXPECT_NEAR(wbest, w0, 2.5 * dw) << "the peak band holds the sine's frequency";
}

// spectra.csv's transfer functions against known gains: the wave elevation,
// the tow point's heave and the body's depth are sums of sines at Fourier
// frequencies (one per 5-bin band, so no leakage between bands), the heave
// G1(omega) and the depth G2(omega) times the elevation's amplitude with
// other phases: body_heave_per_wave must be G2 and body_heave_per_tow_heave
// G2 / G1 in the bands holding a sine (1e-9: the periodogram of a sine at a
// Fourier frequency is exact up to the sums' round-off, ~1e-13, and the file
// has 12 significant digits), blank in the bands without energy.
TEST(SeaStatistics, TransferFunctionsOfKnownGains) {
  towsim::Model m = towsim::testing::cable_model(towsim::testing::CableSpec{});
  towsim::testing::add_sphere_body(m);
  const double dt = 0.5;
  const std::size_t N = 2000;  // N/2 = 1000 = 200 bands of 5
  const double dw = 2 * std::numbers::pi / (N * dt);
  const std::vector<int> bins = {43, 68, 103, 153, 208};  // centre bins 3 + 5 j of bands j = 8, 13, 20, 30, 41
  auto G1 = [](double w) { return 0.8 / (1 + w * w); };   // tow heave per metre of wave [m/m]
  auto G2 = [](double w) { return 0.3 * std::exp(-w); };  // body depth per metre of wave [m/m]
  towsim::output::SeaStatistics stats;
  for (std::size_t n = 0; n < N; ++n) {
    towsim::Sample s;
    s.t = static_cast<double>(n) * dt;
    s.tow_force = towsim::Vec3(1000, 0, 0);
    s.bodies.resize(1);
    s.bodies[0].pos = towsim::Vec3(0, 0, -50);
    for (std::size_t i = 0; i < bins.size(); ++i) {
      const double w = dw * bins[i], a = 0.5 + 0.1 * static_cast<double>(i);
      s.wave_elevation += a * std::cos(w * s.t + 0.3 * static_cast<double>(i));
      s.tow_wave.z() += G1(w) * a * std::cos(w * s.t + 1.1 + 0.3 * static_cast<double>(i));
      s.bodies[0].pos.z() += G2(w) * a * std::cos(w * s.t - 0.7);
    }
    stats.add(m, s);
  }
  const auto path = std::filesystem::temp_directory_path() / ("towsim_spectra_" + std::to_string(::getpid()) + ".csv");
  ASSERT_TRUE(stats.write_spectra(path.string()));
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "omega,wave_elevation,tow_tension,link_force,body_depth,body_heave_per_wave,tow_heave,"
            "body_heave_per_tow_heave");
  int rows = 0, checked = 0, blank = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (line.back() == ',') f.emplace_back();
    ASSERT_EQ(f.size(), 8u) << line;
    const double w = std::stod(f[0]);
    const double bin = w / dw;  // band centre
    bool holds = false;
    for (int b : bins) holds = holds || std::abs(bin - b) < 2.6;
    if (holds) {
      const double wb = dw * std::round(bin);
      EXPECT_NEAR(std::stod(f[5]), G2(wb), 1e-9) << "body_heave_per_wave at omega " << w;
      EXPECT_NEAR(std::stod(f[7]), G2(wb) / G1(wb), 1e-9) << "body_heave_per_tow_heave at omega " << w;
      ++checked;
    } else {
      EXPECT_TRUE(f[5].empty() && f[7].empty()) << line;
      ++blank;
    }
    ++rows;
  }
  std::filesystem::remove(path);
  EXPECT_EQ(rows, 200);
  EXPECT_EQ(checked, 5);
  EXPECT_EQ(blank, 195);
}

}  // namespace
