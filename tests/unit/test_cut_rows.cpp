// A row cut off at the end of a run's file (a kill inside a write): towsim's
// readers (plot, report) leave it out (docs/reliability.md "Interruption").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/cli.hpp"
#include "run_files.hpp"

namespace fs = std::filesystem;
using CutRows = towsim::testing::TempDirTest;

TEST_F(CutRows, ReadersLeaveOutALastLineWithoutNewline) {
  const fs::path out = dir_ / "out";
  const auto r = towsim::testing::run_towsim("run --example paper-3d-turn --set simulation.duration=1 --quiet --out " +
                                             towsim::testing::quoted(out));
  ASSERT_EQ(r.status, 0) << r.out;
  towsim::cli::CsvTable whole;
  std::vector<towsim::cli::NodeFrame> whole_frames;
  std::string error;
  ASSERT_TRUE(towsim::cli::read_csv_table((out / "timeseries.csv").string(), whole, error)) << error;
  ASSERT_TRUE(towsim::cli::read_node_frames((out / "nodes.csv").string(), {0.0, 1.0}, whole_frames, error)) << error;
  // The start of a next row, cut in its numbers ("1.1,0.0" of "1.1,0.0123,...").
  std::ofstream(out / "timeseries.csv", std::ios::app) << "1.1,0.0";
  std::ofstream(out / "nodes.csv", std::ios::app) << "1,0,0.0";
  towsim::cli::CsvTable cut;
  std::vector<towsim::cli::NodeFrame> cut_frames;
  ASSERT_TRUE(towsim::cli::read_csv_table((out / "timeseries.csv").string(), cut, error)) << error;
  ASSERT_TRUE(towsim::cli::read_node_frames((out / "nodes.csv").string(), {0.0, 1.0}, cut_frames, error)) << error;
  EXPECT_EQ(cut.rows, whole.rows);
  ASSERT_EQ(cut_frames.size(), whole_frames.size());
  EXPECT_EQ(cut_frames.back().x, whole_frames.back().x);
  // The report reads them too: it is written.
  const auto rep = towsim::testing::run_towsim("report " + towsim::testing::quoted(out));
  EXPECT_EQ(rep.status, 0) << rep.out;
}
