// `towsim report DIR`: the self-contained page (io/report.hpp), with and
// without the 3-D view, and loaded offline in headless Chromium.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

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
  EXPECT_NE(page.find("final layback [m]"), std::string::npos);
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
  towsim::io::ReportOptions opt;
  opt.viewer_note = "npm was not found when towsim was built (test)";
  opt.plots = false;
  std::ostringstream log;
  ASSERT_EQ(towsim::io::report_run(dir.string(), log, opt), 0) << log.str();
  const std::string page = slurp(dir / "report.html");
  EXPECT_NE(page.find("id=\"no3d\""), std::string::npos);
  EXPECT_NE(page.find("npm was not found when towsim was built (test)"), std::string::npos);
  EXPECT_EQ(page.find("id=\"view3d\""), std::string::npos);
  EXPECT_NE(page.find("final layback [m]"), std::string::npos);
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
  EXPECT_NE(page.find("final layback [m]"), std::string::npos);
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
void expect_renders_in_chromium(const std::string& name, const std::string& run_settings) {
  if (towsim::io::embedded_viewer_js().empty())
    GTEST_SKIP() << "this towsim was built without the 3-D view: " << towsim::io::embedded_viewer_note();
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  const fs::path dir = fs::path(TOWSIM_TEST_OUTPUT_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto [rs, ro] = towsim_cli("run --example paper-3d-turn --set simulation.duration=20 " + run_settings +
                                   " --out '" + dir.string() + "'");
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
