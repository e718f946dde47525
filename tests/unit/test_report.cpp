// `towsim report DIR`: the self-contained page (io/report.hpp), with and
// without the 3-D view, and loaded offline in headless Chromium.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../support/cli.hpp"
#include "report.hpp"

namespace fs = std::filesystem;
using towsim::testing::fresh_dir;
using towsim::testing::shell;
using towsim::testing::towsim_cli;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A short run of the 3-D example with a body into `dir`.
void short_run(const fs::path& dir) {
  const auto [status, out] = towsim_cli("run --example paper-3d-turn --set simulation.duration=20 --out '" +
                                        dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
}

/// The first Chromium program on PATH, "" when none.
std::string chromium() {
  for (const char* p : {"chromium", "chromium-browser", "google-chrome"})
    if (std::system((std::string("command -v ") + p + " >/dev/null 2>&1").c_str()) == 0) return p;
  return "";
}

/// The value of attribute `name` of the <html> element in a DOM dump, "" if absent.
std::string html_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  const std::regex re("<html[^>]*\\s" + name + "=\"([^\"]*)\"");
  return std::regex_search(dom, m, re) ? m[1].str() : std::string();
}

}  // namespace

TEST(Report, ThePageHoldsTheViewerTheDataTheFiguresAndTheSummary) {
  const fs::path dir = fresh_dir("report");
  short_run(dir);
  const auto [status, out] = towsim_cli("report '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const std::string page = slurp(dir / "report.html");
  EXPECT_NE(page.find("<script id=\"towsim-data\" type=\"application/json\">"), std::string::npos);
  EXPECT_NE(page.find("id=\"view3d\""), std::string::npos);
  EXPECT_NE(page.find("<tr><td>final layback</td><td class=\"n\">"), std::string::npos);
  EXPECT_NE(page.find("max_tow_tension"), std::string::npos);
  // Self-contained: nothing loaded from elsewhere (figures are data URIs).
  EXPECT_EQ(page.find("src=\"http"), std::string::npos);
  EXPECT_EQ(page.find("href=\"http"), std::string::npos);
  EXPECT_EQ(page.find("<script src="), std::string::npos);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_NE(page.find("id=\"fig-depth_layback\""), std::string::npos);
    EXPECT_NE(page.find("id=\"fig-tension_map\""), std::string::npos);
    EXPECT_NE(page.find("src=\"data:image/png;base64,iVBOR"), std::string::npos);  // a PNG's signature
  }
  fs::remove_all(dir);
}

