// The output directory: what towsim removes there before writing, and what
// it refuses to touch (docs/reliability.md "Output directory").
#include <gtest/gtest.h>

#include <sys/mount.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "../support/cli.hpp"
#include "towsim/output/output.hpp"
#include "towsim/output/row_file.hpp"

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

// Two runs into one --out mixed their files (the CSVs of one, the summary of
// the other, both exit 0): the second is refused while the first runs.
TEST_F(OutputDir, SecondRunIntoABusyDirectoryIsRefused) {
  const fs::path out = dir_ / "out";
  towsim::testing::Child first({"run", "--example", "paper-3d-turn", "--set", "simulation.duration=100000", "--out",
                                out.string(), "--quiet"},
                               dir_);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline && first.running() && !fs::exists(out / "timeseries.csv"))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(first.running());
  const std::string busy =
      " is in use by another towsim run (wait for it to end, or choose another output "
      "directory)\n";
  const CliResult second = run_towsim("run" + kShortRun + quoted(out));
  EXPECT_EQ(second.status, 1) << second.out;
  EXPECT_EQ(second.out, "towsim: " + out.string() + busy);
  const CliResult statics = run_towsim("statics --example cable-tow --out " + quoted(out));
  EXPECT_EQ(statics.status, 1) << statics.out;
  EXPECT_NE(statics.out.find("towsim: statics: " + out.string() + busy), std::string::npos) << statics.out;
  ::kill(first.pid(), SIGTERM);
  EXPECT_EQ(first.wait().status, 130);
  // Free again once the first has ended.
  EXPECT_EQ(run_towsim("run" + kShortRun + quoted(out)).status, 0);
}

// A disk that takes no more: the batch that did not fit is cut back off the
// file (whole rows only), and the cause is kept.
TEST_F(OutputDir, RowFileOnAFullDiskKeepsWholeRowsAndTheCause) {
  towsim::output::RowFile full("/dev/full");
  EXPECT_FALSE(full.append("1,2\n"));
  EXPECT_EQ(full.error(), "cannot write /dev/full: No space left on device");
  EXPECT_FALSE(full.append("3,4\n"));  // nothing more after a failure
  // summary.json is whole or absent (written beside, then renamed).
  std::string why;
  EXPECT_FALSE(towsim::output::write_summary((dir_ / "none").string(), nlohmann::ordered_json::object(), &why));
  EXPECT_EQ(why, "cannot create " + (dir_ / "none" / "summary.json.part").string() + ": No such file or directory");
}

// An existing output directory on a read-only file system (a tmpfs remounted
// read-only, where the test may mount one): statics --out once aborted on the
// exception (exit 134); it exits 1 naming the file and the cause, as run does.
TEST_F(OutputDir, ReadOnlyFileSystemExits1ForStaticsAndRun) {
  const fs::path mnt = dir_ / "ro";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here";
  const fs::path out = mnt / "out";
  fs::create_directories(out);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=64k") != 0) {
    ::umount(mnt.c_str());
    GTEST_SKIP() << "cannot remount the tmpfs read-only here";
  }
  const std::string cause = "cannot create " + (out / "timeseries.csv").string() + ": Read-only file system\n";
  const CliResult statics = run_towsim("statics --example cable-tow --out " + quoted(out));
  EXPECT_EQ(statics.status, 1) << statics.out;
  EXPECT_NE(statics.out.find("towsim: statics: " + cause), std::string::npos) << statics.out;
  const CliResult run = run_towsim("run" + kShortRun + quoted(out));
  EXPECT_EQ(run.status, 1) << run.out;
  EXPECT_EQ(run.out, "towsim: " + cause);
  EXPECT_TRUE(fs::is_empty(out));
  ::umount(mnt.c_str());
}

// A full file system (a 256 KiB tmpfs, where the test may mount one): exit 1
// naming the file and the cause (once only "cannot write summary.json"), every
// file ending in a whole row, no empty summary.json.
TEST_F(OutputDir, FullDiskExits1WithTheCauseAndWholeRows) {
  const fs::path mnt = dir_ / "small";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=256k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here";
  const fs::path out = mnt / "out";
  const CliResult r = run_towsim("run --example paper-3d-turn --set simulation.duration=200 --quiet --out " +
                                 quoted(out));
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out.rfind("towsim: cannot write " + out.string() + "/", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("No space left on device"), std::string::npos) << r.out;
  for (const char* name : {"timeseries.csv", "nodes.csv"}) {
    const std::string text = towsim::testing::slurp(out / name);
    EXPECT_TRUE(text.empty() || text.back() == '\n') << name;
  }
  if (fs::exists(out / "summary.json")) {
    EXPECT_TRUE(nlohmann::json::accept(towsim::testing::slurp(out / "summary.json")));
  }
  EXPECT_FALSE(fs::exists(out / "summary.json.part"));
  ::umount(mnt.c_str());
}
