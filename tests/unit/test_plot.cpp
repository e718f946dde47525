// `towsim plot`: figures from a run's output directory (app/plot.hpp), on a
// tiny synthetic output directory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "../support/cli.hpp"
#include "../support/png.hpp"
#include "plot.hpp"

namespace fs = std::filesystem;
using towsim::cli::plot_names;
using towsim::cli::plot_run;

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

// ------------------------------------------------- readable axes (issue 30)

using towsim::cli::axis_ticks;

// The tick step follows the span AND the pixels the axis gets: a 2910 m wide
// x axis drawn 226 pixels wide (a tall equal-scale plan view, 13 point font:
// 5-character labels of 52 px need 73 px from tick to tick) takes 1000 m,
// not gnuplot's 500 m (39 px: "-1500-1000-500" ran together); 901 pixels wide,
// 500 m; labels that do not fit twice side by side stand upright.
// A network's run (nodes.csv starting with its `line` column): each line's
// top tension, each body's and junction's depth (not a line end's), and the
// lines' shapes at the last output time, one block per line.
TEST_F(PlotRun, NetworkRunGetsItsLinesBodiesAndJunctions) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  {
    std::ofstream ts(dir_ / "timeseries.csv");
    ts << "time,main_top_tension,main_end_depth,leg_top_tension,fish_depth,fish_link_tension,shackle_depth\n";
    std::ofstream nd(dir_ / "nodes.csv");
    nd << "line,time,node,x,y,z,vx,vy,vz,tension,axial_force,strain\n";
    for (int k = 0; k <= 2; ++k) {
      const double t = k;
      ts << t << ',' << 100 + t << ',' << 10 + t << ',' << 50 + t << ',' << 12 + t << ",40," << 10 + t << '\n';
      for (int j = 0; j <= 2; ++j)
        nd << "main," << t << ',' << j << ',' << -j << ",0," << -5 * j << ",0,0,0,100,100,0\n";
      for (int j = 0; j <= 1; ++j)
        nd << "leg," << t << ',' << j << ',' << -2 - 0.5 * j << ",0," << -10 - j << ",0,0,0,50,50,0\n";
    }
    std::ofstream(dir_ / "summary.json") << "{\"model\": \"net\", \"status\": \"ok\"}\n";
  }
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  for (const char* n : {"line_tensions", "depths", "network_shape_xz", "network_shape_xy"})
    EXPECT_TRUE(fs::exists(dir_ / "plots" / (std::string(n) + ".png"))) << n;
  const std::string tensions = towsim::testing::slurp(dir_ / "plots" / "line_tensions.gp");
  EXPECT_NE(tensions.find("'main_top_tension'"), std::string::npos);
  EXPECT_NE(tensions.find("'leg_top_tension'"), std::string::npos);
  const std::string depths = towsim::testing::slurp(dir_ / "plots" / "depths.gp");
  EXPECT_NE(depths.find("'fish_depth'"), std::string::npos);
  EXPECT_NE(depths.find("'shackle_depth'"), std::string::npos);
  EXPECT_EQ(depths.find("main_end_depth"), std::string::npos);
  // The last time's rows, a block per line (the leg's two nodes after two blank lines).
  EXPECT_EQ(towsim::testing::slurp(dir_ / "plots" / "network_shapes.dat"),
            "0 0 0 100\n-1 0 -5 100\n-2 0 -10 100\n\n\n-2 0 -10 50\n-2.5 0 -11 50\n");
}

TEST(AxisTicks, StepFromTheSpanAndThePixels) {
  EXPECT_EQ(axis_ticks(-1556.2, 2910.3, 226, 13, true).step, 1000);
  EXPECT_FALSE(axis_ticks(-1556.2, 2910.3, 226, 13, true).rotate);
  EXPECT_EQ(axis_ticks(-1556.2, 2910.3, 901, 13, true).step, 500);
  // Vertical: one line (17.3 px at 13 points) between stacked labels.
  EXPECT_EQ(axis_ticks(-7000, 7450, 579, 13, false).step, 1000);
  EXPECT_EQ(axis_ticks(-7000, 7450, 60, 13, false).step, 5000);
  // 120 px: 1000 m gives 41 px (< 73 px side by side), 2000 m one label only:
  // upright labels (two lines apart, 35 px) at 1000 m.
  const auto upright = axis_ticks(-1556.2, 2910.3, 120, 13, true);
  EXPECT_EQ(upright.step, 1000);
  EXPECT_TRUE(upright.rotate);
  EXPECT_EQ(axis_ticks(0, 0, 500, 13, true).step, 0);
}

