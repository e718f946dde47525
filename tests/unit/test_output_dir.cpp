// The output directory: what towsim removes there before writing, and what
// it refuses to touch (docs/reliability.md "Output directory").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../support/cli.hpp"

namespace fs = std::filesystem;
using towsim::testing::CliResult;
using towsim::testing::quoted;
using towsim::testing::run_towsim;
using OutputDir = towsim::testing::TempDirTest;

namespace {

const std::string kShortRun = " --example cable-tow --set simulation.duration=0.2 --quiet --out ";

}  // namespace

// A user's directory named summary.json inside --out was deleted with its
// contents: now refused (exit 1), left as it was, for run and statics
// (statics once aborted on the exception: exit 134).
TEST_F(OutputDir, UsersDirectoryWithATowsimNameIsLeftAlone) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "summary.json");
  std::ofstream(out / "summary.json" / "mine.txt") << "keep me\n";
  const std::string expected = (out / "summary.json").string() +
                               " is not a file of towsim's (a directory): move it away or choose another output "
                               "directory\n";
  const CliResult run = run_towsim("run" + kShortRun + quoted(out));
  EXPECT_EQ(run.status, 1) << run.out;
  EXPECT_EQ(run.out, "towsim: " + expected);
  const CliResult statics = run_towsim("statics --example cable-tow --out " + quoted(out));
  EXPECT_EQ(statics.status, 1) << statics.out;
  EXPECT_NE(statics.out.find("towsim: statics: " + expected), std::string::npos) << statics.out;
  EXPECT_TRUE(fs::exists(out / "summary.json" / "mine.txt"));
}

// A rerun replaces towsim's own files, and keeps what else is in plots/.
TEST_F(OutputDir, RerunRemovesOnlyTowsimsRegularFiles) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "plots" / "notes");
  std::ofstream(out / "plots" / "tension.svg") << "stale\n";
  std::ofstream(out / "plots" / "notes" / "n.txt") << "keep me\n";
  std::ofstream(out / "spectra.csv") << "stale\n";
  std::ofstream(out / "mine.csv") << "keep me\n";
  const CliResult run = run_towsim("run" + kShortRun + quoted(out));
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_FALSE(fs::exists(out / "plots" / "tension.svg"));
  EXPECT_FALSE(fs::exists(out / "spectra.csv"));  // stale: cable-tow has no sea
  EXPECT_TRUE(fs::exists(out / "plots" / "notes" / "n.txt"));
  EXPECT_TRUE(fs::exists(out / "mine.csv"));
  EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
}
