// `towsim statics`: steady tow of the built-in examples from the command line.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

/// Run the towsim binary with `args`; returns (exit status, stdout + stderr).
std::pair<int, std::string> towsim(const std::string& args) {
  const std::string cmd = std::string("'") + TOWSIM_BINARY + "' " + args + " 2>&1";
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return {-1, out};
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  const int st = ::pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

class CliStatics : public ::testing::TestWithParam<std::string> {};

TEST_P(CliStatics, ConvergesAndWritesTheConfiguration) {
  const fs::path dir = fs::temp_directory_path() / ("towsim_statics_" + GetParam() + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto [status, out] = towsim("statics --example " + GetParam() + " --out '" + dir.string() + "'");
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("converged: yes"), std::string::npos) << out;
  EXPECT_NE(out.find("tow force F_R = ("), std::string::npos) << out;
  // nodes.csv: header + one row per joint P_0..P_n.
  std::ifstream nodes(dir / "nodes.csv");
  ASSERT_TRUE(nodes.good());
  std::string line;
  int rows = 0;
  while (std::getline(nodes, line)) ++rows;
  EXPECT_GE(rows, 1 + 2);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, CliStatics,
                         ::testing::Values("paper-planar-a", "paper-planar-b", "paper-3d-turn", "cable-tow"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

TEST(CliStaticsErrors, ForceModeIsRefused) {
  const auto [status, out] = towsim("statics --example cable-tow --set tow.mode=force --set 'tow.force=[10,0,0]'");
  EXPECT_EQ(status, 2) << out;
  EXPECT_NE(out.find("statics needs mode: motion"), std::string::npos) << out;
}

}  // namespace
