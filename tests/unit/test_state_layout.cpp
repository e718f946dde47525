// The flat state's layout (StateLayout) against the systems that use it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "towsim/integrators/state_layout.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"

namespace towsim {
namespace {

/// A built-in example with --set overrides, compiled.
Model example_model(const std::string& name, const std::vector<std::string>& sets = {}) {
  const scenario::Example* e = scenario::find_example(name);
  EXPECT_NE(e, nullptr) << name;
  if (e == nullptr) return Model{};
  scenario::LoadedScenario sc = scenario::load_scenario_text(e->yaml, name + ".yaml", name, "", sets);
  EXPECT_TRUE(sc.ok()) << sc.diags.str();
  return sc.ok() ? *sc.model : Model{};
}

/// The blocks follow each other without gaps and end at the state's size.
void expect_contiguous(const StateLayout& l) {
  std::size_t end = 0;
  for (const StateBlock* b : {&l.tow, &l.directions, &l.rates, &l.bodies, &l.winch, &l.lengths, &l.controls, &l.angles,
                              &l.angle_rates, &l.charts}) {
    EXPECT_EQ(b->offset, end);
    end = b->end();
  }
  EXPECT_EQ(end, l.size);
}

/// The layout sizes the system's state and names its rows as the system does.
void expect_matches(const Model& m, const StateLayout& l, const std::string& what) {
  const auto sys = make_system(m);
  const StateVector y = sys->initial(PhysicalState::hanging(m), 0.0);
  ASSERT_EQ(y.size(), l.size) << what;
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_EQ(sys->describe(i), l.describe(i, m)) << what << " row " << i;
}

TEST(StateLayout, DefaultBlocksOfEveryExample) {
  for (const char* name : {"cable-tow", "fish-depth-change", "fish-depth-control", "paper-3d-turn", "paper-planar-a",
                           "paper-planar-b", "sea-state-tow", "two-part-tow"}) {
    const Model m = example_model(name);
    const StateLayout l = StateLayout::default_of(m);
    expect_contiguous(l);
    const std::size_t n = m.cable.elements.size();
    EXPECT_EQ(l.directions.size, 3 * n) << name;
    EXPECT_EQ(l.bodies.size, StateLayout::kBodyRows * m.bodies.size()) << name;
    EXPECT_EQ(l.winch.size, m.winch.active() ? 2u : 0u) << name;
    EXPECT_EQ(l.charts.size, 0u) << name;
    expect_matches(m, l, name);
    const auto sys = make_system(m);
    for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(sys->element_rate_row(k), l.rate(k)) << name;
    for (std::size_t b = 0; b < m.bodies.size(); ++b) EXPECT_EQ(sys->body_rate_row(b), l.body(b) + 4) << name;
  }
}

TEST(StateLayout, DepthControllersAndElasticLengths) {
  const Model control = example_model("fish-depth-control");
  EXPECT_GT(StateLayout::default_of(control).controls.size, 0u);
  const Model elastic = example_model("cable-tow", {"cable.axial_stiffness=1e7"});
  const StateLayout l = StateLayout::default_of(elastic);
  EXPECT_EQ(l.lengths.size, 2 * elastic.cable.elements.size());
  expect_contiguous(l);
  expect_matches(elastic, l, "elastic cable-tow");
}

TEST(StateLayout, PaperBlocksCarryTheCharts) {
  for (const char* name : {"cable-tow", "paper-3d-turn", "paper-planar-a"}) {
    const Model m = example_model(name, {"simulation.formulation=paper"});
    const StateLayout l = StateLayout::paper_of(m);
    expect_contiguous(l);
    EXPECT_EQ(l.charts.size, StateLayout::kChartRows * (m.cable.elements.size() + m.bodies.size())) << name;
    EXPECT_EQ(l.directions.size + l.bodies.size + l.controls.size, 0u) << name;
    expect_matches(m, l, name);
  }
}

}  // namespace
}  // namespace towsim
