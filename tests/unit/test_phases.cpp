// Manoeuvre phases (towsim/sim/phases.hpp) of known tow laws and winch
// schedules, and the settling of a signal (towsim/output/transients.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "towsim/output/output.hpp"
#include "towsim/output/transients.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/phases.hpp"

using namespace towsim;
using towsim::output::Settling;
using towsim::output::TransientRecord;

namespace {

/// An example's compiled model.
Model example(const char* name) {
  const scenario::Example* e = scenario::find_example(name);
  EXPECT_NE(e, nullptr) << name;
  const auto s = scenario::load_scenario_text(e->yaml, std::string(name) + ".yaml", name, "");
  EXPECT_TRUE(s.ok()) << s.diags.str();
  return *s.model;
}

/// "kind start end settle_end" of each phase, for readable failures.
struct Expected {
  Phase::Kind kind;
  double start, end, settle_end;
  int piece;
  bool winch;
};

void expect_phases(const std::vector<Phase>& got, const std::vector<Expected>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE("phase " + std::to_string(i));
    EXPECT_EQ(phase_kind_name(got[i].kind), std::string(phase_kind_name(want[i].kind)));
    EXPECT_EQ(got[i].start, want[i].start);
    EXPECT_EQ(got[i].end, want[i].end);
    EXPECT_EQ(got[i].settle_end, want[i].settle_end);
    EXPECT_EQ(got[i].piece, want[i].piece);
    EXPECT_EQ(got[i].winch, want[i].winch);
  }
}

using K = Phase::Kind;

}  // namespace

TEST(Phases, AccelerationThenAnEndlessTurn) {
  // paper-3d-turn: ramp to 1.57 m/s over 15 s, then a turn from 15 s that never ends; 300 s.
  expect_phases(run_phases(example("paper-3d-turn")), {{K::Accelerate, 0, 15, 15, 0, false},  // the turn starts at 15
                                                       {K::Turn, 15, 300, 300, 1, false}});
}

TEST(Phases, ANinetyDegreeTurnBetweenSteadyTows) {
  // two-part-tow: steady at 5 kn, a 90 deg turn of 500 m radius from 300 s, 1500 s in all.
  const auto p = run_phases(example("two-part-tow"));
  ASSERT_EQ(p.size(), 3u);
  // The turn lasts a quarter circle at the course speed: (pi/2) 500 / (5 * 1852 / 3600) s.
  const double end = 300 + std::numbers::pi / 2 * 500 / (5 * 1852.0 / 3600);
  EXPECT_NEAR(p[1].end, end, 1e-9);  // the course's own arithmetic: round-off only
  expect_phases(p, {{K::Steady, 0, 300, 300, -1, false},
                    {K::Turn, 300, p[1].end, 1500, 1, false},
                    {K::Steady, p[1].end, 1500, 1500, -1, false}});
}

TEST(Phases, WinchPayOutHoldAndHaulIn) {
  // fish-depth-change: rate [[0,0],[60,0],[70,1],[360,1],[370,0],[700,0],[710,-1],[1000,-1],[1010,0]], 1300 s.
  expect_phases(run_phases(example("fish-depth-change")), {{K::Steady, 0, 60, 60, -1, false},
                                                           {K::PayOut, 60, 370, 700, -1, true},
                                                           {K::Steady, 370, 700, 700, -1, false},
                                                           {K::HaulIn, 700, 1010, 1300, -1, true},
                                                           {K::Steady, 1010, 1300, 1300, -1, false}});
}

TEST(Phases, OverlappingManoeuvresAndAWinchRateThroughZero) {
  Model m;
  m.sim.duration = 200;
  m.tow.pieces = {Ramp{Vec3::UnitX(), 2.0, 10.0}, Heave{0.5, 8, 180},
                  Turn{100, 40, true, std::numbers::pi / 2},  // a quarter circle, from 40 s at 2 m/s
                  SpeedChange{1.0, 60, 20}};                  // during the turn: 2 -> 1 m/s from 60 to 80 s
  finalize_tow(m.tow);
  m.winch.mode = Winch::Mode::Imposed;
  // Pay-out at 1 m/s, the rate falling linearly to -1 m/s from 20 s to 30 s
  // (through zero at 25 s), hauling in up to 50 s, stopped at 50.5 s.
  m.winch.schedule = schedule_from_rate({20, 30, 50, 50.5}, {1, -1, -1, 0}, 100, 0, 1e9);
  const auto p = run_phases(m);
  // The turn ends after 50 pi m of arc: 40 m by 60 s, 30 m more by 80 s, the rest at 1 m/s.
  const double turn_end = 80 + (std::numbers::pi / 2 * 100 - 70) / 1.0;
  ASSERT_EQ(p.size(), 7u);
  EXPECT_NEAR(p[3].end, turn_end, 1e-9);  // round-off of the course's arithmetic
  const double te = p[3].end;
  expect_phases(p, {{K::Accelerate, 0, 10, 10, 0, false},   // the pay-out runs on at its end
                    {K::PayOut, 0, 25, 25, -1, true},       // the haul-in starts at its end
                    {K::HaulIn, 25, 50.5, 50.5, -1, true},  // the turn runs on at its end
                    {K::Turn, 40, te, 180, 2, false},       // steady from its end to the heave
                    {K::SpeedChange, 60, 80, 80, 3, false},
                    {K::Steady, te, 180, 180, -1, false},
                    {K::Heave, 180, 200, 200, 1, false}});  // a heave goes on to the run's end
}

