#include "plot_network.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <ostream>
#include <sstream>
#include <vector>

#include "plot_render.hpp"

namespace towsim::cli {

namespace {

namespace fs = std::filesystem;
using plot_render::quote;

/// Names whose column `<name><suffix>` the header has, in header order.
std::vector<std::string> prefixes(const CsvTable& ts, const std::string& suffix) {
  std::vector<std::string> out;
  for (const std::string& c : ts.names)
    if (c.size() > suffix.size() && c.compare(c.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(c.substr(0, c.size() - suffix.size()));
  return out;
}

/// Script text common to the network's figures.
std::string preamble(const std::string& model, const std::string& name, const std::string& what) {
  std::ostringstream s;
  s << "# " << name << ".gp: " << what << " (" << model << ").\n"
    << "# Written by `towsim plot`; re-render from this directory with: gnuplot " << name << ".gp\n"
    << plot_render::style() << "set title " << quote(model + ": " + what) << "\n";
  return s.str();
}

/// One curve per column name over time, from ../timeseries.csv.
std::string time_figure(const std::string& model, const std::string& name, const std::string& what,
                        const std::string& ylabel, const std::vector<std::pair<std::string, std::string>>& curves,
                        bool reverse_y, const PlotOptions& o) {
  std::ostringstream s;
  s << preamble(model, name, what) << "set xlabel 'time [s]'\nset ylabel " << quote(ylabel) << "\n";
  if (reverse_y) s << "set yrange [*:*] reverse\n";
  std::ostringstream cmd;
  cmd << "plot ";
  for (std::size_t i = 0; i < curves.size(); ++i)
    cmd << (i ? ", \\\n     " : "") << "'../timeseries.csv' using 'time':" << quote(curves[i].first)
        << " with lines lw 1.5 title " << quote(curves[i].second);
  s << plot_render::render(name, cmd.str(), o);
  return s.str();
}

/// The shape of every line at time t_last (the last row of timeseries.csv)
/// into `dat` (one block per line, two blank lines apart: x y z tension),
/// read from nodes.csv in one pass keeping that time only (read_node_frames).
/// Returns the number of blocks (0: none, `error` says why).
std::size_t write_last_shapes(const fs::path& nodes, double t_last, const fs::path& dat, std::string& error) {
  std::vector<NodeFrame> frames;
  if (!read_node_frames(nodes.string(), {t_last}, frames, error)) return 0;
  if (frames.empty() || frames.front().x.empty()) {
    error = nodes.string() + ": no rows at the last time of timeseries.csv";
    return 0;
  }
  const NodeFrame& f = frames.front();
  std::ofstream out(dat, std::ios::trunc);
  std::size_t next = 0;  // the next line's start in f.line_starts
  for (std::size_t k = 0; k < f.x.size(); ++k) {
    if (next < f.line_starts.size() && k == f.line_starts[next]) out << "\n\n", ++next;
    out << f.x[k] << ' ' << f.y[k] << ' ' << f.z[k] << ' ' << f.tension[k] << '\n';
  }
  if (!out) {
    error = "cannot write " + dat.string();
    return 0;
  }
  return f.line_starts.size() + 1;
}

/// The network's lines at the last output time: x-z (side) or x-y (plan).
std::string shape_figure(const std::string& model, const std::vector<std::string>& lines, std::size_t blocks, bool plan,
                         const PlotOptions& o) {
  const std::string name = plan ? "network_shape_xy" : "network_shape_xz";
  std::ostringstream s;
  s << preamble(model, name, std::string("lines at the last output time, ") + (plan ? "plan view" : "side view"))
    << "set xlabel 'x [m]'\nset ylabel " << (plan ? "'y [m]'" : "'z [m]'") << "\nset size ratio -1\n"
    << "set datafile separator whitespace\nunset datafile columnheaders\n";
  std::ostringstream cmd;
  cmd << "plot ";
  for (std::size_t i = 0; i < blocks; ++i)
    cmd << (i ? ", \\\n     " : "") << "'network_shapes.dat' index " << i << " using 1:" << (plan ? 2 : 3)
        << " with linespoints pt 7 ps 0.4 lw 1.5 title " << quote(i < lines.size() ? lines[i] : "line");
  s << plot_render::render(name, cmd.str(), o);
  return s.str();
}

}  // namespace

bool is_network_run(const fs::path& root) {
  std::vector<std::string> names;
  std::string error;
  return read_csv_header((root / "nodes.csv").string(), names, error) && !names.empty() && names[0] == "line";
}

int plot_network_run(const fs::path& root, const CsvTable& ts, const std::string& model, const PlotOptions& opt,
                     std::ostream& log) {
  // 1. What the network is: its lines, bodies and junctions, from the columns.
  const std::vector<std::string> lines = prefixes(ts, "_top_tension");
  std::vector<std::pair<std::string, std::string>> tensions, depths;
  for (const std::string& l : lines) tensions.emplace_back(l + "_top_tension", l);
  for (const std::string& d : prefixes(ts, "_depth")) {
    const bool line_end = d.size() > 4 && d.compare(d.size() - 4, 4, "_end") == 0 &&
                          std::find(lines.begin(), lines.end(), d.substr(0, d.size() - 4)) != lines.end();
    if (!line_end) depths.emplace_back(d + "_depth", d);
  }
  if (lines.empty() || ts.rows.empty() || !ts.has("time")) {
    log << "towsim plot: " << (root / "timeseries.csv").string() << ": no line's top tension or no data rows\n";
    return plot_render::kInvalid;
  }
  // 2. gnuplot, before writing anything; then the figures' folder.
  const std::string prog = plot_render::usable_gnuplot(log);
  if (prog.empty()) return plot_render::kInvalid;
  const fs::path plots = root / "plots";
  std::error_code ec;
  fs::remove_all(plots, ec);  // towsim's folder: no stale figure of an earlier run
  fs::create_directories(plots, ec);
  if (ec) {
    log << "towsim plot: cannot create " << plots.string() << ": " << ec.message() << "\n";
    return plot_render::kGnuplotFailed;
  }
  // 3. Scripts, then figures.
  std::vector<std::pair<std::string, std::string>> scripts;
  scripts.emplace_back("line_tensions", time_figure(model, "line_tensions", "top tension of every line",
                                                    "top tension [N]", tensions, false, opt));
  if (!depths.empty())
    scripts.emplace_back("depths", time_figure(model, "depths", "depth of every body and junction", "depth [m]", depths,
                                               true, opt));
  std::string error;
  const std::size_t blocks = write_last_shapes(root / "nodes.csv", ts.at(ts.rows.size() - 1, "time"),
                                               plots / "network_shapes.dat", error);
  if (blocks == 0) {
    log << "towsim plot: skipped the network's shapes (" << error << ")\n";
  } else {
    scripts.emplace_back("network_shape_xz", shape_figure(model, lines, blocks, false, opt));
    scripts.emplace_back("network_shape_xy", shape_figure(model, lines, blocks, true, opt));
  }
  return plot_render::render_scripts(plots, scripts, prog, log);
}

}  // namespace towsim::cli
