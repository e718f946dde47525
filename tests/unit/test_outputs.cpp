// Output columns and summary of the operations release (issue 15): layback,
// deployed_length, final, min/max depth, the number format, the end-of-run
// line and the removal of a previous run's files.
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "../support/cli.hpp"
#include "towsim/output/output.hpp"

namespace fs = std::filesystem;
using towsim::testing::fresh_dir;
using towsim::testing::read_text_csv;
using towsim::testing::TextCsv;
using towsim::testing::towsim_cli;

namespace {

// Values are written with 12 significant digits: a quantity recomputed from
// other written columns agrees to a few units of 1e-12 of the largest input
// (coordinates up to ~100 m here), so 1e-9 m leaves a margin of 10x or more
// while any formula error (e.g. a missing y term: ~0.1 m here) is far larger.
constexpr double kRoundOff = 1e-9;  // [m]

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

/// Columns of the last row equal `final` in summary.json exactly (both are the
/// same written value), and every column is in `final`.
void expect_final_is_last_row(const TextCsv& ts, const nlohmann::json& sm) {
  ASSERT_TRUE(sm.contains("final")) << sm.dump();
  const auto& fin = sm["final"];
  ASSERT_EQ(fin.size(), ts.header.size());
  const std::size_t last = ts.rows.size() - 1;
  for (const auto& name : ts.header) {
    ASSERT_TRUE(fin.contains(name)) << name;
    EXPECT_EQ(fin[name].get<double>(), ts.num(last, name)) << name;
  }
}

}  // namespace

