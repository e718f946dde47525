// The element count's share of the error (summary.json
// discretisation_error_estimate, docs/theory.md §7.1): the order it assumes is
// measured, the refined cable is the compiled one, and the estimate is checked
// against the true error of a run on paper 5.1's 5-element tow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "../support/physics.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/discretisation.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

/// A built-in example compiled with `sets`.
Model example(const std::string& name, const std::vector<std::string>& sets = {}) {
  const scenario::Example* ex = scenario::find_example(name);
  EXPECT_NE(ex, nullptr) << name;
  const scenario::LoadedScenario sc = scenario::load_scenario_text(ex->yaml, name + ".yaml", name, ".", sets);
  EXPECT_TRUE(sc.ok()) << sc.diags.str();
  return *sc.model;
}

/// A scenario file of the source tree compiled with `sets`.
Model scenario_file(const std::string& path, const std::vector<std::string>& sets = {}) {
  const scenario::LoadedScenario sc = scenario::load_scenario_file(std::string(TOWSIM_SOURCE_DIR) + "/" + path, sets);
  EXPECT_TRUE(sc.ok()) << sc.diags.str();
  return *sc.model;
}

/// Steady tow tension at the tow law's final velocity [N].
double steady_tension(const Model& m) {
  const StaticsResult r = solve_statics(m, final_tow_velocity(m.tow));
  EXPECT_TRUE(r.converged) << r.message;
  return r.tow_force.norm();
}

/// The order p measured from the steady tensions at n, 2n and 4n elements:
/// (T_n - T_2n) / (T_2n - T_4n) = 2^p.
double measured_order(const Model& m) {
  const double t1 = steady_tension(m), t2 = steady_tension(refined_model(m, 2)),
               t4 = steady_tension(refined_model(m, 4));
  return std::log2(std::abs(t1 - t2) / std::abs(t2 - t4));
}

TEST(DiscretisationEstimate, OrderOfTheSteadyTowTensionIsTwo) {
  // kDiscretisationOrder = 2 is a measurement: the ratio of successive
  // differences of the steady tow tension, in the asymptotic range, on paper
  // 5.1's tow (20-40-80 elements) and the 1 km, 100-element turn (100-200-400).
  // Tolerance 0.1 on p: the measured values are 1.96-2.00; below the
  // asymptotic range (5-10-20 on paper 5.1) p is 0.8 (docs/validation.md).
  constexpr double kOrderTolerance = 0.1;
  const double p_paper = measured_order(example("paper-planar-a", {"cable.elements=20"}));
  const double p_km = measured_order(scenario_file("bench/scenarios/km-turn-100.yaml"));
  std::cout << "[measured] order of the steady tow tension: paper 5.1 " << p_paper << ", km-turn-100 " << p_km
            << " (tol " << kOrderTolerance << ")\n";
  EXPECT_NEAR(p_paper, kDiscretisationOrder, kOrderTolerance);
  EXPECT_NEAR(p_km, kDiscretisationOrder, kOrderTolerance);
}

TEST(DiscretisationEstimate, RefinedModelIsTheCompiledRefinement) {
  // Splitting each element in two in the compiled model is the same cable as
  // compiling twice the elements: sections and an in-line body
  // (two-part-tow), and an attachment at a joint of both. Relative 1e-9: the
  // two steady solves converge to angular accelerations below 1e-9 rad/s^2.
  constexpr double kSame = 1e-9;
  const Model parts = example("two-part-tow");
  const double split = steady_tension(refined_model(parts, 2));
  const double compiled = steady_tension(
      example("two-part-tow", {"cable.sections.0.elements=60", "cable.sections.2.elements=20"}));
  EXPECT_NEAR(split, compiled, kSame * compiled);
  const std::vector<std::string> clump = {"cable.attachments=[{at: 60, mass: 40, volume: 0.002, drag_area: 0.05}]"};
  std::vector<std::string> clump10 = clump;
  clump10.emplace_back("cable.elements=10");
  const double split_clump = steady_tension(refined_model(example("paper-planar-a", clump), 2));
  const double compiled_clump = steady_tension(example("paper-planar-a", clump10));
  EXPECT_NEAR(split_clump, compiled_clump, kSame * compiled_clump);
}