TEST(Report, WithoutTheViewerThePageSaysWhyAndKeepsTheRest) {
  // The path of a build without npm: no bundle, a note instead of the view.
  const fs::path dir = fresh_dir("report");
  short_run(dir);
  towsim::cli::ReportOptions opt;
  opt.viewer_note = "npm was not found when towsim was built (test)";
  opt.plots = false;
  std::ostringstream log;
  ASSERT_EQ(towsim::cli::report_run(dir.string(), log, opt), 0) << log.str();
  const std::string page = slurp(dir / "report.html");
  EXPECT_NE(page.find("id=\"no3d\""), std::string::npos);
  EXPECT_NE(page.find("npm was not found when towsim was built (test)"), std::string::npos);
  EXPECT_EQ(page.find("id=\"view3d\""), std::string::npos);
  EXPECT_NE(page.find("<tr><td>final layback</td><td class=\"n\">"), std::string::npos);
  EXPECT_NE(log.str().find("without the 3-D view"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Report, OfARunWithoutNodesDrawsTheChordAndSaysSo) {
  // write_nodes: false leaves no nodes.csv: the page still has its 3-D view
  // (tow point to cable end, from timeseries.csv), a note, the summary.
  const fs::path dir = fresh_dir("report");
  const auto [st, so] = towsim_cli(
      "run --example paper-3d-turn --set simulation.duration=5 "
      "--set simulation.write_nodes=false --out '" +
      dir.string() + "'");
  ASSERT_EQ(st, 0) << so;
  ASSERT_FALSE(fs::exists(dir / "nodes.csv"));
  const auto [status, out] = towsim_cli("report '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const std::string page = slurp(dir / "report.html");
  EXPECT_NE(page.find("id=\"no-nodes\""), std::string::npos);
  EXPECT_NE(page.find("not the cable's shape"), std::string::npos);
  EXPECT_NE(page.find("towsim-data"), std::string::npos);
  EXPECT_NE(page.find("<tr><td>final layback</td><td class=\"n\">"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Report, RefusesADirectoryWithoutOutputs) {
  const fs::path dir = fresh_dir("report");
  const auto [status, out] = towsim_cli("report '" + dir.string() + "'");
  EXPECT_EQ(status, 2);
  EXPECT_NE(out.find("has no timeseries.csv"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dir / "report.html"));
  fs::remove_all(dir);
}

TEST(Report, OfAStaticsConfiguration) {
  const fs::path dir = fresh_dir("report");
  const auto [st, so] = towsim_cli("statics --example paper-3d-turn --out '" + dir.string() + "'");
  ASSERT_EQ(st, 0) << so;
  const auto [status, out] = towsim_cli("report '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(slurp(dir / "report.html").find("towsim-data"), std::string::npos);
  fs::remove_all(dir);
}

// The page loaded offline in headless Chromium: the 3-D view draws its first
// frame (the page marks <html data-ready="1"> and counts the canvas pixels
// that differ from the background) and no script error occurred.
namespace {
void expect_renders_in_chromium(const std::string& name, const std::string& run_settings,
                                std::string* page_dom = nullptr,
                                const std::string& example = "paper-3d-turn --set simulation.duration=20") {
  if (towsim::cli::embedded_viewer_js().empty())
    GTEST_SKIP() << "this towsim was built without the 3-D view: " << towsim::cli::embedded_viewer_note();
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  const fs::path dir = fs::path(TOWSIM_TEST_OUTPUT_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  // `example`: a built-in example's name, or a scenario file's absolute path.
  const std::string input = example.front() == '/' ? "'" + example + "'" : "--example " + example;
  const auto [rs, ro] = towsim_cli("run " + input + " " + run_settings + " --out '" + dir.string() + "'");
  ASSERT_EQ(rs, 0) << ro;
  const auto [status, out] = towsim_cli("report '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  // Offline: every host name fails to resolve. WebGL through SwiftShader
  // (software), as there is no GPU. Virtual time lets the page finish.
  const std::string flags =
      "--headless --disable-gpu --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--host-resolver-rules='MAP * ~NOTFOUND' --no-first-run --disable-extensions "
      "--user-data-dir='" +
      (dir / "profile").string() + "' --virtual-time-budget=10000 --window-size=1280,1600 ";
  const std::string url = "'file://" + fs::absolute(dir / "report.html").string() + "'";
  const auto [rc, dom] = shell(browser + " " + flags + "--dump-dom " + url + " 2>/dev/null");
  ASSERT_EQ(rc, 0) << dom.substr(0, 2000);
  EXPECT_EQ(html_attribute(dom, "data-error"), "") << "script error in the page";
  ASSERT_EQ(html_attribute(dom, "data-ready"), "1") << dom.substr(0, 2000);
  EXPECT_NE(dom.find("<canvas"), std::string::npos);
  // The scene covers a real part of the 3-D view (the cable, body, sea grid):
  // more than 1000 pixels of the ~1200 x 560 view differ from the background.
  const std::string drawn = html_attribute(dom, "data-drawn-pixels");
  ASSERT_FALSE(drawn.empty());
  EXPECT_GT(std::stol(drawn), 1000);
  EXPECT_NE(dom.find("(3-D view ready)"), std::string::npos);  // the title
  if (page_dom != nullptr) *page_dom = dom;
  // A screenshot for a person to look at, kept in the build tree.
  const fs::path png = dir / "report_screenshot.png";
  const auto [sr, so] = shell(browser + " " + flags + "--screenshot='" + png.string() + "' " + url);
  EXPECT_EQ(sr, 0) << so;
  EXPECT_TRUE(fs::is_regular_file(png));
  std::cout << "[ screenshot ] " << png.string() << "\n";
}
}  // namespace

TEST(ReportInBrowser, TheThreeDViewRendersOfflineInHeadlessChromium) {
  expect_renders_in_chromium("report_browser", "");
}

// Without nodes.csv the view draws the tow-point-to-end chord, and renders.
TEST(ReportInBrowser, TheChordViewOfARunWithoutNodesRenders) {
  expect_renders_in_chromium("report_browser_chord", "--set simulation.write_nodes=false");
}

// ------------------------------------------- units, framing, body (issue 30)

TEST(Report, EverySummaryKeyHasItsUnit) {
  using towsim::cli::summary_unit;
  EXPECT_EQ(summary_unit("max_tow_tension"), "N");
  EXPECT_EQ(summary_unit("min_axial_force"), "N");
  EXPECT_EQ(summary_unit("max_depressor_lower_link_force"), "N");
  EXPECT_EQ(summary_unit("max_end_depth"), "m");
  EXPECT_EQ(summary_unit("max_layback"), "m");
  EXPECT_EQ(summary_unit("max_contact_length"), "m");
  EXPECT_EQ(summary_unit("body_pitch_deg"), "deg");
  EXPECT_EQ(summary_unit("wall_seconds"), "s");
  EXPECT_EQ(summary_unit("end_time"), "s");
  EXPECT_EQ(summary_unit("steps"), "count");
  EXPECT_EQ(summary_unit("rhs_evaluations"), "count");
  EXPECT_EQ(summary_unit("samples"), "output times");
  EXPECT_EQ(summary_unit("max_utilisation"), "fraction of the breaking load");
  EXPECT_EQ(summary_unit("status"), "");
}

namespace {
/// The report's summary table rows: (quantity, unit) per row.
std::vector<std::pair<std::string, std::string>> table_units(const std::string& page) {
  std::vector<std::pair<std::string, std::string>> rows;
  const std::regex row(R"(<tr><td>([^<]*)</td><td class="n">[^<]*</td><td>([^<]*)</td><td class="n">)");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), row); it != std::sregex_iterator(); ++it)
    rows.emplace_back((*it)[1].str(), (*it)[2].str());
  return rows;
}

/// The page's embedded data (the 3-D view's JSON).
nlohmann::json page_data(const std::string& page) {
  const std::string open = "<script id=\"towsim-data\" type=\"application/json\">";
  const auto a = page.find(open);
  if (a == std::string::npos) return {};
  const auto b = page.find("</script>", a);
  return nlohmann::json::parse(page.substr(a + open.size(), b - a - open.size()));
}
}  // namespace

// A winch run with a 3 m fish on a 2.7 km track (fish-depth-change, 1300 s at
// 4 kn): the summary table gives every quantity's unit; the view's data frame
// the cable, not the track, and hold the body's true dimensions.
TEST(Report, ALongTrackFramesTheCableAndTheBodyAtItsSize) {
  const fs::path dir = fresh_dir("report");
  const auto [rs, ro] = towsim_cli("run --example fish-depth-change --quiet --out '" + dir.string() + "'");
  ASSERT_EQ(rs, 0) << ro;
  const auto [status, out] = towsim_cli("report --no-plots '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const std::string page = slurp(dir / "report.html");
  EXPECT_NE(page.find("<th>quantity</th><th>value</th><th>unit</th><th>at t (s)</th>"), std::string::npos);
  const auto rows = table_units(page);
  ASSERT_GE(rows.size(), 20u);
  for (const auto& [quantity, unit] : rows)
    if (quantity != "status") {
      EXPECT_FALSE(unit.empty()) << quantity;
    }
  EXPECT_NE(std::find(rows.begin(), rows.end(), std::make_pair(std::string("max_tow_tension"), std::string("N"))),
            rows.end());
  EXPECT_NE(std::find(rows.begin(), rows.end(), std::make_pair(std::string("final layback"), std::string("m"))),
            rows.end());

  const auto data = page_data(page);
  ASSERT_TRUE(data.is_object());
  // The fish: a 3 m x 0.35 m hull along x, two fins of 0.15 m^2 (the scenario).
  const auto& body = data.at("body");
  ASSERT_EQ(body.at("cylinders").size(), 1u);
  EXPECT_EQ(body["cylinders"][0].at("length").get<double>(), 3.0);
  EXPECT_EQ(body["cylinders"][0].at("diameter").get<double>(), 0.35);
  EXPECT_EQ(body["cylinders"][0].at("axis"), nlohmann::json::parse("[1, 0, 0]"));
  ASSERT_EQ(body.at("surfaces").size(), 2u);
  EXPECT_EQ(body["surfaces"][0].at("area").get<double>(), 0.15);
  EXPECT_TRUE(body.at("spheres").empty());
  // The framing: the cable's largest box in any frame, at most the drum's
  // 900 m of cable plus the 3 m fish, at least the tow-point-to-fish chord
  // of the first frame (layback 556.3 m, depth 226.0 m: 600.4 m); the whole
  // run at least the 4 kn x 1300 s = 2675 m track.
  const auto& view = data.at("view");
  const double cable = view.at("cable_extent").get<double>(), all = view.at("all_extent").get<double>();
  EXPECT_LE(cable, 903.0);
  EXPECT_GE(cable, 600.0);
  EXPECT_GE(all, 2675.0);
  // The first frame's view centre: the middle of the box around its joints and
  // the body origin.
  const auto& p = data.at("nodes").at(0);
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (std::size_t k = 0; k + 2 < p.size(); k += 3)
    for (std::size_t d = 0; d < 3; ++d)
      lo[d] = std::min(lo[d], p[k + d].get<double>()), hi[d] = std::max(hi[d], p[k + d].get<double>());
  for (std::size_t d = 0; d < 3; ++d) {
    const double b = body.at("pos").at(0).at(d).get<double>();
    lo[d] = std::min(lo[d], b), hi[d] = std::max(hi[d], b);
  }
  // 1e-3 m: the page's numbers have 7 significant digits (0.1 mm on 1 km).
  for (std::size_t d = 0; d < 3; ++d)
    EXPECT_NEAR(view.at("cable_centres").at(0).at(d).get<double>(), 0.5 * (lo[d] + hi[d]), 1e-3) << d;
  EXPECT_EQ(view.at("cable_centres").size(), data.at("times").size());
  fs::remove_all(dir);
}

// A network's run (examples/bridled-towfish.yaml: main line, then the two
// bridle legs from the shackle at its end): the viewer's data breaks the drawn
// line where each leg starts, and each leg starts at the shackle, the main
// line's last joint (1e-3 m: the page's 7 significant digits).
TEST(Report, ANetworkRunBreaksTheDrawnLineBetweenLines) {
  const fs::path dir = fresh_dir("report");
  const auto [rs, ro] = towsim_cli("run '" + std::string(TOWSIM_SOURCE_DIR) +
                                   "/examples/bridled-towfish.yaml' --set simulation.duration=20 --quiet --out '" +
                                   dir.string() + "'");
  ASSERT_EQ(rs, 0) << ro;
  const auto [status, out] = towsim_cli("report --no-plots '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const auto data = page_data(slurp(dir / "report.html"));
  ASSERT_TRUE(data.is_object());
  const auto& breaks = data.at("breaks");
  ASSERT_EQ(breaks.size(), 2u);  // leg_fwd and leg_aft after main
  for (const auto& p : data.at("nodes")) {
    const std::size_t legs = breaks[0].get<std::size_t>(), aft = breaks[1].get<std::size_t>();
    ASSERT_GT(aft, legs);
    ASSERT_GT(p.size() / 3, aft);
    for (const std::size_t start : {legs, aft})
      for (std::size_t d = 0; d < 3; ++d)
        EXPECT_NEAR(p[3 * start + d].get<double>(), p[3 * (legs - 1) + d].get<double>(), 1e-3) << start << " " << d;
  }
  // The fish drawn with its own shapes (a hull cylinder, two fins) at its
  // pose of each frame: timeseries.csv's fish_x, ..., fish_yaw_deg at that
  // time (1e-6 relative: the page prints 7 significant digits).
  ASSERT_TRUE(data.at("body").is_null());
  const auto& bodies = data.at("bodies");
  ASSERT_EQ(bodies.size(), 1u);
  const auto& fish = bodies[0];
  EXPECT_EQ(fish.at("name"), "fish");
  EXPECT_EQ(fish.at("cylinders").size(), 1u);
  EXPECT_EQ(fish.at("surfaces").size(), 2u);
  const auto ts = towsim::testing::read_csv(dir / "timeseries.csv");
  const int ct = ts.column("time");
  const auto& times = data.at("times");
  ASSERT_EQ(fish.at("pos").size(), times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    const auto row = std::find_if(ts.rows.begin(), ts.rows.end(), [&](const std::vector<double>& r) {
      return std::abs(r[static_cast<std::size_t>(ct)] - times[i].get<double>()) < 1e-9;
    });
    ASSERT_NE(row, ts.rows.end());
    const char* cols[6] = {"fish_x", "fish_y", "fish_z", "fish_roll_deg", "fish_pitch_deg", "fish_yaw_deg"};
    for (std::size_t k = 0; k < 6; ++k) {
      const double want = (*row)[static_cast<std::size_t>(ts.column(cols[k]))];
      const double got = (k < 3 ? fish.at("pos")[i][k] : fish.at("rpy")[i][k - 3]).get<double>();
      EXPECT_NEAR(got, want, 1e-6 * std::max(1.0, std::abs(want))) << cols[k] << " at " << times[i];
    }
  }
  fs::remove_all(dir);
}

// A network whose main line is paid out by its winch: its joints change
// from frame to frame, yet every frame keeps as many of each line's joints
// (the line's fewest), so the drawn line breaks at the same places and both
// legs start at the shackle, the main line's last joint kept, to 1e-3 m.
TEST(Report, ANetworkRunWithAWinchKeepsItsLinesApart) {
  const fs::path dir = fresh_dir("report");
  const auto [rs, ro] = towsim_cli("run '" + std::string(TOWSIM_SOURCE_DIR) +
                                   "/examples/bridled-towfish.yaml' --set simulation.duration=20 --set "
                                   "'lines.0.winch={rate: 1.0}' --quiet --out '" +
                                   dir.string() + "'");
  ASSERT_EQ(rs, 0) << ro;
  const std::string nodes = slurp(dir / "nodes.csv");
  ASSERT_EQ(nodes.rfind("line,time,node,node_id,", 0), 0u);  // the winch's joint identities
  const auto [status, out] = towsim_cli("report --no-plots '" + dir.string() + "'");
  ASSERT_EQ(status, 0) << out;
  const auto data = page_data(slurp(dir / "report.html"));
  const auto& breaks = data.at("breaks");
  ASSERT_EQ(breaks.size(), 2u);
  const std::size_t legs = breaks[0].get<std::size_t>();
  for (const auto& p : data.at("nodes")) {
    ASSERT_EQ(p.size() / 3, legs + 4);  // the main line's joints kept, then 2 per leg
    for (const std::size_t start : {legs, breaks[1].get<std::size_t>()})
      for (std::size_t d = 0; d < 3; ++d)
        EXPECT_NEAR(p[3 * start + d].get<double>(), p[3 * (legs - 1) + d].get<double>(), 1e-3) << start << " " << d;
  }
  fs::remove_all(dir);
}

TEST(ReportInBrowser, ANetworkRunRenders) {
  expect_renders_in_chromium("report_network", "--set simulation.duration=20", nullptr,
                             std::string(TOWSIM_SOURCE_DIR) + "/examples/bridled-towfish.yaml");
}

// A 3 m fish on a 2.7 km track (fish-depth-change): the view opens on the
// cable, which spans a good part of it (the first frame's 600 m of cable, seen
// obliquely in a view sized for the 903 m the cable takes at most: 0.245 of
// the view measured, at least 0.2 asserted; framed on the whole track it took
// about 0.04), and the body is drawn at its true size: its shapes' box,
// in body axes, is the 3 m hull and the fins' squares of sqrt(0.15) = 0.3873 m.
TEST(ReportInBrowser, ALongTrackOpensOnTheCableWithTheBodyAtItsSize) {
  std::string dom;
  expect_renders_in_chromium("report_browser_long_track", "", &dom, "fish-depth-change");
  if (dom.empty()) return;  // skipped
  const std::string size = html_attribute(dom, "data-body-size");
  ASSERT_FALSE(size.empty());
  double sx = 0, sy = 0, sz = 0;
  ASSERT_EQ(std::sscanf(size.c_str(), "%lf,%lf,%lf", &sx, &sy, &sz), 3) << size;
  // 1e-4 m: the page prints 6 significant digits.
  EXPECT_NEAR(sx, 3.0, 1e-4);
  EXPECT_NEAR(sy, std::sqrt(0.15), 1e-4);
  EXPECT_NEAR(sz, std::sqrt(0.15), 1e-4);
  const std::string fraction = html_attribute(dom, "data-cable-view-fraction");
  ASSERT_FALSE(fraction.empty());
  EXPECT_GE(std::stod(fraction), 0.2);
}