TEST(RunOutputs, LaybackDeployedLengthFinalAndDepthsWithABody) {
  const fs::path dir = fresh_dir("out");
  // A cross current makes the layback three-dimensional (y != 0).
  const auto [status, out] = towsim_cli(
      "run --example paper-3d-turn --set simulation.duration=3 "
      "--set 'environment.current=[0,0.3,0]' --out '" +
      dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const TextCsv ts = read_text_csv(dir / "timeseries.csv");
  ASSERT_EQ(ts.rows.size(), 31u);
  ASSERT_GE(ts.col("layback"), 0);
  ASSERT_GE(ts.col("deployed_length"), 0);
  double min_d = 1e300, max_d = -1e300, max_l = -1e300, max_y = 0;
  for (std::size_t r = 0; r < ts.rows.size(); ++r) {
    // Layback: the geometric distance from the same row's tow and body columns.
    const double dx = ts.num(r, "body_x") - ts.num(r, "tow_x"), dy = ts.num(r, "body_y") - ts.num(r, "tow_y");
    EXPECT_NEAR(ts.num(r, "layback"), std::hypot(dx, dy), kRoundOff) << "row " << r;
    EXPECT_EQ(ts.num(r, "deployed_length"), 300.0) << "row " << r;  // paper-3d-turn: a 300 m cable, no winch
    min_d = std::min(min_d, ts.num(r, "body_depth"));
    max_d = std::max(max_d, ts.num(r, "body_depth"));
    max_l = std::max(max_l, ts.num(r, "layback"));
    max_y = std::max(max_y, std::abs(dy));
  }
  EXPECT_GT(max_y, 1e-3);  // the check above did exercise the y term
  const auto sm = read_json(dir / "summary.json");
  expect_final_is_last_row(ts, sm);
  EXPECT_EQ(sm["extremes"]["min_depth"]["value"].get<double>(), min_d);
  EXPECT_EQ(sm["extremes"]["max_depth"]["value"].get<double>(), max_d);
  EXPECT_EQ(sm["extremes"]["max_layback"]["value"].get<double>(), max_l);
  EXPECT_TRUE(sm["extremes"].contains("max_tow_tension"));  // kept
  // The end-of-run line gives the results first.
  EXPECT_NE(out.find("layback "), std::string::npos) << out;
  EXPECT_NE(out.find("body depth "), std::string::npos) << out;
  EXPECT_NE(out.find("tow tension "), std::string::npos) << out;
  EXPECT_NE(out.find("max tow tension "), std::string::npos) << out;
  fs::remove_all(dir);
}

TEST(RunOutputs, LaybackOfTheCableEndWithoutABodyAndTimesWithoutNoise) {
  const fs::path dir = fresh_dir("out");
  const auto [status,
              out] = towsim_cli("run --example cable-tow --set simulation.duration=1 --out '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const TextCsv ts = read_text_csv(dir / "timeseries.csv");
  ASSERT_EQ(ts.rows.size(), 11u);
  for (std::size_t r = 0; r < ts.rows.size(); ++r) {
    const double dx = ts.num(r, "end_x") - ts.num(r, "tow_x"), dy = ts.num(r, "end_y") - ts.num(r, "tow_y");
    EXPECT_NEAR(ts.num(r, "layback"), std::hypot(dx, dy), kRoundOff) << "row " << r;
    EXPECT_EQ(ts.num(r, "deployed_length"), 100.0);
  }
  // Times are k * 0.1 s written as such (3 * 0.1 is 0.30000000000000004 in
  // binary arithmetic), and no cell is round-off noise such as 1e-145.
  EXPECT_EQ(ts.rows[3][0], "0.3");
  EXPECT_EQ(ts.rows[7][0], "0.7");
  for (const auto& row : ts.rows)
    for (const auto& cell : row) {
      const auto e = cell.find('e');
      if (e != std::string::npos) {
        EXPECT_GE(std::stoi(cell.substr(e + 1)), -9) << cell;
      }
    }
  const auto sm = read_json(dir / "summary.json");
  expect_final_is_last_row(ts, sm);
  EXPECT_EQ(sm["extremes"]["max_depth"]["value"].get<double>(), sm["extremes"]["max_end_depth"]["value"].get<double>());
  EXPECT_NE(out.find("end depth "), std::string::npos) << out;
  fs::remove_all(dir);
}

TEST(NumberFormat, RoundOffIsZeroAndTimesAreRoundedToTheNanosecond) {
  EXPECT_EQ(towsim::output::tidy(1.57601e-145), 0.0);
  EXPECT_EQ(towsim::output::tidy(-3e-12), 0.0);
  EXPECT_EQ(towsim::output::tidy(2e-9), 2e-9);  // above the threshold: kept
  EXPECT_EQ(towsim::output::tidy(1.0 / 3.0), 0.333333333333);
  std::string s;
  towsim::output::put_time(s, 70884 * 0.1);  // 7088.400000000001 in binary arithmetic
  EXPECT_EQ(s, "7088.4");
  s.clear();
  towsim::output::put_time(s, 123456.123456789);  // nanoseconds kept for long runs
  EXPECT_EQ(s, "123456.123456789");
  s.clear();
  towsim::output::put_number(s, 1.57601e-145);
  EXPECT_EQ(s, "0");
}

// put_number and tidy round directly (a scaled integer); the reference is the
// standard library's "%.12g", std::to_chars(general, 12): the same bytes,
// over every decade the outputs see and beyond (the fallback), for random
// values, short decimals, and values whose 13th digit is a 5 (ties and
// near-ties, where the scaled product's round-off could matter).
TEST(NumberFormat, TwelveDigitsAreTheBytesOfToChars) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  auto reference = [](double v) {
    char b[64];
    const auto r = std::to_chars(b, b + sizeof b, std::abs(v) < towsim::output::kZeroBelow ? 0.0 : v,
                                 std::chars_format::general, 12);
    return std::string(b, r.ptr);
  };
  int mismatches = 0;
  auto check = [&](double v) {
    std::string s;
    towsim::output::put_number(s, v);
    if (s != reference(v) && ++mismatches <= 5) ADD_FAILURE() << "value " << v << ": " << s << " vs " << reference(v);
    // tidy: the double nearest to those digits, as std::from_chars reads them back.
    const std::string r = reference(v);
    double back = 0;
    std::from_chars(r.data(), r.data() + r.size(), back);
    const double t = towsim::output::tidy(v);
    if (std::isfinite(v) && !(t == back && std::signbit(t) == std::signbit(back)) && ++mismatches <= 5)
      ADD_FAILURE() << "tidy " << v << ": " << t << " vs " << back;
    // Writing needs no tidy first (nodes.csv writes values unrounded): the same bytes.
    std::string st;
    towsim::output::put_number(st, t);
    if (st != s && ++mismatches <= 5) ADD_FAILURE() << "put_number(tidy(" << v << ")): " << st << " vs " << s;
  };
  for (int i = 0; i < 200000; ++i) check((rng() & 1 ? -1 : 1) * std::pow(10.0, -14 + 30 * u(rng)));
  char buf[64];
  for (int i = 0; i < 100000; ++i) {
    const int digits = 1 + static_cast<int>(rng() % 13), exponent = -15 + static_cast<int>(rng() % 30);
    const long long m = static_cast<long long>(rng() % static_cast<unsigned long long>(std::pow(10, digits)));
    for (const char* tail : {"", "5", "4999999", "5000001"}) {
      std::snprintf(buf, sizeof buf, "%lld%se%d", m, tail, exponent);
      check(std::strtod(buf, nullptr));
    }
  }
  for (double v : {0.0,
                   1.0,
                   10.0,
                   1e11,
                   1e12,
                   999999999999.5,
                   999999999999.4,
                   99999999999.95,
                   99999999999.949997,
                   1e-4,
                   9.99999999999e-5,
                   9.999999999995e-5,
                   1e-9,
                   1.0 / 3,
                   -2.0 / 3,
                   123456789012.0,
                   1e300,
                   -1e-300,
                   std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN()})
    check(v);
  EXPECT_EQ(mismatches, 0);
}

TEST(RunOutputs, AReusedDirectoryKeepsNoStaleFileButKeepsOtherFiles) {
  const fs::path dir = fresh_dir("stale");
  for (const char* f : {"timeseries.csv", "nodes.csv", "summary.json", "report.html", "notes.txt", "my.csv"})
    std::ofstream(dir / f) << "old\n";
  fs::create_directories(dir / "plots");
  std::ofstream(dir / "plots" / "body_angles.png") << "old\n";
  // Invalid input: nothing written, nothing removed.
  auto [bad, bad_out] = towsim_cli("run --example cable-tow --set cable.elements=-1 --out '" + dir.string() + "'");
  EXPECT_EQ(bad, 2) << bad_out;
  EXPECT_TRUE(fs::exists(dir / "report.html"));
  EXPECT_TRUE(fs::exists(dir / "plots" / "body_angles.png"));
  // A run without nodes.csv: the old nodes.csv, plots/ and report.html go.
  const auto [status, out] = towsim_cli(
      "run --example cable-tow --set simulation.duration=0.5 "
      "--set simulation.write_nodes=false --out '" +
      dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  EXPECT_FALSE(fs::exists(dir / "nodes.csv"));
  EXPECT_FALSE(fs::exists(dir / "plots"));
  EXPECT_FALSE(fs::exists(dir / "report.html"));
  EXPECT_NE(read_text_csv(dir / "timeseries.csv").header.size(), 1u);
  // Files towsim does not write are kept.
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "my.csv"));
  fs::remove_all(dir);
}

