// `towsim plot` on a network's run (docs/scenario.md "A network's outputs"):
// the top tension of every line, the depth of every body and junction, and
// the network's shape at the last output time, side and plan views.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

#include "plot.hpp"
#include "run_files.hpp"

namespace towsim::cli {

/// True when root/nodes.csv's header starts with the network's `line` column.
bool is_network_run(const std::filesystem::path& root);

/// Write root/plots/{line_tensions, depths, network_shape_xz, network_shape_xy}
/// (.gp, .png, .svg) from timeseries.csv (`ts`, read) and nodes.csv. Returns
/// 0, 1 (a figure failed) or 2 (nothing to plot, no usable gnuplot).
int plot_network_run(const std::filesystem::path& root, const CsvTable& ts, const std::string& model,
                     const PlotOptions& opt, std::ostream& log);

}  // namespace towsim::cli
