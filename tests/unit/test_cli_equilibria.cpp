// `towsim statics`: the equilibria of the bodies, their stability, the
// warning of several stable trims, trim jumps in a statics sweep, and
// --trim (the link point for a level body). two-part-tow's depressor: its
// trim passes from nose up to nose down near 561.6 kg, where for about
// 0.01 kg it has two stable balances.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "../support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace towsim::testing;

const std::string kMass = "cable.sections.1.body.mass";

/// The depressor's pitch as `towsim statics` prints it (its "body depressor:" line) [deg].
double depressor_pitch(const std::string& out) {
  std::smatch m;
  const std::regex re(R"(body depressor: depth \S+ m, roll/pitch/yaw \(\s*(\S+)\s+(\S+)\s+(\S+)\) deg)");
  if (!std::regex_search(out, m, re)) return std::nan("");
  return std::stod(m[2].str());
}

TEST(CliEquilibria, TwoPartTowConvergesWithoutHintsFrom300To2000Kg) {
  // Pitch to 1e-3 deg: the printed six digits; one stable balance each.
  const std::vector<std::pair<int, double>> expected{{300, 53.873},  {500, 24.3337},   {550, 10.0755},
                                                     {600, -13.033}, {1000, -24.7191}, {2000, -28.394}};
  for (const auto& [mass, pitch] : expected) {
    const auto [status, out] = run_towsim("statics --example two-part-tow --set " + kMass + "=" + std::to_string(mass));
    EXPECT_EQ(status, 0) << mass << " kg\n" << out;
    EXPECT_NEAR(depressor_pitch(out), pitch, 1e-3) << mass << " kg";
    EXPECT_EQ(out.find("warning"), std::string::npos) << out;
    const auto from = out.find("equilibria of body depressor");
    ASSERT_NE(from, std::string::npos) << out;
    const std::string list = out.substr(from, out.find("  body:", from) - from);
    EXPECT_EQ(std::count(list.begin(), list.end(), '\n'), 2) << list;  // the heading and one balance
    EXPECT_NE(list.find("deg: stable, stiffness"), std::string::npos) << list;
  }
}

TEST(CliEquilibria, BothBranchesAtTheFlipAreListedWithTheirStability) {
  const fs::path dir = fresh_dir("equilibria_flip") / "out";
  const auto [status,
              out] = run_towsim("statics --example two-part-tow --set " + kMass + "=561.62 --out " + quoted(dir));
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("towsim: statics: warning: trim of body depressor: two stable equilibria, +0.3 and -0.5 deg "
                     "pitch; reported +0.3, the one reached from its initial attitude (an initial_attitude_deg near "
                     "another selects it)\n"),
            std::string::npos)
      << out;
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  ASSERT_EQ(j["bodies"].size(), 2u);
  const auto& dep = j["bodies"][0];
  EXPECT_EQ(dep["name"], "depressor");
  ASSERT_EQ(dep["equilibria"].size(), 3u);           // nose up, the unstable one between, nose down
  const double pitch[] = {0.3467, 0.0470, -0.4865};  // [deg] to 1e-3 (four digits printed)
  const bool stable[] = {true, false, true};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(dep["equilibria"][i]["pitch_deg"].get<double>(), pitch[i], 1e-3) << i;
    EXPECT_EQ(dep["equilibria"][i]["stable"].get<bool>(), stable[i]) << i;
    EXPECT_EQ(dep["equilibria"][i]["pitch_stiffness"].get<double>() > 0, stable[i]) << i;
  }
  EXPECT_EQ(dep["chosen"], 0);
  EXPECT_EQ(j["bodies"][1]["name"], "body");
  EXPECT_EQ(j["bodies"][1]["equilibria"].size(), 1u);
  ASSERT_EQ(j["warnings"].size(), 1u);
  EXPECT_EQ(j["warnings"][0],
            "trim of body depressor: two stable equilibria, +0.3 and -0.5 deg pitch; reported +0.3, the one reached "
            "from its initial attitude (an initial_attitude_deg near another selects it)");
  fs::remove_all(dir.parent_path());
}

TEST(CliEquilibria, StaticsSweepReportsTheFlip) {
  const fs::path dir = fresh_dir("equilibria_sweep");
  std::ofstream(dir / "sweep.yaml") << "example: two-part-tow\nstatics: true\ngrid:\n  " << kMass
                                    << ": [500, 561.6, 561.62, 561.64, 600]\n";
  const auto [status,
              out] = run_towsim("sweep " + quoted(dir / "sweep.yaml") + " --out " + quoted(dir / "out") + " --jobs 2");
  EXPECT_EQ(status, 0) << out;
  const std::string w = "towsim: sweep: warning: trim of body depressor between neighbouring cases ";
  for (const std::string& line : {w + "case-0000 (" + kMass + "=500) and case-0001 (" + kMass +
                                      "=561.6): pitch +24.3 to +0.6 deg, a change of more than 10 deg\n",
                                  w + "case-0001 (" + kMass + "=561.6) and case-0002 (" + kMass +
                                      "=561.62): stable equilibria 1 to 2, a change of branch\n",
                                  w + "case-0002 (" + kMass + "=561.62) and case-0003 (" + kMass +
                                      "=561.64): stable equilibria 2 to 1, a change of branch\n",
                                  w + "case-0003 (" + kMass + "=561.64) and case-0004 (" + kMass +
                                      "=600): pitch -0.7 to -13.0 deg, a change of more than 10 deg\n"})
    EXPECT_NE(out.find(line), std::string::npos) << line << "\n" << out;
  size_t warnings = 0;
  for (auto p = out.find("sweep: warning"); p != std::string::npos; p = out.find("sweep: warning", p + 1)) ++warnings;
  EXPECT_EQ(warnings, 4u) << out;
  fs::remove_all(dir);
}

TEST(CliEquilibria, TrimGivesALinkPointThatLevelsTheDepressor) {
  const auto [status, out] = run_towsim("statics --example two-part-tow --trim depressor");
  ASSERT_EQ(status, 0) << out;
  std::smatch m;
  const std::regex re(R"(--set '([^']+)'\))");
  ASSERT_TRUE(std::regex_search(out, m, re)) << out;
  EXPECT_EQ(m[1].str().rfind("cable.sections.1.body.link_point=[0.111973", 0), 0u) << m[1];
  // Passed back: level to the search's tolerance (kTrimTolerance, 1e-4 deg).
  const auto [status2, out2] = run_towsim("statics --example two-part-tow --set '" + m[1].str() + "'");
  EXPECT_EQ(status2, 0) << out2;
  EXPECT_LT(std::abs(depressor_pitch(out2)), 1e-4) << out2;
}

TEST(CliEquilibria, TrimOfAnUnknownBodyIsRefused) {
  const auto [status, out] = run_towsim("statics --example two-part-tow --trim fish");
  EXPECT_EQ(status, 2) << out;
  EXPECT_EQ(out, "towsim: statics: --trim fish: no such body (the scenario's: depressor, body)\n");
}

}  // namespace