TEST(StaticsOutputs, WritesSummaryWithFinalAndLayback) {
  const fs::path dir = fresh_dir("statics");
  std::ofstream(dir / "report.html") << "old\n";
  const auto [status, out] = towsim_cli("statics --example paper-planar-a --out '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  EXPECT_FALSE(fs::exists(dir / "report.html"));
  const TextCsv ts = read_text_csv(dir / "timeseries.csv");
  ASSERT_EQ(ts.rows.size(), 1u);
  const double dx = ts.num(0, "body_x") - ts.num(0, "tow_x"), dy = ts.num(0, "body_y") - ts.num(0, "tow_y");
  EXPECT_NEAR(ts.num(0, "layback"), std::hypot(dx, dy), kRoundOff);
  const auto sm = read_json(dir / "summary.json");
  expect_final_is_last_row(ts, sm);
  fs::remove_all(dir);
}

TEST(RunOutputs, TheProgressBarShowsSimulatedTime) {
  // The bar is drawn only on a terminal: `script` gives the run one.
  if (towsim::testing::shell("command -v script").first != 0) GTEST_SKIP() << "no `script` program (util-linux)";
  const fs::path dir = fresh_dir("progress");
  const auto [status, out] = towsim::testing::shell("script -qec \"'" + std::string(TOWSIM_BINARY) +
                                                    "' run --example cable-tow --set simulation.duration=2 --out '" +
                                                    dir.string() + "'\" /dev/null");
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("100% t = 2 / 2 s"), std::string::npos) << out;
  fs::remove_all(dir);
}
