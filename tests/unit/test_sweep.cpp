#include <algorithm>
// Sweeps (issue 16): the sweep file's expansion into cases, value texts that
// read back as the same YAML, summary figures, and the columns shared by the
// files and the Python module.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/scenario_files.hpp"
#include "sweep.hpp"
#include "towsim/output/output.hpp"

using namespace towsim::cli;
using namespace towsim::scenario;
using namespace towsim::output;

namespace {

class Sweep : public towsim::testing::ScenarioFiles {};

/// "k=v" of a case's overrides.
std::vector<std::string> sets_of(const SweepCase& c) {
  std::vector<std::string> out;
  for (const auto& [k, v] : c.sets) out.push_back(k + "=" + v);
  return out;
}

}  // namespace

TEST_F(Sweep, GridIsAProductWithTheLastKeyFastestTimesTheList) {
  Diagnostics d;
  const auto spec = read_sweep(write("example: cable-tow\n"
                                     "set: {simulation.duration: 2}\n"
                                     "grid: {a.b: [1, 2], c: [x, y, z]}\n"
                                     "cases: [{d: 1}, {d: 2, e: [1, 2]}]\n"),
                               d);
  ASSERT_TRUE(d.ok()) << d.str();
  EXPECT_EQ(spec.example, "cable-tow");
  EXPECT_EQ(spec.common, std::vector<std::string>{"simulation.duration=2"});
  EXPECT_EQ(spec.keys, (std::vector<std::string>{"a.b", "c", "d", "e"}));
  ASSERT_EQ(spec.cases.size(), 12u);  // 2 x 3 grid points x 2 list entries
  EXPECT_EQ(sets_of(spec.cases[0]), (std::vector<std::string>{"a.b=1", "c=x", "d=1"}));
  EXPECT_EQ(sets_of(spec.cases[1]), (std::vector<std::string>{"a.b=1", "c=y", "d=1"}));
  EXPECT_EQ(sets_of(spec.cases[3]), (std::vector<std::string>{"a.b=2", "c=x", "d=1"}));
  EXPECT_EQ(sets_of(spec.cases[11]), (std::vector<std::string>{"a.b=2", "c=z", "d=2", "e=[1, 2]"}));
  EXPECT_FALSE(spec.write_cases);
}

TEST_F(Sweep, ValuesReadBackAsTheSameYaml) {
  // Each value becomes the VALUE of --set KEY=VALUE: applied to a tree, it
  // must give what the sweep file says (strings with flow characters quoted).
  Diagnostics d;
  const auto spec = read_sweep(write("scenario: s.yaml\n"
                                     "cases:\n"
                                     "  - {name: 'a, b: c', v: \"1.5\", m: {law: skin, ct: 0.01}, n: null}\n"),
                               d);
  ASSERT_TRUE(d.ok()) << d.str();
  EXPECT_EQ(spec.scenario, (std::filesystem::path(dir_) / "s.yaml").string());  // beside the sweep file
  YNode root = parse_yaml("{}", "t", d);
  const auto sets = sets_of(spec.cases[0]);
  for (std::size_t i = 0; i < sets.size(); ++i) apply_set(root, sets[i], static_cast<int>(i) + 1, d);
  ASSERT_TRUE(d.ok()) << d.str();
  const auto j = to_json(root);
  EXPECT_EQ(j["name"], "a, b: c");
  EXPECT_EQ(j["v"], "1.5");  // quoted in the file: stays a string
  EXPECT_EQ(j["m"]["law"], "skin");
  EXPECT_EQ(j["m"]["ct"], 0.01);
  EXPECT_TRUE(j["n"].is_null());
}

TEST_F(Sweep, TooManyCasesAreRefusedBeforeExpanding) {
  Diagnostics d;
  std::string values = "[";
  for (int i = 0; i < 100; ++i) values += std::to_string(i) + (i < 99 ? ", " : "]");
  read_sweep(write("example: cable-tow\ngrid: {a: " + values + ", b: " + values + ", c: " + values + "}\n"), d);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d.list()[0].str().substr(d.list()[0].str().find(": grid")),
            ": grid: expands to 1000000 cases (at most 100000)");
}

TEST(SweepFigures, SummaryFlattenedByName) {
  nlohmann::ordered_json s = {
      {"status", "ok"},
      {"end_time", 5.0},
      {"max_element_drift", 1e-12},
      {"extremes",
       {{"max_tow_tension", {{"value", 10.0}, {"time", 1.0}}},
        {"max_link_force", {{"value", nullptr}, {"time", nullptr}}},
        {"body_roll_deg", {{"min", {{"value", -1.0}, {"time", 2.0}}}, {"max", {{"value", 3.0}, {"time", 4.0}}}}}}},
      {"max_utilisation", {{"value", 0.5}, {"time", 3.0}}},
      {"final", {{"time", 5.0}, {"end_depth", 42.0}}}};
  const auto f = summary_figures(s);
  ASSERT_EQ(f.size(), 8u);
  EXPECT_EQ(f[0], (Figure{"end_time", 5.0}));
  EXPECT_EQ(f[1], (Figure{"max_tow_tension", 10.0}));
  EXPECT_EQ(f[2].first, "max_link_force");
  EXPECT_TRUE(std::isnan(f[2].second));  // null: no value
  EXPECT_EQ(f[3], (Figure{"body_roll_deg_min", -1.0}));
  EXPECT_EQ(f[4], (Figure{"body_roll_deg_max", 3.0}));
  EXPECT_EQ(f[5], (Figure{"max_utilisation", 0.5}));  // max_element_drift is not a result
  EXPECT_EQ(f[6], (Figure{"final_time", 5.0}));
  EXPECT_EQ(f[7], (Figure{"final_end_depth", 42.0}));
}

TEST(SweepFigures, ValuesMatchTheColumns) {
  // The one function behind timeseries.csv and the Python arrays gives one
  // value per column, with and without a body.
  towsim::Sample s;
  s.node_pos = {towsim::Vec3(0, 0, 0), towsim::Vec3(1, 0, -2)};
  for (bool body : {false, true}) {
    towsim::Model m;
    m.cable.elements.resize(1);
    if (body) m.bodies.emplace_back();
    s.bodies.resize(body ? 1 : 0);
    std::vector<double> v;
    timeseries_values(m, s, v);
    const auto cols = timeseries_columns(m);
    EXPECT_EQ(v.size(), cols.size());
    const auto at = std::find(cols.begin(), cols.end(), "end_depth") - cols.begin();
    EXPECT_EQ(v[static_cast<std::size_t>(at)], 2.0);  // end_depth
  }
  std::vector<double> n;
  node_values(s, 1, n);
  EXPECT_EQ(n.size(), node_columns().size());
}
