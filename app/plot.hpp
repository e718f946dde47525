// `towsim plot DIR`: figures of a run's outputs, rendered by gnuplot.
//
// Reads DIR/timeseries.csv, DIR/nodes.csv and DIR/summary.json (the output
// of `towsim run --out DIR`), writes one gnuplot script per figure into
// DIR/plots/NAME.gp (data read straight from the CSV files, by column name;
// re-run one by hand with `cd DIR/plots && gnuplot NAME.gp`) and runs the
// `gnuplot` program (>= 5.4, with the pngcairo and svg terminals) on each, which
// writes DIR/plots/NAME.png and DIR/plots/NAME.svg. The figures:
//   trajectories_xz  tow point, cable lower end, body origin (when it is not
//                    the lower end) and, for a body of two or more spheres,
//                    the second sphere's centre, in the x-z plane
//   tow_force        tow force components and magnitude vs time
//   paths_xy         horizontal paths of both cable ends (3D runs only)
//   end_depth        depth of the cable's lower end vs time
//   body_angles      body roll, pitch, yaw vs time (with a body)
//   cable_shapes_xz  cable shape at 8 evenly spaced times, side view
//   cable_shapes_xy  the same in plan view (3D runs only)
//   link_force       link force components and magnitude vs time (with a body)
//   depth_layback    depth of the body origin (or cable end) against layback
//   tension_map      tension along the cable (distance from the tow point)
//                    against time, a colour map of up to 200 output times
//   tension_along_cable  (one output time, `towsim statics --out DIR`) tension
//                    against distance along the cable
//   spectra          (with DIR/spectra.csv, a sea-state run) spectral densities
//                    of wave elevation, tow point heave, body heave and tow
//                    tension; below, the ship -> fish transfer function (body
//                    heave per tow point heave) and body heave per metre of wave
// The figures against time (tow_force, end_depth, body_angles, link_force,
// winch, tension_map) mark each boundary of a phase other than steady from
// summary.json `phases` with a dashed vertical line and a label.
// nodes.csv is read once: the rows the figures need are extracted into
// DIR/plots/cable_shapes.dat and DIR/plots/tension_map.dat. summary.json is
// optional (the model name is then the directory's name). DIR/plots/ is
// emptied first (it is towsim's; no stale figure of an earlier run remains).
// A run is "3D" when some y coordinate is non-zero. The program is `gnuplot`
// from PATH, or the one named by the environment variable TOWSIM_GNUPLOT.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace towsim::cli {

/// Rendering options of plot_run.
struct PlotOptions {
  int width = 1000;  // PNG and SVG size, pixels
  int height = 700;
  int snapshots = 8;  // cable shapes drawn in cable_shapes_*
};

/// Render DIR's figures into DIR/plots/. Progress and errors go to `log`.
/// Returns 0 on success; 2 (nothing rendered) when DIR or one of its three
/// files is missing or unreadable (the message names the missing files), or
/// when gnuplot (or its pngcairo/svg terminal) is missing (the message says
/// to install gnuplot-nox); 1 when gnuplot fails on a script (its messages are
/// copied to `log` and kept in DIR/plots/gnuplot.log).
int plot_run(const std::string& dir, std::ostream& log);
int plot_run(const std::string& dir, std::ostream& log, const PlotOptions& options);

/// Tick marks of a figure's axis: the step between labelled ticks and whether
/// the labels are turned upright (rotated by 90 degrees) to fit.
struct AxisTicks {
  double step = 0;
  bool rotate = false;
};

/// The ticks of an axis spanning [lo, lo + span] over `pixels` pixels with
/// labels in a font of `font` points: the smallest 1-2-5 step of at least a
/// tenth of the span that gives two labels or more with room between them
/// (`horizontal`: side by side, a gap of two characters or a third of the
/// longest label, else upright; vertical: one line apart). Step 0 when the
/// span or the pixels are not > 0.
AxisTicks axis_ticks(double lo, double span, double pixels, int font, bool horizontal);

/// The figure names (without extension) plot_run renders for a run with or
/// without a body, planar or 3D; `single`: one output time (the output of
/// `towsim statics --out`), where only the cable's shape and tension are drawn;
/// `spectra`: DIR/spectra.csv exists (a sea-state run).
std::vector<std::string> plot_names(bool has_body, bool three_d, bool single = false, bool spectra = false);

}  // namespace towsim::cli
