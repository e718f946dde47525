// `towsim report DIR`: DIR/report.html, one self-contained page viewable
// offline: an animated 3-D view of the cable and body (three.js, bundled at
// build time and inlined), the figures of `towsim plot` (PNG data URIs) and
// the summary. Reads the output of `towsim run --out DIR` or
// `towsim statics --out DIR`; nodes.csv is read once.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>

namespace towsim::cli {

/// Options of report_run.
struct ReportOptions {
  int max_frames = 300;  // animation frames, spread evenly over the output times
  int max_nodes = 400;   // joints drawn per frame (spread evenly, both ends kept)
  bool plots = true;     // render the figures first (`towsim plot`); false: use DIR/plots as it is
  /// The 3-D view's script (three.js and web/viewer.js, one IIFE) and, when
  /// it is empty, why: the page then shows that note instead of the view.
  std::string_view viewer_js;
  std::string_view viewer_note;
};

/// The bundle embedded at build time (cmake/ReportViewer.cmake); empty when
/// the build had no npm, and then embedded_viewer_note() says why.
std::string_view embedded_viewer_js();
std::string_view embedded_viewer_note();

/// The unit of a summary.json key as the report's summary table prints it
/// ("m", "N", "deg", "s", "count", ...; "" for a key without one, e.g. status).
std::string summary_unit(const std::string& key);

/// Options with the embedded viewer.
ReportOptions default_report_options();

/// Write DIR/report.html. Progress and errors go to `log`. Returns 0 on
/// success (also without gnuplot or without the 3-D view: the page says
/// what is missing), 2 when DIR is not an output directory (nothing written),
/// 1 when the page cannot be written.
int report_run(const std::string& dir, std::ostream& log, const ReportOptions& options);

}  // namespace towsim::cli