TEST(Phases, ForceTableChanges) {
  Model m;
  m.sim.duration = 100;
  m.tow.mode = Tow::Mode::Force;
  m.tow.force_time = {0, 10, 20, 30, 40};
  m.tow.force_value = {Vec3(5, 0, 0), Vec3(5, 0, 0), Vec3(8, 0, 0), Vec3(9, 0, 0), Vec3(9, 0, 0)};
  finalize_tow(m.tow);
  expect_phases(run_phases(m), {{K::Steady, 0, 10, 10, -1, false},
                                {K::ForceChange, 10, 30, 100, -1, false},
                                {K::Steady, 30, 100, 100, -1, false}});
}

namespace {

/// The band parameters of a tension (summary.json `phases`).
Settling::Result tension_result(const Settling& s, double window_start) {
  return s.result(output::kSettleChangeFraction, output::kSettleValueFraction, output::kSettleTensionFloor,
                  output::kSettleHoldFraction, window_start);
}

}  // namespace

TEST(Settling, AFirstOrderApproachSettlesAtTauLnOfChangeOverBand) {
  // x = 1000 (1 - exp(-(t - 50) / tau)) N from t = 50 s, tau = 10 s, sampled every 0.1 s up to 20 tau.
  // Band: 2 % of the change (20 N; 0.5 % of the value is 5 N). Inside it once
  // 1000 exp(-(t - 50) / tau) <= 20 N, i.e. t - 50 >= tau ln(1000 / 20) = 39.12 s.
  const double tau = 10, dt = 0.1;
  Phase phase{Phase::Kind::Turn, 1, false, 50, 60, 250};
  TransientRecord rec({phase}, 250, false);
  Settling alone;
  for (int k = 0; k <= 2000; ++k) {
    const double t = output::tidy_time(50 + k * dt), x = 1000 * (1 - std::exp(-(t - 50) / tau));
    rec.add(t, x, 100, std::nan(""));
    alone.add(t, x);
  }
  const Settling::Result r = tension_result(alone, 50);
  const double change = 1000 * (1 - std::exp(-20.0));  // the settled value - the first
  EXPECT_DOUBLE_EQ(r.band, 0.02 * change);
  // The analytic instant, then the first sample at or after it (39.12 s is
  // 0.08 s from the grid: no round-off can move it across a sample).
  const double t_star = -tau * std::log(r.band / 1000 + std::exp(-20.0));
  // The approach is not quite over at 20 tau: that shifts it by 49 tau exp(-20) = 1.0e-6 s.
  EXPECT_NEAR(t_star, tau * std::log(50.0), 2e-6);
  EXPECT_NEAR(r.since - 50, std::ceil(t_star / dt) * dt, 1e-9);  // times tidied to the nanosecond
  EXPECT_NEAR(r.since - 50, 39.2, 1e-9);
  const auto j = rec.json(250);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["tow_tension"]["settle_time"].get<double>(), output::tidy_time(r.since - 50));
  EXPECT_EQ(j[0]["tow_tension"]["band"].get<double>(), output::tidy(r.band));
  EXPECT_EQ(j[0]["tow_tension"]["settled_value"].get<double>(),
            1000 * (1 - std::exp(-(output::tidy_time(250) - 50) / tau)));
  EXPECT_EQ(j[0]["depth"]["settle_time"].get<double>(), 0);  // constant: settled from the start
  EXPECT_EQ(j[0]["depth"]["band"].get<double>(), output::kSettleDepthFloor);
  EXPECT_EQ(j[0]["settle_time"].get<double>(), output::tidy_time(r.since - 50));  // the later of the two
  EXPECT_FALSE(j[0].contains("link_tension"));
  // Extremes over [start, end) = [50, 60) only.
  EXPECT_EQ(j[0]["tow_tension"]["max"]["time"].get<double>(), 59.9);
  EXPECT_EQ(j[0]["tow_tension"]["max"]["value"].get<double>(),
            1000 * (1 - std::exp(-(output::tidy_time(50 + 99 * dt) - 50) / tau)));
  EXPECT_EQ(j[0]["tow_tension"]["min"]["value"].get<double>(), 0);
  EXPECT_EQ(j[0]["tow_tension"]["min"]["time"].get<double>(), 50);
}