namespace {

/// Rows of dark (grey < 60: the black border and text, not the coloured
/// curves) pixels spanning at least `share` of the width: the plot boxes' edges.
std::vector<int> border_rows(const towsim::testing::Image& img, double share) {
  std::vector<int> rows;
  for (int y = 0; y < img.height; ++y) {
    int n = 0;
    for (int x = 0; x < img.width; ++x) n += img.dark(x, y, 60) ? 1 : 0;
    if (n >= share * img.width) rows.push_back(y);
  }
  return rows;
}

/// Runs of columns with a dark pixel in rows [y0, y1), runs closer than
/// `join` pixels merged (the characters of one label): [first, last] columns.
std::vector<std::pair<int, int>> dark_runs(const towsim::testing::Image& img, int y0, int y1, int join) {
  std::vector<std::pair<int, int>> runs;
  for (int x = 0; x < img.width; ++x) {
    bool d = false;
    for (int y = y0; y < y1 && !d; ++y) d = img.dark(x, y, 128);
    if (!d) continue;
    if (!runs.empty() && x - runs.back().second <= join)
      runs.back().second = x;
    else
      runs.emplace_back(x, x);
  }
  return runs;
}

}  // namespace

class PlotPicture : public PlotRun {
 protected:
  /// A long survey line's plan view taller than wide: 2750 m east, then
  /// 6650 m south (the shape of two-part-tow run for 3000 s).
  void write_tall_track() {
    std::ofstream ts(dir_ / "timeseries.csv");
    ts << "time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z,tow_tension,end_depth\n";
    std::ofstream nd(dir_ / "nodes.csv");
    nd << "time,node,x,y,z,vx,vy,vz,tension\n";
    for (int k = 0; k <= 100; ++k) {
      const double t = 30.0 * k;
      const double x = k < 30 ? -1500 + 2750.0 * k / 30 : 1250, y = k < 30 ? 0 : -6650.0 * (k - 30) / 70;
      const double ex = k < 30 ? x - 100 : 1150, ey = k < 30 ? 0 : y + 100;
      ts << t << ',' << x << ',' << y << ",0,5000,0,3000," << ex << ',' << ey << ",-200,5831," << 200 << '\n';
      for (int j = 0; j <= 2; ++j)
        nd << t << ',' << j << ',' << x + j * (ex - x) / 2 << ',' << y + j * (ey - y) / 2 << ',' << -100.0 * j
           << ",0,0,0," << 5000 - 100 * j << '\n';
    }
    std::ofstream(dir_ / "summary.json") << "{\"model\": \"tall\", \"status\": \"ok\"}\n";
  }

  /// A winch run: paying out at 1 m/s from 600 m to 900 m, holding, hauling
  /// back at 1 m/s; the tow tension 4 % to 11 % of the winch rating.
  void write_winch_run() {
    std::ofstream ts(dir_ / "timeseries.csv");
    ts << "time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z,tow_tension,end_depth,"
          "deployed_length,payout_speed,winch_load_ratio\n";
    std::ofstream nd(dir_ / "nodes.csv");
    nd << "time,node,x,y,z,vx,vy,vz,tension\n";
    for (int k = 0; k <= 130; ++k) {
      const double t = 10.0 * k;
      const double v = t >= 60 && t < 360 ? 1.0 : t >= 700 && t < 1000 ? -1.0 : 0.0;
      const double len = t < 60 ? 600 : t < 360 ? 600 + (t - 60) : t < 700 ? 900 : t < 1000 ? 900 - (t - 700) : 600;
      ts << t << ',' << 2 * t << ",0,0,3000,0,1000," << 2 * t - 500 << ",0,-250,3162,250," << len << ',' << v << ','
         << 0.04 + 0.07 * t / 1300 << '\n';
      for (int j = 0; j <= 2; ++j)
        nd << t << ',' << j << ',' << 2 * t - 250.0 * j << ",0," << -125.0 * j << ",0,0,0,3000\n";
    }
    std::ofstream(dir_ / "summary.json") << "{\"model\": \"synthetic\", \"status\": \"ok\"}\n";
  }
};

