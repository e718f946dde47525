// What every `towsim plot` figure set shares: quoting, a figure's rendering
// as PNG and SVG, the gnuplot program and the rendering of a set of scripts.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "plot.hpp"

namespace towsim::cli::plot_render {

constexpr int kOk = 0;             // every figure written
constexpr int kGnuplotFailed = 1;  // a figure failed (gnuplot's messages in the log)
constexpr int kInvalid = 2;        // not a run's directory, or no usable gnuplot

/// The settings every figure starts with: CSV read by column name, grid, key, border.
std::string style();
/// s as a gnuplot string literal.
std::string quote(const std::string& s);
/// Script text that renders the current plot (`plot_cmd`) as NAME.png and NAME.svg.
std::string render(const std::string& name, const std::string& plot_cmd, const PlotOptions& o);
/// The gnuplot program, checked for its pngcairo and svg terminals; "" (the
/// reason in `log`) when it cannot draw.
std::string usable_gnuplot(std::ostream& log);
/// Write each (name, script) into `plots` and render it with `prog`.
int render_scripts(const std::filesystem::path& plots, const std::vector<std::pair<std::string, std::string>>& scripts,
                   const std::string& prog, std::ostream& log);

}  // namespace towsim::cli::plot_render
