// The winch through the program: outputs stay well-formed while the element
// count changes (timeseries.csv, nodes.csv with node_id, summary.json), and
// `towsim statics --target-depth`.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "../support/cli.hpp"

namespace fs = std::filesystem;
using towsim::testing::CliResult;
using towsim::testing::fresh_dir;
using towsim::testing::quoted;
using towsim::testing::read_csv;
using towsim::testing::run_towsim;
using towsim::testing::slurp;

// fish-depth-change up to 450 s: 600 -> 900 m (ten 30 m elements added).
TEST(WinchRun, OutputsFollowTheChangingChain) {
  const fs::path out = fresh_dir("winch_run");
  const CliResult r = run_towsim("run --example fish-depth-change --set simulation.duration=450 --out " + quoted(out) +
                                 " --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto ts = read_csv(out / "timeseries.csv");
  const int len = ts.column("deployed_length"), speed = ts.column("payout_speed"),
            ratio = ts.column("winch_load_ratio");
  ASSERT_GE(len, 0);
  ASSERT_GE(speed, 0);
  ASSERT_GE(ratio, 0);
  ASSERT_EQ(ts.rows.size(), 451u);
  EXPECT_DOUBLE_EQ(ts.rows[0][len], 600);
  EXPECT_DOUBLE_EQ(ts.rows[200][len], 735);  // 5 m in the ramp, then 1 m/s from 70 s
  EXPECT_DOUBLE_EQ(ts.rows[200][speed], 1);
  EXPECT_DOUBLE_EQ(ts.rows[450][len], 900);
  EXPECT_DOUBLE_EQ(ts.rows[450][speed], 0);
  EXPECT_NEAR(ts.rows[450][ratio], ts.rows[450][ts.column("tow_tension")] / 5e4, 1e-9);
  // nodes.csv: node 0..N-1 at each time, N = deployed elements + 1; node_id stable.
  const auto nodes = read_csv(out / "nodes.csv");
  ASSERT_GE(nodes.header.size(), 3u);
  EXPECT_EQ(nodes.header[2], "node_id");
  std::map<double, std::vector<std::pair<int, int>>> at;  // time -> (node, node_id)
  for (const auto& row : nodes.rows) at[row[0]].emplace_back(static_cast<int>(row[1]), static_cast<int>(row[2]));
  ASSERT_EQ(at.size(), 451u);
  EXPECT_EQ(at[0.0].size(), 21u);
  EXPECT_EQ(at[450.0].size(), 31u);
  for (const auto& [t, rows] : at) {
    std::set<int> ids;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      EXPECT_EQ(rows[k].first, static_cast<int>(k)) << "t = " << t;
      ids.insert(rows[k].second);
    }
    EXPECT_EQ(ids.size(), rows.size()) << "t = " << t;  // identities are unique
    EXPECT_EQ(rows.front().second, 0);                  // the sheave
    EXPECT_EQ(rows.back().second, 20);                  // the cable's end keeps its identity
    EXPECT_EQ(rows[rows.size() - 2].second, 19);
  }
  // The joints added at the top are numbered in order of creation.
  EXPECT_EQ(at[450.0][1].second, 30);
  EXPECT_EQ(at[450.0][10].second, 21);
  const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(summary["winch"]["splits"], 10);
  EXPECT_EQ(summary["winch"]["removals"], 0);
  EXPECT_EQ(summary["winch"]["rating"], 5e4);
  EXPECT_EQ(summary["final"]["deployed_length"], 900);
}

TEST(WinchRun, StaticsTargetDepth) {
  const fs::path out = fresh_dir("winch_statics");
  const CliResult r = run_towsim("statics --example fish-depth-change --target-depth 300 --out " + quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("deployed length for a depth of 300 m: 796.52"), std::string::npos) << r.out;
  const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_NEAR(summary["target_depth"]["reached_depth"].get<double>(), 300, 1e-6);
  EXPECT_NEAR(summary["final"]["deployed_length"].get<double>(),
              summary["target_depth"]["deployed_length"].get<double>(), 1e-6);
  const CliResult bad = run_towsim("statics --example fish-depth-change --target-depth -3");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.out, "towsim: statics: --target-depth must be > 0 (got -3)\n");
}