// The x tick labels of a tall plan view stand apart on the rendered PNG: below
// the plot box, one cluster of dark pixels per tick of the axis's range,
// separated by at least 10 pixels (the characters of one label are 3-4 px
// apart). Before, gnuplot's 500 m step put 6 labels in 226 px: 3 clusters.
TEST_F(PlotPicture, PlanViewTickLabelsDoNotOverlap) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_tall_track();
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  const std::string gp = towsim::testing::slurp(dir_ / "plots" / "paths_xy.gp");
  EXPECT_NE(gp.find("\nset xtics 1000\n"), std::string::npos) << gp;
  EXPECT_NE(gp.find("\nset ytics 1000\n"), std::string::npos) << gp;
  towsim::testing::Image img;
  std::string error;
  if (!towsim::testing::load_png((dir_ / "plots" / "paths_xy.png").string(), img, error)) GTEST_SKIP() << error;
  // The x range gnuplot drew, and so the ticks it labelled.
  const auto [rc, out] = towsim::testing::shell("cd '" + (dir_ / "plots").string() +
                                                "' && gnuplot paths_xy.gp -e 'print GPVAL_X_MIN, GPVAL_X_MAX' 2>&1");
  ASSERT_EQ(rc, 0) << out;
  std::istringstream range(out);
  double x0 = 0, x1 = 0;
  range >> x0 >> x1;
  const int ticks = static_cast<int>(std::floor(x1 / 1000) - std::ceil(x0 / 1000) + 1);
  EXPECT_EQ(ticks, 3);                          // -1000, 0, 1000 in about [-1590, 1390]
  const auto borders = border_rows(img, 0.15);  // the box is ~230 px of 1000
  ASSERT_FALSE(borders.empty());
  const int bottom = borders.back();
  const auto labels = dark_runs(img, bottom + 4, bottom + 4 + 24, 5);  // one line of 13 point text
  ASSERT_EQ(static_cast<int>(labels.size()), ticks);
  for (std::size_t i = 1; i < labels.size(); ++i) EXPECT_GE(labels[i].first - labels[i - 1].second, 10) << i;
}

// The winch figure: the pay-out speed on its own right-hand axis over its own
// range (-1..1 m/s drawn on -1.2..1.2, not on the deployed length's -2..12),
// the load in a panel of its own, and a short title inside the canvas.
TEST_F(PlotPicture, WinchPayOutSpeedOnItsOwnAxisAndTheTitleInside) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  write_winch_run();
  std::ostringstream log;
  ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
  const std::string gp = towsim::testing::slurp(dir_ / "plots" / "winch.gp");
  EXPECT_NE(gp.find("set multiplot layout 2,1 title 'synthetic: winch'\n"), std::string::npos) << gp;
  EXPECT_NE(gp.find("set y2range [-1.2:1.2]\n"), std::string::npos) << gp;
  EXPECT_NE(gp.find("set y2label 'pay-out speed (m/s)'\n"), std::string::npos) << gp;
  EXPECT_NE(gp.find("set ylabel 'tow tension / rating (%)'\n"), std::string::npos) << gp;
  towsim::testing::Image img;
  std::string error;
  if (!towsim::testing::load_png((dir_ / "plots" / "winch.png").string(), img, error)) GTEST_SKIP() << error;
  const auto borders = border_rows(img, 0.6);  // the two panels' top and bottom edges
  ASSERT_GE(borders.size(), 4u);
  // The title and the legend above the first panel: every dark pixel at
  // least 3 px inside the canvas (a clipped title touches its edge).
  const int top = borders.front();
  int dark = 0;
  for (int y = 0; y < top; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.dark(x, y)) {
        ++dark;
        EXPECT_TRUE(x >= 3 && x < img.width - 3) << x << "," << y;
      }
  EXPECT_GT(dark, 100);  // the title is there
  // The pay-out speed (red, #d62728) spans 2 of the axis's 2.4: 83 % of the
  // panel's height (at least 75 %: the line's width and the border rows
  // blur its ends). On the old shared -2..12 axis: 14 %.
  int panel_bottom = top;
  for (int y : borders)
    if (y < img.height / 2) panel_bottom = y;
  int red_lo = img.height, red_hi = -1;
  for (int y = top; y <= panel_bottom; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.channel(x, y, 0) > 170 && img.channel(x, y, 1) < 90 && img.channel(x, y, 2) < 90)
        red_lo = std::min(red_lo, y), red_hi = std::max(red_hi, y);
  ASSERT_GE(red_hi, red_lo);
  EXPECT_GE(static_cast<double>(red_hi - red_lo) / (panel_bottom - top), 0.75);
}

// Every axis of every figure says its unit.
TEST_F(PlotPicture, EveryAxisLabelHasAUnit) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  const std::regex label(R"(set (x|y|y2|cb)label '([^']*)')");
  const std::regex unit(R"(\((m|s|N|deg|m/s|%|rad/s|m\^2 s/rad|N\^2 s/rad|m/m)\))");
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 0)
      write_run(true, true);
    else
      write_winch_run();
    std::ostringstream log;
    ASSERT_EQ(plot_run(dir_.string(), log), 0) << log.str();
    int labels = 0;
    for (const auto& e : fs::directory_iterator(dir_ / "plots")) {
      if (e.path().extension() != ".gp") continue;
      const std::string gp = towsim::testing::slurp(e.path());
      for (auto it = std::sregex_iterator(gp.begin(), gp.end(), label); it != std::sregex_iterator(); ++it, ++labels)
        EXPECT_TRUE(std::regex_search((*it)[2].str(), unit)) << e.path().filename() << ": " << (*it)[0];
    }
    EXPECT_GE(labels, pass == 0 ? 20 : 14);
  }
}
