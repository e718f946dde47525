// summary.json `phases` of runs of the built-in examples with turns and
// winch phases: each phase's extremes and settle times against a direct scan
// of the same run's timeseries.csv rows, and the marks and table of
// `towsim plot` and `towsim report`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/cli.hpp"
#include "towsim/output/output.hpp"
#include "towsim/output/transients.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using towsim::testing::CliResult;
using towsim::testing::Csv;
using towsim::testing::fresh_dir;
using towsim::testing::quoted;
using towsim::testing::read_csv;
using towsim::testing::run_towsim;
using towsim::testing::slurp;

namespace {

/// The documented figures of one column over rows with a <= time < b (extremes)
/// and a <= time < w (settling), each closed at the run's duration, from the rows alone.
struct Scan {
  double min = NAN, min_t = NAN, max = NAN, max_t = NAN;
  double settled = NAN, band = NAN, settle = NAN;
};

Scan scan(const Csv& ts, int col, double a, double b, double w, double duration, bool tension) {
  const int tc = ts.column("time");
  Scan s;
  std::vector<double> t, v;
  auto before = [duration](double time, double end) { return time < end || (time == end && end >= duration); };
  for (const auto& row : ts.rows) {
    const double time = row[static_cast<std::size_t>(tc)], x = row[static_cast<std::size_t>(col)];
    if (time < a || !before(time, w)) continue;
    t.push_back(time);
    v.push_back(x);
    if (!before(time, b)) continue;
    if (std::isnan(s.max) || x > s.max) s.max = x, s.max_t = time;
    if (std::isnan(s.min) || x < s.min) s.min = x, s.min_t = time;
  }
  if (v.empty()) return s;
  s.settled = v.back();
  s.band = std::max({towsim::output::kSettleChangeFraction * std::abs(v.back() - v.front()),
                     tension ? towsim::output::kSettleValueFraction * std::abs(v.back()) : 0.0,
                     tension ? towsim::output::kSettleTensionFloor : towsim::output::kSettleDepthFloor});
  std::size_t k = v.size() - 1;  // the first sample from which every later one is within the band
  while (k > 0 && std::abs(v[k - 1] - v.back()) <= s.band) --k;
  const double since = t[k];
  if (v.size() >= 2 && t.back() - since >= towsim::output::kSettleHoldFraction * (t.back() - a)) s.settle = since - a;
  return s;
}

/// A JSON number or NaN for null.
double number(const json& j) { return j.is_number() ? j.get<double>() : NAN; }

/// Equal, NaN matching NaN (null).
void expect_same(double got, double want, const std::string& what) {
  if (std::isnan(want))
    EXPECT_TRUE(std::isnan(got)) << what << ": " << got << ", expected null";
  else
    EXPECT_EQ(got, want) << what;
}

/// Run an example with overrides into `out`; every phase's figures against the rows.
json run_and_check(const std::string& args, const fs::path& out) {
  const CliResult r = run_towsim("run " + args + " --out " + quoted(out) + " --quiet");
  EXPECT_EQ(r.status, 0) << r.out;
  const Csv ts = read_csv(out / "timeseries.csv");
  const json sm = json::parse(slurp(out / "summary.json"));
  const bool body = ts.column("body_depth") >= 0;
  const std::vector<std::pair<std::string, std::string>> quantities{{"tow_tension", "tow_tension"},
                                                                    {"depth", body ? "body_depth" : "end_depth"},
                                                                    {"link_tension", "link_tension"}};
  EXPECT_TRUE(sm["phases"].is_array());
  const double duration = sm["scenario"]["simulation"]["duration"].get<double>();
  for (const auto& p : sm["phases"]) {
    const std::string name = p["name"].get<std::string>();
    const double a = p["start"].get<double>(), b = p["end"].get<double>(), w = p["settle_end"].get<double>();
    double settle[2] = {NAN, NAN};
    for (std::size_t q = 0; q < quantities.size(); ++q) {
      const auto& [key, column] = quantities[q];
      if (!body && key == "link_tension") {
        EXPECT_FALSE(p.contains(key)) << name;
        continue;
      }
      const std::string what = name + " " + key;
      if (!p.contains(key)) {
        ADD_FAILURE() << what << ": missing";
        continue;
      }
      const Scan s = scan(ts, ts.column(column), a, b, w, duration, key != "depth");
      const json& j = p[key];
      expect_same(number(j["min"]["value"]), s.min, what + " min");
      expect_same(number(j["min"]["time"]), s.min_t, what + " min time");
      expect_same(number(j["max"]["value"]), s.max, what + " max");
      expect_same(number(j["max"]["time"]), s.max_t, what + " max time");
      expect_same(number(j["settled_value"]), s.settled, what + " settled value");
      expect_same(number(j["band"]), towsim::output::tidy(s.band), what + " band");
      expect_same(number(j["settle_time"]), towsim::output::tidy_time(s.settle), what + " settle time");
      if (q < 2) settle[q] = s.settle;
    }
    expect_same(number(p["settle_time"]),
                std::isnan(settle[0]) || std::isnan(settle[1])
                    ? NAN
                    : towsim::output::tidy_time(std::max(settle[0], settle[1])),
                name + " settle time");
  }
  return sm;
}

/// name, kind, source, start, end of each phase, one line each.
std::string outline(const json& sm) {
  std::string s;
  for (const auto& p : sm["phases"]) {
    char b[64];
    std::snprintf(b, sizeof b, " %.9g %.9g %.9g\n", p["start"].get<double>(), p["end"].get<double>(),
                  p["settle_end"].get<double>());
    s += p["name"].get<std::string>() + " " + p["kind"].get<std::string>() + " " +
         (p["source"].is_null() ? std::string("-") : p["source"].get<std::string>()) + b;
  }
  return s;
}

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

}  // namespace