TEST(DiscretisationEstimate, PaperTowWithinAFactorOf3OfTheTrueError) {
  // Paper 5.1, law A, at its own 5 elements and default settings: the
  // estimate against the true error of the run's final tow tension (at 200 s,
  // within 0.1 % of steady) and of its peak (the start-up transient), both
  // measured against the run with 40 elements (its own error from the
  // element count is 2.4 % of the 5-element run's). The factor 3 is the
  // contract (docs/scenario.md); measured: 0.73 and 0.43.
  constexpr double kFactor = 3;
  const Model coarse = example("paper-planar-a");
  const DiscretisationEstimate d = estimate_discretisation_error(coarse);
  ASSERT_TRUE(d.available()) << d.message;
  EXPECT_FALSE(d.proxy);
  // The reference: 40 elements, rosenbrock at tolerance 1e-8 (its time error
  // is below 1e-6 of the tension, far below the 1.7e-3 measured).
  Model fine = example("paper-planar-a",
                       {"cable.elements=40", "simulation.integrator=rosenbrock", "simulation.tolerance=1e-8"});
  Model run5 = coarse;
  run5.sim.write_nodes = fine.sim.write_nodes = false;
  const std::vector<Sample> a = testing::run(run5), b = testing::run(fine);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  auto peak = [](const std::vector<Sample>& s) {
    double m = 0;
    for (const Sample& x : s) m = std::max(m, x.tow_force.norm());
    return m;
  };
  const double final_true = std::abs(a.back().tow_force.norm() / b.back().tow_force.norm() - 1);
  const double peak_true = std::abs(peak(a) / peak(b) - 1);
  std::cout << "[measured] paper 5.1, 5 elements: estimate " << d.estimate << "; true error of the final tow tension "
            << final_true << " (ratio " << d.estimate / final_true << "), of the peak " << peak_true << " (ratio "
            << d.estimate / peak_true << "), tol factor " << kFactor << "\n";
  EXPECT_GT(d.estimate, final_true / kFactor);
  EXPECT_LT(d.estimate, final_true * kFactor);
  EXPECT_GT(d.estimate, peak_true / kFactor);
  EXPECT_LT(d.estimate, peak_true * kFactor);
}

TEST(DiscretisationEstimate, AdviceMeetsTheAccuracyItIsFor) {
  // The count advised for 0.1 % on paper 5.1's tow, checked against the
  // steady tension of 640 elements (converged to 2e-7): the advised count's
  // true error is within a factor 1.5 of 0.1 % (Richardson's estimate at the
  // advised count is itself within a factor 3; measured here: 1.2e-3 at 7).
  constexpr double kWithin = 1.5;
  const Model m = example("paper-planar-a");
  const DiscretisationEstimate d = estimate_discretisation_error(m);
  const ElementAdvice a = advise_elements(m, d, kAdvisedAccuracy, 64);
  ASSERT_GT(a.elements, 0);
  EXPECT_FALSE(a.enough);
  EXPECT_FALSE(a.beyond);
  const double converged = steady_tension(example("paper-planar-a", {"cable.elements=640"}));
  const double at_advice = steady_tension(example("paper-planar-a", {"cable.elements=" + std::to_string(a.elements)}));
  const double err = std::abs(at_advice / converged - 1);
  std::cout << "[measured] paper 5.1: advised " << a.elements << " elements for 0.1 %: true error " << err << "\n";
  EXPECT_LT(err, kWithin * kAdvisedAccuracy);
}

TEST(DiscretisationEstimate, NoneInForceMode) {
  Model m = example("paper-planar-a");
  m.tow.mode = Tow::Mode::Force;
  m.tow.force_time = {0};
  m.tow.force_value = {Vec3(100, 0, 0)};
  const DiscretisationEstimate d = estimate_discretisation_error(m);
  EXPECT_FALSE(d.available());
  EXPECT_EQ(discretisation_warning(d, {}), "");
}

}  // namespace
}  // namespace towsim
