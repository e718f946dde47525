// Failure behaviour of the built program (TOWSIM_BINARY), docs/contract.md §U3:
// a numerical failure exits 3, names the simulated time and the element or
// body, and keeps what was computed up to then (complete rows, a summary with
// status "failed"); SIGTERM during a run keeps complete rows and a summary
// with status "interrupted".
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/cli.hpp"

namespace fs = std::filesystem;

namespace {

using towsim::testing::Child;
using towsim::testing::Exit;
using towsim::testing::slurp;

/// timeseries.csv checked line by line: every line ends in '\n' and has the
/// header's number of columns; returns the data rows (header excluded).
std::vector<std::string> complete_rows(const fs::path& csv) {
  const std::string text = slurp(csv);
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "last line of " << csv << " is incomplete";
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  if (lines.empty()) return {};
  const auto columns = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  const auto ncol = columns(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) EXPECT_EQ(columns(lines[i]), ncol) << "line " << i + 1;
  return {lines.begin() + 1, lines.end()};
}

double first_number(const std::string& row) { return std::stod(row.substr(0, row.find(','))); }

using Failure = towsim::testing::TempDirTest;

// A short, stiff cable (1 m in 10 elements of 0.1 m, fast tow) integrated by
// fixed-step RK4 with a step beyond its stability limit: the first element's
// rotation blows up after a few output times (about t = 0.24 s).
const char* kUnstable =
    "name: unstable\n"
    "cable: {length: 1, elements: 10, mass_per_length: 0.1, diameter: 0.01}\n"
    "body:\n"
    "  mass: 2\n"
    "  inertia: [0.01, 0.02, 0.02]\n"
    "  link_point: [0, 0, 0]\n"
    "  spheres: [{center: [0, 0, 0], radius: 0.05}]\n"
    "tow:\n"
    "  motion: [{type: ramp, direction: [1, 0, 0], speed: 3, ramp_time: 0.5}]\n"
    "simulation: {duration: 20, time_step: 0.01, integrator: rk4, output_interval: 0.1}\n";

}  // namespace

TEST_F(Failure, NumericalBlowUpExits3AndKeepsRowsUpToThen) {
  const fs::path scen = dir_ / "unstable.yaml";
  std::ofstream(scen) << kUnstable;
  const fs::path out = dir_ / "out";
  Child c({"run", scen.string(), "--out", out.string(), "--quiet"}, dir_);
  const Exit r = c.wait();
  ASSERT_EQ(r.status, 3) << r.err;
  // One line naming the simulated time and the element or body (or the tow point).
  EXPECT_EQ(r.err.rfind("towsim: simulation failed", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const std::regex where("numerical failure at t = ([0-9.e+-]+) s: (element [0-9]+|body|tow point)[: ]");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, where)) << r.err;
  EXPECT_NE(r.err.find(out.string()), std::string::npos) << "the message does not say where the results are";
  const double t_fail = std::stod(m[1]);
  EXPECT_GT(t_fail, 0);
  EXPECT_LT(t_fail, 20);

  // Complete rows up to the failure, none after it.
  const auto rows = complete_rows(out / "timeseries.csv");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(first_number(rows.front()), 0.0);
  EXPECT_LE(first_number(rows.back()), t_fail);
  EXPECT_GT(first_number(rows.back()), t_fail - 0.1 - 1e-9);  // the last output time before the failure
  complete_rows(out / "nodes.csv");

  // summary.json: status "failed" and the reason.
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["status"], "failed");
  const std::string reason = j["message"];
  EXPECT_EQ(reason.rfind("numerical failure at t = ", 0), 0u) << reason;
  EXPECT_NE(r.err.find(reason), std::string::npos) << "stderr does not carry the reason:\n" << r.err;
  EXPECT_EQ(j["samples"], static_cast<long>(rows.size()));
  EXPECT_DOUBLE_EQ(j["end_time"].get<double>(), t_fail);
}

TEST_F(Failure, SigtermKeepsCompleteRowsAndSummaryInterrupted) {
  const fs::path out = dir_ / "out";
  // Long enough never to finish within the test.
  Child c({"run", "--example", "paper-3d-turn", "--set", "simulation.duration=100000", "--out", out.string(),
           "--quiet"},
          dir_);
  // Wait until a few samples are on disk (the run has started integrating).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline && c.running()) {
    std::ifstream in(out / "timeseries.csv");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (std::count(text.begin(), text.end(), '\n') >= 4) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(c.running()) << "the run ended before it could be interrupted";
  ASSERT_EQ(::kill(c.pid(), SIGTERM), 0);
  const Exit r = c.wait();
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_EQ(r.err.rfind("towsim: interrupted at t = ", 0), 0u) << r.err;
  const auto rows = complete_rows(out / "timeseries.csv");
  EXPECT_GE(rows.size(), 3u);
  complete_rows(out / "nodes.csv");
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["status"], "interrupted");
  EXPECT_EQ(j["samples"], static_cast<long>(rows.size()));
  EXPECT_NEAR(j["end_time"].get<double>(), first_number(rows.back()), 1e-9);
}

// SIGTERM between output times stops the run at once (it once waited for the
// next output time: ~500 s at 100000 elements). Here the next output time is
// 5e6 simulated seconds away (several minutes of integration); the run must
// end within 5 s of the signal (1 s asked for, margin for a loaded machine).
TEST_F(Failure, SigtermBetweenOutputTimesStopsPromptly) {
  const fs::path out = dir_ / "out";
  Child c({"run", "--example", "paper-3d-turn", "--set", "simulation.duration=1e7", "--set",
           "simulation.output_interval=5e6", "--out", out.string(), "--quiet"},
          dir_);
  // Integrating by then (the t = 0 row may still be in the writer's buffer: rows go out at the next sample).
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_TRUE(c.running()) << "the run ended before it could be interrupted";
  const auto sent = std::chrono::steady_clock::now();
  ASSERT_EQ(::kill(c.pid(), SIGTERM), 0);
  const Exit r = c.wait();
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  EXPECT_LT(waited, 5.0);
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_EQ(complete_rows(out / "timeseries.csv").size(), 1u);  // the t = 0 row only
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["status"], "interrupted");
  EXPECT_EQ(j["end_time"], 0.0);  // the last sample on disk
}

// SIGKILL at random moments (the trial found 4 of 102 runs with a last row
// cut off: a kill inside the write(2) of a batch of rows, which the kernel
// ends at a page boundary). Every line but the last is whole; the last one is
// whole or has no newline, and towsim's readers leave such a line out.
TEST_F(Failure, SigkillLeavesWholeRowsButPerhapsACutLastLine) {
  for (int i = 0; i < 8; ++i) {
    const fs::path out = dir_ / ("out" + std::to_string(i));
    Child c({"run", "--example", "paper-3d-turn", "--set", "simulation.duration=100000", "--out", out.string(),
             "--quiet"},
            dir_);
    std::this_thread::sleep_for(std::chrono::milliseconds(100 + 60 * i));
    ::kill(c.pid(), SIGKILL);
    c.wait();
    for (const char* name : {"timeseries.csv", "nodes.csv"}) {
      const std::string text = slurp(out / name);
      if (text.empty()) continue;  // killed before the file was written
      std::vector<std::string> lines;
      std::istringstream in(text.substr(0, text.rfind('\n') + 1));
      for (std::string l; std::getline(in, l);) lines.push_back(l);
      const auto columns = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
      for (std::size_t k = 1; k < lines.size(); ++k) EXPECT_EQ(columns(lines[k]), columns(lines[0])) << name;
    }
  }
}