TEST(Settling, TheStaircasesFindTheLastSampleOutsideTheBand) {
  // A decaying beat, against a direct scan from the end, for bands of several widths.
  std::vector<double> t, x;
  Settling s;
  for (int k = 0; k < 3000; ++k) {
    t.push_back(0.5 * k);
    x.push_back(500 + 80 * std::exp(-k / 700.0) * std::sin(0.37 * k) * std::cos(0.011 * k) + 3 * std::sin(2.1 * k));
    s.add(t.back(), x.back());
  }
  for (double floor : {0.1, 2.0, 4.0, 10.0, 30.0, 100.0}) {
    const Settling::Result r = s.result(0, 0, floor, 0, 0);
    std::size_t k = x.size() - 1;
    while (k > 0 && std::abs(x[k - 1] - x.back()) <= floor) --k;
    EXPECT_EQ(r.since, t[k]) << "band " << floor;
  }
}

TEST(Settling, ASignalThatNeverFlattensDoesNotSettle) {
  // x = t over 100 s: within 2 % of the change (2) of its last value only over
  // the last 2 s, less than a fifth of the window.
  Settling s;
  for (int k = 0; k <= 100; ++k) s.add(k, k);
  const Settling::Result r = tension_result(s, 0);
  EXPECT_EQ(r.band, 2);
  EXPECT_TRUE(std::isnan(r.since));
  // Held for exactly a fifth of the window (from 80 s of 100 s, band 20): settled at 80 s.
  EXPECT_EQ(s.result(0, 0, 20, output::kSettleHoldFraction, 0).since, 80);
}

TEST(TransientRecord, ABoundarySampleBelongsToThePhaseStartingThere) {
  // A 40 s run stopped at 25 s: steady [0, 10), a turn [10, 20) whose window runs to 30 s.
  TransientRecord rec({Phase{Phase::Kind::Steady, -1, false, 0, 10, 10},
                       Phase{Phase::Kind::Turn, 0, false, 10, 20, 30}},
                      40, true);
  for (int k = 0; k <= 25; ++k) rec.add(k, k == 12 ? 50.0 : 1.0, 5, 2.0 * k);
  const auto j = rec.json(25);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0]["name"], "steady 1");
  EXPECT_EQ(j[0]["source"], nullptr);
  EXPECT_EQ(j[1]["name"], "turn 1");
  EXPECT_EQ(j[1]["source"], "tow.motion.0");
  // t = 10 s is the turn's (its loads are those of the turn), not the steady phase's.
  EXPECT_EQ(j[0]["link_tension"]["max"]["value"], 18.0);
  EXPECT_EQ(j[0]["link_tension"]["max"]["time"], 9.0);
  EXPECT_EQ(j[1]["link_tension"]["min"]["value"], 20.0);
  EXPECT_EQ(j[1]["link_tension"]["min"]["time"], 10.0);
  EXPECT_EQ(j[1]["link_tension"]["max"]["value"], 38.0);  // at 19 s: 20 s is after the turn
  EXPECT_EQ(j[0]["tow_tension"]["max"]["value"], 1.0);
  EXPECT_EQ(j[1]["tow_tension"]["max"]["value"], 50.0);
  EXPECT_EQ(j[1]["tow_tension"]["max"]["time"], 12.0);
  EXPECT_EQ(j[1]["tow_tension"]["min"]["time"], 10.0);  // a tie keeps the first time
  EXPECT_EQ(j[0]["settle_time"], 0.0);                  // its window [0, 10) was run: constant tension and depth
  EXPECT_EQ(j[0]["tow_tension"]["settled_value"], 1.0);
  for (const char* q : {"tow_tension", "depth", "link_tension"}) {
    EXPECT_TRUE(j[1][q]["settle_time"].is_null()) << q;  // [10, 30): the run stopped at 25 s
    EXPECT_TRUE(j[1][q]["settled_value"].is_null()) << q;
    EXPECT_TRUE(j[1][q]["band"].is_null()) << q;
  }
  EXPECT_TRUE(j[1]["settle_time"].is_null());
}

TEST(TransientRecord, ThePhaseEndingWithTheRunHasItsLastSample) {
  TransientRecord rec({Phase{Phase::Kind::Steady, -1, false, 0, 10, 10}}, 10, false);
  for (int k = 0; k <= 10; ++k) rec.add(k, k, 0, std::nan(""));
  const auto j = rec.json(10);
  EXPECT_EQ(j[0]["tow_tension"]["max"]["time"], 10.0);
  EXPECT_EQ(j[0]["tow_tension"]["settled_value"], 10.0);
}
