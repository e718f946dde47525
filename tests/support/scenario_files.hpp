// A GoogleTest fixture that writes scenario files into a fresh directory per
// test and loads them, plus the minimal valid scenario pieces the parser
// tests build on.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "towsim/scenario/scenario.hpp"

namespace towsim::testing {

/// A fresh directory per test (removed at the end) and scenario loading.
class ScenarioFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("towsim_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// Write `text` into DIR/name (bytes as given) and return its path.
  std::string write(const std::string& text, const std::string& name = "scen.yaml") {
    const std::filesystem::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  /// Load `text` as the scenario file DIR/scen.yaml with --set overrides.
  scenario::LoadedScenario load(const std::string& text, const std::vector<std::string>& sets = {}) {
    path_ = write(text);
    return scenario::load_scenario_file(path_, sets);
  }
  /// The expected error line for the scenario file.
  std::string at(const std::string& rest) const { return path_ + ":" + rest + "\n"; }
  /// The same for another file of the test directory.
  std::string in(const std::string& name, const std::string& rest) const {
    return (dir_ / name).string() + ":" + rest + "\n";
  }

  std::filesystem::path dir_;
  std::string path_;
};

// Lines 1-5 and 6-7: a body, when added after them, starts on line 8.
inline const std::string kCable =
    "cable:\n"
    "  length: 100\n"
    "  elements: 5\n"
    "  mass_per_length: 1.5\n"
    "  diameter: 0.019\n";
inline const std::string kSim =
    "simulation:\n"
    "  duration: 10\n";

}  // namespace towsim::testing
