// `towsim plot`: figures from a run's output directory (io/plot.hpp), on a
// tiny synthetic output directory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/cli.hpp"
#include "plot.hpp"

namespace fs = std::filesystem;
using towsim::io::plot_names;
using towsim::io::plot_run;

namespace {

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

/// A fresh directory per test, removed at the end.
class PlotRun : public towsim::testing::TempDirTest {
 protected:
  void TearDown() override {
    ::unsetenv("TOWSIM_GNUPLOT");
    TempDirTest::TearDown();
  }

  /// Write a small run: 3 joints, 11 output times; with a two-sphere body,
  /// and horizontal motion in y when `three_d`.
  void write_run(bool body, bool three_d, bool nodes = true) {
    std::ofstream ts(dir_ / "timeseries.csv");
    ts << "time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z";
    if (body)
      ts << ",body_x,body_y,body_z,body_roll_deg,body_pitch_deg,body_yaw_deg,link_force_x,link_force_y,link_force_z";
    ts << ",tow_tension,end_depth\n";
    std::ofstream nd(dir_ / "nodes.csv");
    nd << "time,node,x,y,z,vx,vy,vz,tension\n";
    for (int k = 0; k <= 10; ++k) {
      const double t = 0.5 * k, x = 2.0 * t, y = three_d ? std::sin(t) : 0.0;
      const double ex = 0.5 * x, ez = -10 + 0.3 * t;
      ts << t << ',' << x << ',' << y << ",0," << 50 + t << ',' << (three_d ? 5 * y : 0.0) << ",100," << ex << ','
         << 0.5 * y << ',' << ez;
      if (body)
        // Pitch passes -90 deg (reported as roll = yaw = 180) in the middle.
        ts << ',' << ex << ',' << 0.5 * y << ',' << ez << ',' << (k == 5 ? 180 : 0) << ',' << (k == 5 ? -85 : -10.0 * k)
           << ',' << (k == 5 ? 180 : 0) << ",3,0,8";
      ts << ',' << std::hypot(50 + t, 100) << ',' << -ez << '\n';
      for (int j = 0; j <= 2; ++j)
        nd << t << ',' << j << ',' << x + j * (ex - x) / 2 << ',' << y * (1 - 0.25 * j) << ',' << j * ez / 2
           << ",0,0,0," << 100 - 40 * j << '\n';
    }
    std::ofstream sm(dir_ / "summary.json");
    sm << "{\"model\": \"synthetic\", \"status\": \"ok\", \"files\": {\"timeseries\": \"timeseries.csv\", "
       << "\"nodes\": " << (nodes ? "\"nodes.csv\"" : "null") << "}, \"scenario\": {\"name\": \"synthetic\"";
    if (body)
      sm << ", \"body\": {\"mass\": 2, \"link_point\": [0, 0, 0], \"spheres\": ["
         << "{\"center\": [0, 0, 0], \"radius\": 0.25}, {\"center\": [-1.5, 0, 0], \"radius\": 0.25}]}";
    sm << "}}\n";
    if (!nodes) {
      nd.close();
      fs::remove(dir_ / "nodes.csv");
    }
  }

  /// Every figure's .gp, .png and .svg exist and are non-empty.
  void expect_figures(const std::vector<std::string>& names) {
    for (const auto& n : names)
      for (const char* ext : {".gp", ".png", ".svg"}) {
        const fs::path p = dir_ / "plots" / (n + ext);
        ASSERT_TRUE(fs::is_regular_file(p)) << p;
        EXPECT_GT(fs::file_size(p), 0u) << p;
      }
  }
};

}  // namespace

TEST(PlotNames, DependOnBodyAndDimension) {
  EXPECT_EQ(plot_names(false, false), (std::vector<std::string>{"trajectories_xz", "tow_force", "end_depth",
                                                                "depth_layback", "cable_shapes_xz", "tension_map"}));
  EXPECT_EQ(plot_names(true, true), (std::vector<std::string>{"trajectories_xz", "tow_force", "paths_xy", "end_depth",
                                                              "depth_layback", "body_angles", "cable_shapes_xz",
                                                              "cable_shapes_xy", "tension_map", "link_force"}));
  // A sea-state run (spectra.csv): the spectra figure last.
  EXPECT_EQ(plot_names(false, false, false, true).back(), "spectra");
  // One output time (towsim statics --out): shapes and tension only.
  EXPECT_EQ(plot_names(true, true, true),
            (std::vector<std::string>{"cable_shapes_xz", "cable_shapes_xy", "tension_along_cable"}));
}

