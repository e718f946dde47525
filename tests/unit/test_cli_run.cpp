// The built program (TOWSIM_BINARY): exit statuses, nothing written on bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Result {
  int status = -1;
  std::string out;  // stdout and stderr together
};

/// Run the towsim binary with `args` (shell syntax), capturing its output.
Result towsim(const std::string& args) {
  const std::string cmd = std::string("'") + TOWSIM_BINARY + "' " + args + " 2>&1";
  Result r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("towsim_cli_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string q(const fs::path& p) const { return "'" + p.string() + "'"; }
  fs::path dir_;
};

}  // namespace

TEST_F(Cli, BrokenFileExits2AndCreatesNothing) {
  const fs::path scen = dir_ / "bad.yaml";
  std::ofstream(scen) << "cable:\n  length: 100\n  elements: 0\n  mass_per_length: 1.5\n  diameter: -0.019\n"
                         "simulation:\n  duration: 1\n";
  const fs::path out = dir_ / "out";
  const Result r = towsim("run " + q(scen) + " --out " + q(out));
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(r.out, scen.string() + ":3:13: cable.elements: must be >= 1 (got 0)\n" + scen.string() +
                       ":5:13: cable.diameter: must be > 0 (got -0.019)\n");
}

TEST_F(Cli, BadSetExits2) {
  const fs::path out = dir_ / "out";
  const Result r = towsim("run --example cable-tow --set cable.elements=0 --out " + q(out));
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out, "--set:1:16: cable.elements: must be >= 1 (got 0)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, ExamplesListsTheBuiltInNames) {
  const Result r = towsim("examples");
  EXPECT_EQ(r.status, 0);
  for (const char* name : {"paper-planar-a", "paper-planar-b", "paper-3d-turn", "cable-tow"})
    EXPECT_NE(("\n" + r.out).find(std::string("\n") + name + " "), std::string::npos) << name << " in:\n" << r.out;
}

TEST_F(Cli, ExamplePrintsYamlAndUnknownNameFails) {
  const Result r = towsim("examples paper-3d-turn");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("name: paper-3d-turn"), std::string::npos);
  const Result bad = towsim("examples paper-3d");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("did you mean 'paper-3d-turn'?"), std::string::npos) << bad.out;
}

TEST_F(Cli, CheckPrintsDerivedQuantities) {
  const Result r = towsim("check --example paper-planar-a");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("element length              20 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("apparent weight in water"), std::string::npos);
}

TEST_F(Cli, RunWritesTheThreeFiles) {
  const fs::path out = dir_ / "run";
  const Result r = towsim("run --example cable-tow --set simulation.duration=2 --out " + q(out) + " --quiet");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "");
  for (const char* f : {"timeseries.csv", "nodes.csv", "summary.json"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  std::ifstream in(out / "timeseries.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z", 0), 0u);
}

TEST_F(Cli, UsageErrorsExit2) {
  EXPECT_EQ(towsim("run --example cable-tow").status, 2);  // no --out
  EXPECT_EQ(towsim("").status, 2);                         // no subcommand
  EXPECT_EQ(towsim("check").status, 2);                    // no input
  EXPECT_EQ(towsim("--help").status, 0);
}
