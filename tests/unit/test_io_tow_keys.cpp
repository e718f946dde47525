// Scenario keys of the manoeuvres, knots and track files: values compiled and
// exact error texts (FILE:LINE:COL: PATH: problem).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "../support/scenario_files.hpp"
#include "towsim/scenario/scenario.hpp"

namespace {

using TowKeys = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;
const std::string kTow = "tow:\n  motion:\n";  // lines 8-9: pieces start on line 10
const std::string kRamp = "    - {type: ramp, direction: [1, 0, 0], speed: 2, ramp_time: 10}\n";

}  // namespace

// 1 kn = 1852/3600 m/s exactly: the value is the correctly rounded product.
TEST_F(TowKeys, SpeedsInKnots) {
  const auto s = load(kCable + kSim + kTow + "    - {type: ramp, direction: [1, 0, 0], speed_kn: 4, ramp_time: 10}\n" +
                      "    - {type: speed, speed_kn: 6, start_time: 300, ramp_time: 30}\n" +
                      "environment:\n  current_kn: [1, 0, 0]\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& p = s.model->tow.pieces;
  EXPECT_EQ(std::get<towsim::Ramp>(p[0]).speed, 4 * 1852.0 / 3600.0);
  EXPECT_EQ(std::get<towsim::SpeedChange>(p[1]).speed, 6 * 1852.0 / 3600.0);
  EXPECT_EQ(std::get<towsim::SpeedChange>(p[1]).start_time, 300.0);
  EXPECT_EQ(std::get<towsim::SpeedChange>(p[1]).ramp_time, 30.0);
  EXPECT_EQ(s.model->fluid.current_velocity.at(0).x(), 1852.0 / 3600.0);
  const auto rows = load(kCable + kSim + "environment:\n  current_kn:\n    - {depth: 0, velocity_kn: [2, 0, 0]}\n" +
                         "    - {depth: 50, velocity_kn: [0, 1, 0]}\n");
  ASSERT_TRUE(rows.ok()) << rows.diags.str();
  EXPECT_EQ(rows.model->fluid.current_velocity.at(0).x(), 2 * 1852.0 / 3600.0);
  EXPECT_EQ(rows.model->fluid.current_velocity.at(1).y(), 1852.0 / 3600.0);
}

TEST_F(TowKeys, SpeedGivenTwiceOrNotAtAll) {
  const auto s = load(kCable + kSim + kTow +
                      "    - {type: ramp, direction: [1, 0, 0], speed: 2, speed_kn: 4, ramp_time: 1}\n" +
                      "    - {type: speed, start_time: 3, ramp_time: 2}\n");
  EXPECT_EQ(s.diags.str(), at("10:52: tow.motion.0.speed_kn: give either 'speed' or 'speed_kn', not both") +
                               at("11:7: tow.motion.1.speed: missing required key"));
  const auto c = load(kCable + kSim + "environment:\n  current: [1, 0, 0]\n  current_kn: [1, 0, 0]\n");
  EXPECT_EQ(c.diags.str(), at("10:3: environment.current_kn: give either 'current' or 'current_kn', not both"));
}

// The _kn keys are accepted but not listed among a piece's keys.
TEST_F(TowKeys, SpeedPieceKeys) {
  const auto s = load(kCable + kSim + kTow + kRamp + "    - {type: speed, speed: -1, ramp_time: 0, angle_deg: 3}\n");
  EXPECT_EQ(s.diags.str(),
            at("11:28: tow.motion.1.speed: must be >= 0 (got -1)") +
                at("11:43: tow.motion.1.ramp_time: must be > 0 (got 0)") +
                at("11:46: tow.motion.1.angle_deg: unknown key (expected one of: type, speed, start_time, "
                   "ramp_time)"));
}

TEST_F(TowKeys, TurnAngle) {
  const auto s = load(kCable + kSim + kTow + kRamp + "    - {type: turn, radius: 50, start_time: 20, angle_deg: 90}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& turn = std::get<towsim::Turn>(s.model->tow.pieces.at(1));
  EXPECT_EQ(turn.angle, 90 * std::numbers::pi / 180);
  EXPECT_FALSE(std::isfinite(
      std::get<towsim::Turn>(load(kCable + kSim + kTow + kRamp + "    - {type: turn, radius: 50, start_time: 20}\n")
                                 .model->tow.pieces.at(1))
          .angle));
  const auto z = load(kCable + kSim + kTow + kRamp + "    - {type: turn, radius: 50, angle_deg: 0}\n");
  EXPECT_EQ(z.diags.str(), at("11:43: tow.motion.1.angle_deg: must be > 0 (got 0)"));
}

// Manoeuvres listed out of time order; a turn during a turn; a speed change
// during another; the first manoeuvre with no horizontal speed (no heading).
TEST_F(TowKeys, ManoeuvreSequenceRefusals) {
  const auto order = load(kCable + kSim + kTow + kRamp +
                          "    - {type: speed, speed: 1, start_time: 50, ramp_time: 5}\n" +
                          "    - {type: turn, radius: 5, start_time: 20, angle_deg: 90}\n");
  EXPECT_EQ(order.diags.str(), at("12:7: tow.motion.2: starts at t = 20 s, before tow.motion.1 (t = 50 s): list turns "
                                  "and speed changes in time order"));
  const auto speeds = load(kCable + kSim + kTow + kRamp +
                           "    - {type: speed, speed: 1, start_time: 50, ramp_time: 30}\n" +
                           "    - {type: speed, speed: 3, start_time: 60, ramp_time: 5}\n");
  EXPECT_EQ(speeds.diags.str(), at("12:7: tow.motion.2: a speed change cannot start while the speed change "
                                   "tow.motion.1 goes on (until t = 80 s)"));
  // 90 degrees of R = 20 m at 2 m/s: pi/2 * 10 s, from t = 20 s.
  const auto turns = load(kCable + kSim + kTow + kRamp +
                          "    - {type: turn, radius: 20, start_time: 20, angle_deg: 90}\n" +
                          "    - {type: turn, radius: 20, start_time: 30, angle_deg: 90}\n");
  EXPECT_EQ(turns.diags.str(), at("12:7: tow.motion.2: a turn cannot start while the turn tow.motion.1 goes on (until "
                                  "t = 35.70796327 s)"));
  const auto still = load(kCable + kSim + kTow + "    - {type: heave, amplitude: 1, period: 10}\n" +
                          "    - {type: speed, speed: 1, start_time: 5, ramp_time: 5}\n");
  EXPECT_EQ(still.diags.str(), at("11:7: tow.motion.1: a speed change needs a non-zero horizontal tow speed at its "
                                  "start time (got 0 m/s at t = 5 s)"));
  // Stopped by a speed change, a later turn has no speed to turn with.
  const auto stopped = load(kCable + kSim + kTow + kRamp +
                            "    - {type: speed, speed: 0, start_time: 20, ramp_time: 5}\n" +
                            "    - {type: turn, radius: 5, start_time: 30}\n");
  EXPECT_EQ(stopped.diags.str(), at("12:7: tow.motion.2: a turn needs a non-zero horizontal tow speed at its start "
                                    "time (got 0 m/s at t = 30 s)"));
}

// A header names the columns: `time,y,x,z` swaps x and y.
TEST_F(TowKeys, TrackHeaderColumnsByName) {
  write("# a survey line\ntime, y, x, z\n0, 1, 2, 3\n10, 4, 5, 6\n", "track.csv");
  const auto s = load(kCable + kSim + kTow + "    - {type: track, file: track.csv}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& tr = std::get<towsim::Track>(s.model->tow.pieces.at(0));
  EXPECT_EQ(tr.time, (std::vector<double>{0, 10}));
  EXPECT_EQ(tr.pos.at(0), towsim::Vec3(2, 1, 3));
  EXPECT_EQ(tr.pos.at(1), towsim::Vec3(5, 4, 6));
}

TEST_F(TowKeys, TrackHeaderRefusals) {
  write("time,x,q,z\n0,0,0,0\n1,1,0,0\n", "unknown.csv");
  write("time,x,z\n0,0,0\n1,1,0\n", "missing.csv");
  write("time,x,x,z\n0,0,0,0\n1,1,0,0\n", "twice.csv");
  const auto s = load(kCable + kSim + kTow + "    - {type: track, file: unknown.csv}\n" +
                      "    - {type: track, file: missing.csv}\n    - {type: track, file: twice.csv}\n");
  EXPECT_EQ(s.diags.str(),
            in("unknown.csv",
               "1:8: tow.motion.0.file: unknown column 'q' in the track header (expected time, x, y, z)") +
                in("missing.csv",
                   "1:1: tow.motion.1.file: the track header has no column 'y' (expected time, x, y, z)") +
                in("twice.csv", "1:8: tow.motion.2.file: column 'x' appears twice in the track header"));
}

// speed_scale divides the track's times: the same path, speed_scale times faster.
TEST_F(TowKeys, TrackSpeedScale) {
  const std::string track = "    - {type: track, points: [[0, 0, 0, 0], [10, 20, 0, 0], [30, 20, 40, 0]]";
  const auto s = load(kCable + kSim + kTow + track + ", speed_scale: 2}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_EQ(std::get<towsim::Track>(s.model->tow.pieces.at(0)).time, (std::vector<double>{0, 5, 15}));
  const auto one = load(kCable + kSim + kTow + track + "}\n");
  const auto two = load(kCable + kSim + kTow + track + ", speed_scale: 2}\n");
  const auto a = towsim::tow_kinematics(one.model->tow, 12.0), b = towsim::tow_kinematics(two.model->tow, 6.0);
  EXPECT_LE((a.pos - b.pos).norm(), 1e-12);  // round-off on ~20 m
  EXPECT_LE((2 * a.vel - b.vel).norm(), 1e-12);
  // From the command line: --set on the track piece.
  const auto set = load(kCable + kSim + kTow + track + "}\n", {"tow.motion.0.speed_scale=4"});
  ASSERT_TRUE(set.ok()) << set.diags.str();
  EXPECT_EQ(std::get<towsim::Track>(set.model->tow.pieces.at(0)).time, (std::vector<double>{0, 2.5, 7.5}));
  const auto bad = load(kCable + kSim + kTow + track + ", speed_scale: 0}\n");
  EXPECT_EQ(bad.diags.str(), at("10:91: tow.motion.0.speed_scale: must be > 0 (got 0)"));
}