TEST_F(PlotRun, RendersEveryFigureOfA3DRunWithABody) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_run(true, true);
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  expect_figures(plot_names(true, true));
  // The PNG is a PNG, the SVG an SVG.
  std::ifstream png(dir_ / "plots" / "tow_force.png", std::ios::binary);
  char sig[4] = {};
  png.read(sig, 4);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  std::stringstream svg;
  svg << std::ifstream(dir_ / "plots" / "tow_force.svg").rdbuf();
  EXPECT_NE(svg.str().find("<svg"), std::string::npos);
  // The scripts name the example and read the CSVs by column name.
  std::stringstream gp;
  gp << std::ifstream(dir_ / "plots" / "trajectories_xz.gp").rdbuf();
  EXPECT_NE(gp.str().find("synthetic: trajectories"), std::string::npos);
  EXPECT_NE(gp.str().find("second sphere centre"), std::string::npos);
  EXPECT_NE(gp.str().find("'../timeseries.csv'"), std::string::npos);
}

TEST_F(PlotRun, RendersTheFiguresOfAPlanarCableRun) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_run(false, false);
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  expect_figures(plot_names(false, false));
  for (const char* n : {"paths_xy", "body_angles", "link_force", "cable_shapes_xy"})
    EXPECT_FALSE(fs::exists(dir_ / "plots" / (std::string(n) + ".png"))) << n;
}

// A sea-state run's spectra.csv (blank cells where a gain is undefined)
// adds the spectra figure: densities and the ship -> fish transfer function.
TEST_F(PlotRun, SpectraFigureOfASeaStateRun) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_run(true, false);
  {
    std::ofstream sp(dir_ / "spectra.csv");
    sp << "omega,wave_elevation,tow_tension,link_force,body_depth,body_heave_per_wave,tow_heave,"
          "body_heave_per_tow_heave\n";
    for (int k = 1; k <= 40; ++k) {
      const double w = 0.05 * k, S = std::exp(-std::pow(w - 0.7, 2) / 0.02) + 1e-8;
      const bool gain = S > 1e-3;
      sp << w << ',' << S << ',' << 1e4 * S << ',' << 1e3 * S << ',' << 0.04 * S << ',';
      if (gain) sp << 0.2;
      sp << ',' << 0.25 * S << ',';
      if (gain) sp << 0.4;
      sp << '\n';
    }
  }
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  expect_figures(plot_names(true, false, false, true));
  std::stringstream gp;
  gp << std::ifstream(dir_ / "plots" / "spectra.gp").rdbuf();
  EXPECT_NE(gp.str().find("'body_heave_per_tow_heave'"), std::string::npos);
  EXPECT_NE(gp.str().find("ship -> fish"), std::string::npos);
}

TEST_F(PlotRun, WithoutNodesWhenTheRunWroteNone) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_run(false, false, /*nodes=*/false);
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  expect_figures({"trajectories_xz", "tow_force", "end_depth", "depth_layback"});
  EXPECT_FALSE(fs::exists(dir_ / "plots" / "cable_shapes_xz.png"));
  EXPECT_NE(log.str().find("skipped tension_map"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("skipped cable_shapes_xz"), std::string::npos) << log.str();
}

TEST_F(PlotRun, MissingDirectoryIsStatus2AndNamesTheFiles) {
  const std::string missing = (dir_ / "no-such-run").string();
  std::ostringstream log;
  EXPECT_EQ(plot_run(missing, log), 2);
  EXPECT_NE(log.str().find(missing), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("no such directory"), std::string::npos) << log.str();
  for (const char* f : {"timeseries.csv", "nodes.csv", "summary.json"})
    EXPECT_NE(log.str().find(f), std::string::npos) << log.str();
  EXPECT_FALSE(fs::exists(missing));
}

