// Bending stiffness keys (docs/scenario.md "Bending stiffness"):
// bending_stiffness at cable level or per section, its refusal, and what a
// run writes (nodes.csv `bending_moment`).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/scenario/scenario.hpp"

namespace fs = std::filesystem;

namespace {

using BendingKeys = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;

/// Fields of one CSV line.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

}  // namespace

TEST_F(BendingKeys, CableLevelAndSectionValuesReachTheElements) {
  const auto s = load(kCable + "  bending_stiffness: 250\n" + kSim);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  for (const auto& el : s.model->cable.elements) EXPECT_EQ(el.bending_stiffness, 250);
  const auto t = load(
      "cable:\n  mass_per_length: 1.5\n  diameter: 0.019\n  bending_stiffness: 100\n  sections:\n"
      "    - {length: 50, elements: 5}\n"
      "    - {length: 20, elements: 4, bending_stiffness: 0}\n" +
      kSim);
  ASSERT_TRUE(t.ok()) << t.diags.str();
  const auto& els = t.model->cable.elements;
  ASSERT_EQ(els.size(), 9u);
  EXPECT_EQ(els[0].bending_stiffness, 100);
  EXPECT_EQ(els[8].bending_stiffness, 0);
  // Absent: none (the paper's model).
  const auto u = load(kCable + kSim);
  ASSERT_TRUE(u.ok());
  EXPECT_EQ(u.model->cable.elements[0].bending_stiffness, 0);
}

TEST_F(BendingKeys, NegativeStiffnessIsRefusedWithItsPlace) {
  const auto bad = load(kCable + "  bending_stiffness: -3\n" + kSim);
  EXPECT_EQ(bad.diags.str(), at("6:22: cable.bending_stiffness: must be >= 0 (got -3)"));
  const auto sec = load(
      "cable:\n  mass_per_length: 1.5\n  diameter: 0.019\n  sections:\n"
      "    - {length: 50, elements: 5, bending_stiffness: -1}\n" +
      kSim);
  EXPECT_EQ(sec.diags.str(), at("5:52: cable.sections.0.bending_stiffness: must be >= 0 (got -1)"));
}

TEST_F(BendingKeys, RunWritesTheBendingMomentOfEachJoint) {
  // A 10 m beam pinned at a fixed tow point, released horizontal in air:
  // it bends as it falls; the ends carry no moment.
  const std::string scen = write(
      "environment: {water_density: 0}\n"
      "cable:\n  length: 10\n  elements: 5\n  mass_per_length: 2\n  diameter: 0.05\n  bending_stiffness: 400\n"
      "initial: {direction: [1, 0, 0]}\n"
      "simulation:\n  duration: 0.5\n  output_interval: 0.25\n");
  const fs::path out = dir_ / "out";
  const auto r = towsim::testing::run_towsim("run " + towsim::testing::quoted(scen) + " --out " +
                                             towsim::testing::quoted(out) + " --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto lines = towsim::testing::lines_of(out / "nodes.csv");
  ASSERT_EQ(lines.size(), 1u + 3 * 6);  // header, 3 times x 6 joints
  EXPECT_EQ(lines[0], "time,node,x,y,z,vx,vy,vz,tension,axial_force,strain,bending_moment");
  // At t = 0.5 s: zero at the tow point and the free end, positive inside.
  for (std::size_t i = 13; i < lines.size(); ++i) {
    const auto f = fields(lines[i]);
    const double M = std::stod(f.back());
    const int node = std::stoi(f[1]);
    if (node == 0 || node == 5)
      EXPECT_EQ(M, 0.0) << lines[i];
    else
      EXPECT_GT(M, 1e-3) << lines[i];  // bent by the fall (measured 0.18-3 N m)
  }
  // Without bending stiffness the column is not there.
  const std::string plain = write(
      "environment: {water_density: 0}\n"
      "cable:\n  length: 10\n  elements: 5\n  mass_per_length: 2\n  diameter: 0.05\n"
      "initial: {direction: [1, 0, 0]}\n"
      "simulation:\n  duration: 0.5\n  output_interval: 0.25\n");
  const fs::path out2 = dir_ / "out2";
  ASSERT_EQ(towsim::testing::run_towsim("run " + towsim::testing::quoted(plain) + " --out " +
                                        towsim::testing::quoted(out2) + " --quiet")
                .status,
            0);
  EXPECT_EQ(towsim::testing::lines_of(out2 / "nodes.csv")[0], "time,node,x,y,z,vx,vy,vz,tension,axial_force,strain");
}
