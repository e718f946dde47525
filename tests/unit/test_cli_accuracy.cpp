// summary.json discretisation_error_estimate, its warning, and the element
// count `towsim check` advises (docs/scenario.md "summary.json").
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../support/cli.hpp"

namespace fs = std::filesystem;
using towsim::testing::CliResult;
using towsim::testing::quoted;
using towsim::testing::run_towsim;
using Accuracy = towsim::testing::TempDirTest;

namespace {

/// The JSON text after `"key": ` up to the end of its line.
std::string value_of(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\": ";
  const std::size_t at = json.find(k);
  if (at == std::string::npos) return "(absent)";
  const std::size_t from = at + k.size();
  return json.substr(from, json.find('\n', from) - from);
}

}  // namespace

TEST_F(Accuracy, PaperTowReportsItsEstimateWithoutWarning) {
  // 5 elements: 0.12 % (two significant digits), below the 1 % warning.
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim("run --example paper-planar-a --set simulation.duration=1 --out " + quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("discretisation"), std::string::npos) << r.out;
  const std::string summary = towsim::testing::slurp(out / "summary.json");
  EXPECT_EQ(value_of(summary, "discretisation_error_estimate"), "0.0012,");
  EXPECT_EQ(value_of(summary, "warnings"), "[],");
}

TEST_F(Accuracy, WellResolvedRunIsBelow1e3AndNotWarned) {
  // 20 elements: 2.0e-4 (the steady tension changes 1.5e-4 from 20 to 40).
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim(
      "run --example paper-planar-a --set cable.elements=20 --set simulation.duration=1 --out " + quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("discretisation"), std::string::npos) << r.out;
  const std::string summary = towsim::testing::slurp(out / "summary.json");
  const double e = std::stod(value_of(summary, "discretisation_error_estimate"));
  EXPECT_LT(e, 1e-3);
  EXPECT_GT(e, 0);
  EXPECT_EQ(value_of(summary, "warnings"), "[],");
}

TEST_F(Accuracy, CoarseCableIsWarnedOnStderrAndInTheSummary) {
  // Paper 5.2's 10 elements: the steady straight tow's tension changes 4.4 %
  // from 10 to 20 elements; the turn has no steady state of its own.
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim("run --example paper-3d-turn --set simulation.duration=0.1 --out " + quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string w =
      "discretisation error estimate 5.9 % of the tow tension exceeds 1 %: use more elements (more than 80 for "
      "0.1 %); from the steady tow at the final speed, which stands in for this run's unsteady conditions";
  EXPECT_NE(r.out.find("towsim: warning: " + w + "\n"), std::string::npos) << r.out;
  const std::string summary = towsim::testing::slurp(out / "summary.json");
  EXPECT_EQ(value_of(summary, "discretisation_error_estimate"), "0.059,");
  EXPECT_NE(summary.find("\"warnings\": [\n    \"" + w + "\"\n  ]"), std::string::npos) << summary;
}

TEST_F(Accuracy, QuietRunStillWritesTheWarning) {
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim("run --example paper-3d-turn --set simulation.duration=0.1 --quiet --out " +
                                 quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(towsim::testing::slurp(out / "summary.json").find("\"discretisation error estimate 5.9 %"),
            std::string::npos);
}

TEST_F(Accuracy, ForceModeHasNoEstimate) {
  const fs::path out = dir_ / "run";
  const CliResult r = run_towsim(
      "run --example cable-tow --set tow.mode=force --set 'tow.force=[100, 0, 0]' --set simulation.duration=0.1 "
      "--out " +
      quoted(out));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("discretisation"), std::string::npos) << r.out;
  const std::string summary = towsim::testing::slurp(out / "summary.json");
  EXPECT_EQ(value_of(summary, "discretisation_error_estimate"), "null,");
}

TEST_F(Accuracy, CheckAdvisesAnElementCount) {
  const CliResult r = run_towsim("check --example paper-planar-a");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("accuracy\n"
                       "  discretisation error        0.12 % of the steady tow tension at 2 m/s (825.4491998 N; "
                       "824.7003532 N with 10 elements)\n"
                       "  elements for 0.1 % tension  about 7\n"),
            std::string::npos)
      << r.out;
  const CliResult fine = run_towsim("check --example paper-planar-a --set cable.elements=20");
  EXPECT_NE(fine.out.find("  elements for 0.1 % tension  the present 20 are enough\n"), std::string::npos) << fine.out;
  const CliResult turn = run_towsim("check --example paper-3d-turn");
  EXPECT_NE(turn.out.find("  basis                       the steady tow at the final speed, standing in for this "
                          "run's unsteady conditions\n"),
            std::string::npos)
      << turn.out;
}