TEST_F(PlotRun, MissingFileIsStatus2AndNamesIt) {
  write_run(true, false);
  fs::remove(dir_ / "nodes.csv");
  std::ostringstream log;
  EXPECT_EQ(plot_run(dir_.string(), log), 2);
  EXPECT_EQ(log.str(), "towsim plot: " + dir_.string() +
                           " has no nodes.csv (expected the output directory of `towsim run --out DIR` or "
                           "`towsim statics --out DIR`)\n");
  EXPECT_FALSE(fs::exists(dir_ / "plots"));

  fs::remove(dir_ / "timeseries.csv");
  std::ostringstream log2;
  EXPECT_EQ(plot_run(dir_.string(), log2), 2);
  EXPECT_NE(log2.str().find("has no timeseries.csv and nodes.csv"), std::string::npos) << log2.str();
}

TEST_F(PlotRun, MissingColumnIsStatus2AndNamesIt) {
  write_run(false, false);
  std::ofstream(dir_ / "timeseries.csv") << "time,tow_x,tow_y,tow_z\n0,0,0,0\n";
  std::ostringstream log;
  EXPECT_EQ(plot_run(dir_.string(), log), 2);
  EXPECT_NE(log.str().find("no column tow_force_x, tow_force_y"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("end_z in its header"), std::string::npos) << log.str();
}

TEST_F(PlotRun, MissingGnuplotIsStatus2AndSaysWhatToInstall) {
  write_run(false, false);
  ::setenv("TOWSIM_GNUPLOT", "/nonexistent/towsim-test/gnuplot", 1);
  std::ostringstream log;
  EXPECT_EQ(plot_run(dir_.string(), log), 2);
  EXPECT_NE(log.str().find("gnuplot-nox"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("/nonexistent/towsim-test/gnuplot"), std::string::npos) << log.str();
  EXPECT_FALSE(fs::exists(dir_ / "plots"));
}

TEST_F(PlotRun, NodesAreReadOnceByTowsimNotByGnuplot) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_run(true, false);
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  // No script reads nodes.csv (gnuplot re-read it per snapshot: minutes on a
  // 99 MB file); the snapshots are extracted into cable_shapes.dat.
  for (const auto& n : plot_names(true, false)) {
    std::stringstream gp;
    gp << std::ifstream(dir_ / "plots" / (n + ".gp")).rdbuf();
    EXPECT_EQ(gp.str().find("nodes.csv'"), std::string::npos) << n;
  }
  // cable_shapes.dat: one block of 3 joints per snapshot, the snapshot's
  // nodes.csv rows (write_run: joint j of time t at x = 2t + j(0.5x - x)/2).
  std::ifstream in(dir_ / "plots" / "cable_shapes.dat");
  std::string line;
  int rows = 0;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') {
      ++rows;
      std::istringstream cells(line);
      std::string t, node, x;
      std::getline(cells, t, ',');
      std::getline(cells, node, ',');
      std::getline(cells, x, ',');
      const double T = std::stod(t);
      EXPECT_DOUBLE_EQ(std::stod(x), 2 * T + std::stoi(node) * (T - 2 * T) / 2) << line;
    }
  EXPECT_EQ(rows % 3, 0);
  EXPECT_GE(rows, 3 * 4);
  // tension_map.dat: every output time (11 <= 200), 3 joints each.
  std::ifstream tm(dir_ / "plots" / "tension_map.dat");
  rows = 0;
  while (std::getline(tm, line))
    if (!line.empty() && line[0] != '#') ++rows;
  EXPECT_EQ(rows, 11 * 3);
}

TEST_F(PlotRun, AStaticsOutputDirectory) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string cmd = std::string("'") + TOWSIM_BINARY + "' statics --example paper-3d-turn --out '" +
                          dir_.string() + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  expect_figures({"cable_shapes_xz", "tension_along_cable"});
  EXPECT_FALSE(fs::exists(dir_ / "plots" / "tow_force.png"));  // no time histories of one configuration
  // Also without summary.json (as written by an older towsim statics).
  fs::remove(dir_ / "summary.json");
  std::ostringstream log2;
  ASSERT_EQ(plot_run(dir_.string(), log2), 0) << log2.str();
  expect_figures({"cable_shapes_xz", "tension_along_cable"});
}

TEST_F(PlotRun, StaleFiguresOfAnEarlierPlotAreRemoved) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_run(false, false);
  fs::create_directories(dir_ / "plots");
  std::ofstream(dir_ / "plots" / "body_angles.png") << "old";
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  EXPECT_FALSE(fs::exists(dir_ / "plots" / "body_angles.png"));
}