TEST(PhasesRun, WinchPayOutAndHaulInOfFishDepthChange) {
  const fs::path out = fresh_dir("phases_winch");
  const json sm = run_and_check("--example fish-depth-change", out);
  EXPECT_EQ(outline(sm),
            "steady 1 steady - 0 60 60\n"
            "pay_out 1 pay_out winch 60 370 700\n"
            "steady 2 steady - 370 700 700\n"
            "haul_in 1 haul_in winch 700 1010 1300\n"
            "steady 3 steady - 1010 1300 1300\n");
  fs::remove_all(out);
}

TEST(PhasesRun, ATurnBetweenSteadyTowsOfTwoPartTow) {
  const fs::path out = fresh_dir("phases_turn");
  // The turn at 100 s (not 300 s) and 400 s after it: a shorter run, the same manoeuvre.
  const json sm =
      run_and_check("--example two-part-tow --set tow.motion.1.start_time=100 --set simulation.duration=800", out);
  EXPECT_EQ(outline(sm),
            "steady 1 steady - 0 100 100\n"
            "turn 1 turn tow.motion.1 100 405.338379 800\n"
            "steady 2 steady - 405.338379 800 800\n");
  fs::remove_all(out);
}

TEST(PhasesRun, PlotsMarkThePhasesAndTheReportTablesThem) {
  const fs::path out = fresh_dir("phases_plot");
  const json sm = run_and_check("--example paper-3d-turn --set simulation.duration=40", out);
  EXPECT_EQ(outline(sm),
            "accelerate 1 accelerate tow.motion.0 0 15 15\n"
            "turn 1 turn tow.motion.1 15 40 40\n");
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const CliResult r = run_towsim("report " + quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  // The time figures: a dashed line at each boundary, labelled.
  for (const char* fig : {"tow_force", "end_depth", "body_angles", "link_force"}) {
    const std::string gp = slurp(out / "plots" / (std::string(fig) + ".gp"));
    EXPECT_NE(gp.find("set arrow 1 from 0, graph 0 to 0, graph 1 nohead dt 2"), std::string::npos) << fig;
    EXPECT_NE(gp.find("set label 1 'accelerate 1' at 0, graph 0.98 rotate by 90"), std::string::npos) << fig;
    EXPECT_NE(gp.find("set arrow 2 from 15, graph 0 to 15, graph 1 nohead dt 2"), std::string::npos) << fig;
    EXPECT_NE(gp.find("set label 2 'turn 1, accelerate 1 end' at 15, graph 0.98"), std::string::npos) << fig;
    EXPECT_EQ(gp.find("set arrow 3 "), std::string::npos) << fig;  // the turn's end is the run's
  }
  const std::string map = slurp(out / "plots" / "tension_map.gp");
  EXPECT_NE(map.find("set arrow 2 from first 15, graph 0, graph 1 to first 15, graph 1, graph 1 nohead"),
            std::string::npos);
  EXPECT_EQ(slurp(out / "plots" / "trajectories_xz.gp").find("set arrow"), std::string::npos);  // not a time axis
  // The report's table: a unit in every numeric header, one row per phase.
  const std::string page = slurp(out / "report.html");
  EXPECT_NE(page.find("<h2>Phases</h2>"), std::string::npos);
  EXPECT_NE(page.find("<tr><th>phase</th><th>source</th><th>start [s]</th><th>end [s]</th>"
                      "<th>min tow tension [N]</th><th>at t [s]</th><th>max tow tension [N]</th><th>at t [s]</th>"
                      "<th>min depth [m]</th><th>at t [s]</th><th>max depth [m]</th><th>at t [s]</th>"
                      "<th>max link tension [N]</th><th>at t [s]</th>"
                      "<th>tow tension settle time [s]</th><th>depth settle time [s]</th>"
                      "<th>settled tow tension [N]</th><th>settled depth [m]</th><th>settle window end [s]</th></tr>"),
            std::string::npos);
  EXPECT_NE(page.find("<tr><td>accelerate 1</td><td>tow.motion.0</td><td class=\"n\">0</td><td class=\"n\">15</td>"),
            std::string::npos);
  EXPECT_NE(page.find("<tr><td>turn 1</td><td>tow.motion.1</td><td class=\"n\">15</td><td class=\"n\">40</td>"),
            std::string::npos);
  fs::remove_all(out);
}

TEST(PhasesRun, StaticsWritesNoPhases) {
  const fs::path out = fresh_dir("phases_statics");
  const CliResult r = run_towsim("statics --example two-part-tow --out " + quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  const json sm = json::parse(slurp(out / "summary.json"));
  EXPECT_FALSE(sm.contains("phases"));
  EXPECT_TRUE(sm.contains("final"));
  fs::remove_all(out);
}
