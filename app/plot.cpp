#include "plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "plot_network.hpp"
#include "plot_render.hpp"
#include "run_files.hpp"

extern char** environ;

namespace towsim::cli {

namespace {

namespace fs = std::filesystem;

using plot_render::kGnuplotFailed;
using plot_render::kInvalid;
using plot_render::kOk;
using plot_render::quote;
using plot_render::render;
using plot_render::render_scripts;
using plot_render::usable_gnuplot;

// ---------------------------------------------------------------- reading

/// The whole file's text ("" when it cannot be read).
std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// True when the file's last byte is not a newline: its last row was cut off.
bool ends_cut(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() <= 0) return false;
  in.seekg(-1, std::ios::end);
  return in.get() != '\n';
}

// --------------------------------------------------------------- gnuplot

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.12g", v == 0 ? 0.0 : v);
  return b;
}

/// Run `prog args...` with stdout and stderr appended to `log_path`
/// ("" = /dev/null). Returns the exit status, or -1 with `err` = errno when
/// the program could not be started.
int spawn(const std::string& prog, const std::vector<std::string>& args, const std::string& log_path, int& err) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  const std::string out = log_path.empty() ? "/dev/null" : log_path;
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<std::string> all{prog};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, prog.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    err = rc;
    return -1;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      err = errno;
      return -1;
    }
  }
  if (WIFEXITED(status)) {
    // posix_spawnp may start a child that fails to exec with status 127.
    if (WEXITSTATUS(status) == 127) {
      err = ENOENT;
      return -1;
    }
    return WEXITSTATUS(status);
  }
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::string gnuplot_program() {
  const char* env = std::getenv("TOWSIM_GNUPLOT");
  return env != nullptr && *env != '\0' ? env : "gnuplot";
}

// ------------------------------------------------------------- the plan

/// What plot_run knows about the run.
struct Run {
  std::string model;
  std::string status = "ok";
  bool has_body = false;
  bool three_d = false;
  bool has_nodes = true;
  bool link_at_origin = true;       // body origin == cable lower end
  bool second_sphere = false;       // plot the second sphere's centre
  std::array<double, 3> sphere2{};  // its centre, body axes
  double t0 = 0, t1 = 0;
  double t_last = 0;  // the last row's time [s]
  long rows = 0;      // timeseries rows
  double min_dt = 0;  // smallest output interval
  std::vector<double> snapshot_times;
  bool single = false;                  // one output time: a statics configuration
  bool has_layback = false;             // timeseries.csv has the layback column
  bool has_winch = false;               // timeseries.csv has payout_speed (a winch)
  bool has_rating = false;              // and winch_load_ratio (a winch rating)
  double payout_lo = 0, payout_hi = 0;  // range of payout_speed [m/s]
  bool has_spectra = false;             // spectra.csv (a sea-state run) with data rows
  bool spectra_body = false;            // ... with the body's columns filled
  double spectra_wmax = 0;              // highest omega where the wave spectrum is >= 1e-4 of its peak [rad/s]
  bool cut_series = false;              // timeseries.csv ends in a row cut off (no newline): plots/ gets its whole rows
  double marker_every = 10;             // s between trajectory markers
  int marker_rows = 1;                  // the same in rows
  // Data spans for the equal-scale decisions.
  double x_span = 0, y_span = 0, z_span = 0;
  double x_lo = 0, y_lo = 0, z_lo = 0;  // their lower ends
  // Phase boundaries from summary.json `phases`: time [s] and label (the
  // phases starting there; "NAME end" for those ending there).
  std::vector<std::pair<double, std::string>> marks;
};

/// A "nice" interval (1, 2, 5 x 10^k) close to `v`.
double nice(double v) {
  if (!(v > 0)) return 1;
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  const double m = v / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b"};

/// Colour k of n along a dark-blue -> yellow ramp (viridis-like).
std::string ramp(int k, int n) {
  static const double stops[][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {220, 200, 30}};
  const double s = n <= 1 ? 0 : 4.0 * k / (n - 1);
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  char b[8];
  std::snprintf(b, sizeof b, "#%02x%02x%02x", static_cast<int>(stops[i][0] + f * (stops[i + 1][0] - stops[i][0])),
                static_cast<int>(stops[i][1] + f * (stops[i + 1][1] - stops[i][1])),
                static_cast<int>(stops[i][2] + f * (stops[i + 1][2] - stops[i][2])));
  return b;
}

/// Width of one character of a tick label in pixels, for a font of `font`
/// points (pngcairo at 96 dpi: 4/3 px per point; DejaVu Sans digits advance
/// 0.6 em: 10.4 px at 13 points, as measured on the figures).
double char_px(int font) { return 0.6 * font * 4.0 / 3.0; }

/// The figures' font size in points for a canvas `width` pixels wide.
int font_points(int width) { return std::max(9, static_cast<int>(std::lround(width / 80.0))); }

/// Script text common to every figure.
std::string preamble(const Run& run, const std::string& name, const std::string& what) {
  std::ostringstream s;
  s << "# " << name << ".gp: " << what << " (" << run.model << ").\n"
    << "# Written by `towsim plot`; re-render from this directory with: gnuplot " << name << ".gp\n"
    << "# Data: the run's CSV files in the parent directory, read by column name.\n"
    << plot_render::style()
    << (run.cut_series ? "ts = 'timeseries.csv'  # the whole rows of ../timeseries.csv (its last one cut off)\n"
                       : "ts = '../timeseries.csv'\n")
    << "# Node data: cable_shapes.dat and tension_map.dat beside this script, extracted\n"
    << "# from ../nodes.csv in one pass by `towsim plot` (gnuplot never reads nodes.csv).\n";
  return s.str();
}

std::string title(const Run& run, const std::string& what) {
  return "set title " + quote(run.model + ": " + what) + "\n";
}

/// The characters of the longest tick label ("%g") of step `step` over [lo, lo + span].
std::size_t tick_label_chars(double lo, double span, double step) {
  std::size_t chars = 1;
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor((lo + span) / step + 1e-9);
  for (double k = k0; k <= k1 && k - k0 < 1000; ++k) {
    char b[40];
    const double v = k * step;
    std::snprintf(b, sizeof b, "%g", std::abs(v) < 1e-12 * step ? 0.0 : v);
    chars = std::max(chars, std::strlen(b));
  }
  return chars;
}

}  // namespace

AxisTicks axis_ticks(double lo, double span, double pixels, int font, bool horizontal) {
  if (!(span > 0) || !(pixels > 0)) return {};
  // From about 10 intervals over the span up: the first 1-2-5 step with two
  // labels or more whose labels, side by side (horizontal) or stacked
  // (vertical), have room between them: horizontal, a gap of two characters or
  // a third of the longest label; vertical, one line. Horizontal labels that
  // do not fit twice are turned upright (then one line apart).
  const double p = std::pow(10.0, std::floor(std::log10(span / 10)));
  const double line = font * 4.0 / 3.0;
  for (int turn = 0; turn < 2; ++turn)
    for (int k = 0; k < 30; ++k) {
      const double step = std::array<double, 3>{1, 2, 5}[static_cast<std::size_t>(k % 3)] * p * std::pow(10.0, k / 3);
      if (step < span / 10 * (1 - 1e-9)) continue;
      const double labels = std::floor((lo + span) / step + 1e-9) - std::ceil(lo / step - 1e-9) + 1;
      if (labels < 2) break;
      const double gap = pixels * step / span;  // pixels from one tick to the next
      const auto chars = static_cast<double>(tick_label_chars(lo, span, step));
      const double need = horizontal && turn == 0 ? (chars + std::max(2.0, chars / 3)) * char_px(font) : 2.0 * line;
      if (gap >= need) return {step, turn == 1};
    }
  return {span, false};
}

namespace {

/// Equal axis scale when the data's aspect allows a readable figure (then a
/// wide figure gets its legend below and a lower canvas, `o.height`), with the
/// tick steps chosen so that the tick labels do not overlap on the plot box
/// this scale gives (its size estimated from the canvas, the margins and the
/// legend of `key_chars` characters); returns the title suffix.
std::string equal_scale(std::ostringstream& s, double hlo, double hspan, double vlo, double vspan, PlotOptions& o,
                        int key_chars) {
  const double a = (vspan > 0 ? vspan : 1e-3) / std::max(hspan, 1e-9);
  if (hspan > 0 && vspan > 0 && (a < 1.0 / 12 || a > 4)) return " (axes NOT to the same scale)";
  s << "set size ratio -1\nset autoscale fix\nset offsets graph 0.03, graph 0.03, graph 0.06, graph 0.06\n";
  bool wide = false;
  if (a < 0.6) {  // wide: legend below, canvas about as high as the plot needs
    s << "set key below horizontal noreverse Right width 0\n";
    const double plot_w = o.width - 130.0;
    const int h = static_cast<int>(std::lround(plot_w * std::max(a, 0.05) * 1.15 + 190));
    o.height = std::clamp(h, static_cast<int>(0.45 * o.width), o.height);
    wide = true;
  }
  if (!(hspan > 0) || !(vspan > 0)) return " (equal scales)";
  // The plot box: the drawn ranges (the data and the offsets above) at one
  // scale, in the canvas less the margins: title, x tick labels and x label
  // (about 7 lines) or with the legend below 3 more; the y label and tick
  // labels on the left; the legend on the right unless below.
  const int font = font_points(o.width);
  const double line = font * 4.0 / 3.0, ch = char_px(font);
  const double hr = 1.06 * hspan, vr = 1.12 * vspan, hlo_d = hlo - 0.03 * hspan, vlo_d = vlo - 0.06 * vspan;
  const double box_h = o.height - (wide ? 10.0 : 7.0) * line;
  const double v_step0 = axis_ticks(vlo_d, vr, box_h, font, false).step;
  const double left = (static_cast<double>(tick_label_chars(vlo_d, vr, v_step0)) + 3.5) * ch;
  const double box_w = o.width - left - (wide ? 2.0 * ch : (key_chars + 7.0) * ch);
  const double w = std::min(box_w, box_h * hr / vr), h = w * vr / hr;
  const AxisTicks xt = axis_ticks(hlo_d, hr, w, font, true);
  s << "# Tick steps for a plot box of about " << std::lround(w) << " x " << std::lround(h)
    << " pixels: the tick labels do not overlap.\n"
    << "set xtics " << num(xt.step) << (xt.rotate ? " rotate by 90 right" : "") << "\nset ytics "
    << num(axis_ticks(vlo_d, vr, h, font, false).step) << "\n";
  return " (equal scales)";
}

/// The second sphere's centre from the body origin and angles (R = Rz Ry Rx).
std::string sphere2_functions(const Run& run) {
  std::ostringstream s;
  s << "# Centre of the body's second sphere, c = (" << num(run.sphere2[0]) << ", " << num(run.sphere2[1]) << ", "
    << num(run.sphere2[2]) << ") m in body axes:\n"
    << "# O_t + R c with R = Rz(yaw) Ry(pitch) Rx(roll) (angles in degrees in the CSV).\n"
    << "d2r = pi/180\n"
    << "cx = " << num(run.sphere2[0]) << "; cy = " << num(run.sphere2[1]) << "; cz = " << num(run.sphere2[2]) << "\n"
    << "s2x(x,r,p,y) = x + cos(y*d2r)*cos(p*d2r)*cx"
       " + (cos(y*d2r)*sin(p*d2r)*sin(r*d2r) - sin(y*d2r)*cos(r*d2r))*cy"
       " + (cos(y*d2r)*sin(p*d2r)*cos(r*d2r) + sin(y*d2r)*sin(r*d2r))*cz\n"
    << "s2y(v,r,p,y) = v + sin(y*d2r)*cos(p*d2r)*cx"
       " + (sin(y*d2r)*sin(p*d2r)*sin(r*d2r) + cos(y*d2r)*cos(r*d2r))*cy"
       " + (sin(y*d2r)*sin(p*d2r)*cos(r*d2r) - cos(y*d2r)*sin(r*d2r))*cz\n"
    << "s2z(z,r,p,y) = z - sin(p*d2r)*cx + cos(p*d2r)*sin(r*d2r)*cy + cos(p*d2r)*cos(r*d2r)*cz\n"
    << "ang = \"column('body_roll_deg'), column('body_pitch_deg'), column('body_yaw_deg')\"\n";
  return s.str();
}

std::string markers_note(const Run& run) { return "markers every " + num(run.marker_every) + " s"; }

/// The phase boundaries on a time axis: a dashed vertical line at each, labelled
/// along it at the top. `splot`: for a map view (3-D coordinates).
std::string phase_marks(const Run& run, bool splot = false) {
  if (run.marks.empty()) return "";
  std::ostringstream s;
  s << "# Phase boundaries (summary.json phases): a dashed line at each, labelled with the phases\n"
    << "# starting there (\"NAME end\": ending there).\n";
  if (!splot) s << "set style textbox opaque noborder margins 0.5, 0.5\n";  // labels legible over the curves
  int k = 0;
  for (const auto& [t, label] : run.marks) {
    ++k;
    const std::string T = num(t);
    if (splot)
      s << "set arrow " << k << " from first " << T << ", graph 0, graph 1 to first " << T
        << ", graph 1, graph 1 nohead dt 2 lw 1 lc rgb '#ffffff' front\n";
    else
      s << "set arrow " << k << " from " << T << ", graph 0 to " << T
        << ", graph 1 nohead dt 2 lw 1 lc rgb '#7f7f7f' back\n";
    s << "set label " << k << " " << quote(label) << " at "
      << (splot ? "first " + T + ", graph 0.98, graph 1" : T + ", graph 0.98")
      << " rotate by 90 right offset char 0.9, 0 font ',9' tc rgb " << (splot ? "'#ffffff'" : "'#505050' boxed")
      << " front\n";
  }
  return s.str();
}

// One function per figure: returns the script text.

std::string fig_trajectories(const Run& run, const PlotOptions& opt) {
  const std::string name = "trajectories_xz";
  std::ostringstream s;
  s << preamble(run, name, "trajectories in the vertical x-z plane");
  PlotOptions o = opt;
  const std::string scale = equal_scale(s, run.x_lo, run.x_span, run.z_lo, run.z_span, o,
                                        run.has_body && run.link_at_origin ? 35 : 20);
  s << title(run, "trajectories in the x-z plane" + scale);
  s << "set xlabel 'x (m)'\nset ylabel 'z (m), up; surface z = 0'\n";
  if (run.second_sphere) s << sphere2_functions(run);
  const std::string every = " every " + std::to_string(run.marker_rows);
  std::ostringstream p;
  p << "plot ts using 'tow_x':'tow_z' with lines lw 2 lc rgb '" << kPalette[0] << "' title 'tow point O_r', \\\n"
    << "  ts using 'tow_x':'tow_z'" << every << " with points pt 7 ps 0.6 lc rgb '" << kPalette[0] << "' notitle, \\\n"
    << "  ts using 'end_x':'end_z' with lines lw 2 lc rgb '" << kPalette[1] << "' title "
    << quote(run.has_body && run.link_at_origin ? "cable lower end P_n (= body origin)" : "cable lower end P_n")
    << ", \\\n"
    << "  ts using 'end_x':'end_z'" << every << " with points pt 7 ps 0.6 lc rgb '" << kPalette[1] << "' notitle";
  if (run.has_body && !run.link_at_origin) {
    p << ", \\\n  ts using 'body_x':'body_z' with lines lw 1.5 dt 2 lc rgb '" << kPalette[3]
      << "' title 'body origin O_t', \\\n"
      << "  ts using 'body_x':'body_z'" << every << " with points pt 6 ps 0.6 lc rgb '" << kPalette[3] << "' notitle";
  }
  if (run.second_sphere) {
    p << ", \\\n  ts using (s2x(column('body_x'), @ang)):(s2z(column('body_z'), @ang)) with lines lw 2 lc rgb '"
      << kPalette[2] << "' title 'second sphere centre', \\\n"
      << "  ts using (s2x(column('body_x'), @ang)):(s2z(column('body_z'), @ang))" << every
      << " with points pt 7 ps 0.6 lc rgb '" << kPalette[2] << "' notitle";
  }
  p << ", \\\n  NaN with points pt 7 ps 0.6 lc rgb '#606060' title " << quote(markers_note(run));
  s << render(name, p.str(), o);
  return s.str();
}

std::string fig_components(const Run& run, const PlotOptions& o, const std::string& name, const std::string& what,
                           const std::string& prefix, const std::string& magnitude, const std::string& symbol) {
  std::ostringstream s;
  s << preamble(run, name, what);
  s << title(run, what);
  s << "set xlabel 'time (s)'\nset ylabel 'force (N)'\n"
    << "set xrange [" << num(run.t0) << ":" << num(run.t1) << "]\n"
    << phase_marks(run);
  std::ostringstream p;
  p << "plot ts using 'time':'" << prefix << "x' with lines lw 1.5 lc rgb '" << kPalette[0] << "' title '" << symbol
    << "x', \\\n";
  if (run.three_d)
    p << "  ts using 'time':'" << prefix << "y' with lines lw 1.5 lc rgb '" << kPalette[2] << "' title '" << symbol
      << "y', \\\n";
  p << "  ts using 'time':'" << prefix << "z' with lines lw 1.5 lc rgb '" << kPalette[1] << "' title '" << symbol
    << "z', \\\n";
  if (!magnitude.empty())
    p << "  ts using 'time':'" << magnitude << "'";
  else
    p << "  ts using 'time':(sqrt(column('" << prefix << "x')**2 + column('" << prefix << "y')**2 + column('" << prefix
      << "z')**2))";
  p << " with lines lw 1 dt 2 lc rgb '#404040' title '|" << symbol << "|'";
  s << render(name, p.str(), o);
  return s.str();
}

std::string fig_paths(const Run& run, const PlotOptions& opt) {
  const std::string name = "paths_xy";
  std::ostringstream s;
  s << preamble(run, name, "horizontal paths of the cable ends");
  PlotOptions o = opt;
  const std::string scale = equal_scale(s, run.x_lo, run.x_span, run.y_lo, run.y_span, o, 20);
  s << title(run, "horizontal paths of the cable ends" + scale);
  s << "set xlabel 'x (m)'\nset ylabel 'y (m)'\n";
  if (run.second_sphere) s << sphere2_functions(run);
  const std::string every = " every " + std::to_string(run.marker_rows);
  std::ostringstream p;
  p << "plot ts using 'tow_x':'tow_y' with lines lw 1.5 lc rgb '" << kPalette[0] << "' title 'tow point O_r', \\\n"
    << "  ts using 'tow_x':'tow_y'" << every << " with points pt 7 ps 0.6 lc rgb '" << kPalette[0] << "' notitle, \\\n"
    << "  ts using 'end_x':'end_y' with lines lw 2 lc rgb '" << kPalette[1] << "' title 'cable lower end P_n', \\\n"
    << "  ts using 'end_x':'end_y'" << every << " with points pt 7 ps 0.6 lc rgb '" << kPalette[1] << "' notitle";
  if (run.second_sphere)
    p << ", \\\n  ts using (s2x(column('body_x'), @ang)):(s2y(column('body_y'), @ang)) with lines lw 1.5 lc rgb '"
      << kPalette[2] << "' title 'second sphere centre'";
  p << ", \\\n  ts every ::0::0 using 'tow_x':'tow_y' with points pt 4 ps 1.5 lc rgb '#000000' title 'start', \\\n"
    << "  NaN with points pt 7 ps 0.6 lc rgb '#606060' title " << quote(markers_note(run));
  s << render(name, p.str(), o);
  return s.str();
}

std::string fig_depth(const Run& run, const PlotOptions& o) {
  const std::string name = "end_depth";
  std::ostringstream s;
  s << preamble(run, name, "depth of the cable's lower end");
  s << title(run, "depth of the cable's lower end");
  s << "set xlabel 'time (s)'\nset ylabel 'depth -z (m), downwards'\nset yrange [*:*] reverse\n"
    << "set xrange [" << num(run.t0) << ":" << num(run.t1) << "]\n"
    << phase_marks(run);
  std::ostringstream p;
  p << "plot ts using 'time':(-column('end_z')) with lines lw 2 lc rgb '" << kPalette[1]
    << "' title 'cable lower end P_n'";
  if (run.has_body && !run.link_at_origin)
    p << ", \\\n  ts using 'time':(-column('body_z')) with lines lw 1.5 dt 2 lc rgb '" << kPalette[3]
      << "' title 'body origin O_t'";
  s << render(name, p.str(), o);
  return s.str();
}

/// Script text that renders a multiplot body `plot_cmds` as PNG and SVG (replot
/// does not repeat a multiplot: the commands are written once per terminal).
std::string render_multi(const std::string& name, const std::string& plot_cmds, const PlotOptions& o);

std::string fig_winch(const Run& run, const PlotOptions& o) {
  const std::string name = "winch";
  std::ostringstream s;
  s << preamble(run, name, "deployed length, pay-out speed and winch load");
  // The pay-out speed on its own right-hand axis, over its own range (0 in it)
  // with a tenth of it free above and below.
  const double lo = std::min(run.payout_lo, 0.0), hi = std::max(run.payout_hi, 0.0);
  const double pad = hi - lo > 1e-9 ? 0.1 * (hi - lo) : 0.1;
  std::ostringstream p;
  p << "set multiplot layout " << (run.has_rating ? 2 : 1) << ",1 title " << quote(run.model + ": winch") << "\n"
    << "set key top horizontal outside center samplen 2\n"
    << "set lmargin 10\nset rmargin 10  # the same plot width in both panels\n"
    << "set xlabel 'time (s)'\nset xrange [" << num(run.t0) << ":" << num(run.t1) << "]\n"
    << phase_marks(run) << "set title 'deployed length (left axis) and pay-out speed (right axis)'\n"
    << "set ylabel 'deployed length (m)'\nset y2label 'pay-out speed (m/s)'\n"
    << "set y2range [" << num(lo - pad) << ":" << num(hi + pad) << "]\nset y2tics\nset ytics nomirror\n"
    << "plot ts using 'time':'deployed_length' with lines lw 2 lc rgb '" << kPalette[0]
    << "' title 'deployed length', \\\n  ts using 'time':'payout_speed' axes x1y2 with lines lw 1.5 lc rgb '"
    << kPalette[1] << "' title 'pay-out speed (< 0: hauling in)'\n";
  if (run.has_rating)
    p << "unset y2tics\nunset y2label\nset ytics mirror\n"
      << "unset key\nset title 'winch load: tow tension / winch rating'\nset ylabel 'tow tension / rating (%)'\n"
      << "set yrange [0:*]\n"
      << "plot ts using 'time':(100*column('winch_load_ratio')) with lines lw 1.5 lc rgb '" << kPalette[2]
      << "' title 'tow tension / winch rating (%)'\n";
  p << "unset multiplot";
  s << render_multi(name, p.str(), o);
  return s.str();
}

std::string fig_angles(const Run& run, const PlotOptions& o) {
  const std::string name = "body_angles";
  std::ostringstream s;
  s << preamble(run, name, "body roll, pitch and yaw");
  s << title(run, "body attitude (angles drawn continuous, see body_angles.gp)");
  s << "set xlabel 'time (s)'\nset ylabel 'angle (deg)'\n"
    << "set xrange [" << num(run.t0) << ":" << num(run.t1) << "]\n"
    << phase_marks(run) << "# The CSV gives roll, yaw in (-180, 180] and pitch in [-90, 90]. So that the curves\n"
    << "# do not jump, each row's triple is replaced by the equivalent one closest to\n"
    << "# the previous row's: (roll + 360 i, pitch + 360 j, yaw + 360 k) or the same\n"
    << "# rotation as (roll + 180, 180 - pitch, yaw + 180) (pitch past +-90 deg).\n"
    << "wrap(a) = a - 360.0*floor((a + 180.0)/360.0)\n"
    << "near(a, ref) = ref + wrap(a - ref)\n"
    << "cr = 0; cp = 0; cy = 0\n"
    << "cont(i, r, p, y) = (i == 0 ? (cr = r, cp = p, cy = y) : \\\n"
    << "  (ar = near(r, cr), ap = near(p, cp), ay = near(y, cy), \\\n"
    << "   br = near(r + 180, cr), bp = near(180 - p, cp), by = near(y + 180, cy), \\\n"
    << "   da = abs(ar - cr) + abs(ap - cp) + abs(ay - cy), db = abs(br - cr) + abs(bp - cp) + abs(by - cy), \\\n"
    << "   cr = (da <= db ? ar : br), cp = (da <= db ? ap : bp), cy = (da <= db ? ay : by)), 0)\n"
    << "upd = \"cont(column(0), column('body_roll_deg'), column('body_pitch_deg'), column('body_yaw_deg'))\"\n";
  std::ostringstream p;
  p << "plot ts using (@upd, column('time')):(cr) with lines lw 1.5 lc rgb '" << kPalette[0] << "' title 'roll', \\\n"
    << "  ts using (@upd, column('time')):(cp) with lines lw 1.5 lc rgb '" << kPalette[1]
    << "' title 'pitch (+ = nose down)', \\\n"
    << "  ts using (@upd, column('time')):(cy) with lines lw 1.5 lc rgb '" << kPalette[2] << "' title 'yaw'";
  s << render(name, p.str(), o);
  return s.str();
}

std::string fig_shapes(const Run& run, const PlotOptions& opt, bool plan) {
  const std::string name = plan ? "cable_shapes_xy" : "cable_shapes_xz";
  const std::string v = plan ? "y" : "z";
  std::ostringstream s;
  s << preamble(run, name, plan ? "cable shapes, plan view" : "cable shapes, side view");
  // Shapes span less than the trajectories; scale them on the nodes' spans.
  PlotOptions o = opt;
  const std::string scale = equal_scale(s, run.x_lo, run.x_span, plan ? run.y_lo : run.z_lo,
                                        plan ? run.y_span : run.z_span, o, 10);
  s << title(run, std::string(plan ? "cable shapes, plan view (x-y)" : "cable shapes, side view (x-z)") + scale);
  s << "set xlabel 'x (m)'\nset ylabel " << (plan ? "'y (m)'" : "'z (m), up; surface z = 0'") << "\n"
    << "set key title 'time'\n"
    << "# cable_shapes.dat: one block (index k) per snapshot, columns time, node, x, y, z, tension.\n"
    << "shapes = 'cable_shapes.dat'\n";
  std::ostringstream p;
  p << "plot ";
  const int n = static_cast<int>(run.snapshot_times.size());
  for (int k = 0; k < n; ++k) {
    const std::string T = num(run.snapshot_times[static_cast<std::size_t>(k)]);
    if (k > 0) p << ", \\\n  ";
    p << "shapes index " << k << " using 3:" << (plan ? 4 : 5) << " with linespoints lw 2 pt 7 ps 0.5 lc rgb '"
      << ramp(k, n) << "' title '" << T << " s'";
  }
  if (n == 0) p << "NaN notitle";
  if (plan)  // where the tow point went, for reference
    p << ", \\\n  ts using 'tow_x':'tow_y' with lines lw 1 dt 3 lc rgb '#909090' title 'tow path'";
  s << render(name, p.str(), o);
  return s.str();
}

std::string fig_depth_layback(const Run& run, const PlotOptions& o) {
  const std::string name = "depth_layback";
  const std::string who = run.has_body ? "body origin O_t" : "cable lower end P_n";
  const std::string p = run.has_body ? "body_" : "end_";
  std::ostringstream s;
  s << preamble(run, name, "depth of the " + who + " against layback");
  s << title(run, "depth against layback of the " + who);
  s << "set xlabel 'layback: horizontal distance from the tow point (m)'\n"
    << "set ylabel 'depth -z (m), downwards'\nset yrange [*:*] reverse\n";
  if (run.has_layback)
    s << "lay(dummy) = column('layback')\n";
  else
    s << "lay(dummy) = sqrt((column('" << p << "x') - column('tow_x'))**2 + (column('" << p
      << "y') - column('tow_y'))**2)\n";
  std::ostringstream q;
  q << "plot ts using (lay(0)):(-column('" << p << "z')) with lines lw 2 lc rgb '" << kPalette[run.has_body ? 3 : 1]
    << "' title " << quote(who) << ", \\\n"
    << "  ts every ::0::0 using (lay(0)):(-column('" << p << "z')) with points pt 4 ps 1.5 lc rgb '#000000' title "
    << quote("start, t = " + num(run.t0) + " s") << ", \\\n"
    << "  ts using (lay(0)):(-column('" << p << "z')) every ::" << std::max<long>(0, run.rows - 1)
    << " with points pt 7 ps 1.5 lc rgb '#000000' title " << quote("end, t = " + num(run.t_last) + " s");
  s << render(name, q.str(), o);
  return s.str();
}

std::string fig_tension_map(const Run& run, const PlotOptions& o) {
  const std::string name = "tension_map";
  std::ostringstream s;
  s << preamble(run, name, "tension along the cable against time");
  s << title(run, "tension along the cable against time");
  s << "# tension_map.dat: one block per output time (at most 200, evenly spread), columns time,\n"
    << "# distance along the cable from the tow point (m), tension (N).\n"
    << "unset datafile columnheaders\n"
    << "set view map\nset pm3d map corners2color c1\nunset key\nunset grid\n"
    << "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 '#fde725')\n"
    << "set xlabel 'time (s)'\nset ylabel 'distance along the cable from the tow point (m)'\n"
    << "set cblabel 'tension (N)'\nset autoscale fix\nset yrange [*:*] reverse\n"
    << "set xrange [" << num(run.t0) << ":" << num(run.t1) << "]\n"
    << phase_marks(run, true);
  s << render(name, "splot 'tension_map.dat' using 1:2:3 with pm3d notitle", o);
  return s.str();
}

std::string fig_tension_along(const Run& run, const PlotOptions& o) {
  const std::string name = "tension_along_cable";
  std::ostringstream s;
  s << preamble(run, name, "tension along the cable");
  s << title(run, "tension along the cable" + (run.single ? std::string() : " (snapshots)"));
  s << "unset datafile columnheaders\n"
    << "set xlabel 'distance along the cable from the tow point (m)'\nset ylabel 'tension (N)'\n"
    << "set key title 'time'\n";
  std::ostringstream p;
  p << "plot ";
  const int n = static_cast<int>(run.snapshot_times.size());
  for (int k = 0; k < n; ++k) {
    if (k > 0) p << ", \\\n  ";
    p << "'cable_shapes.dat' index " << k << " using 7:6 with linespoints lw 2 pt 7 ps 0.5 lc rgb '" << ramp(k, n)
      << "' title '" << num(run.snapshot_times[static_cast<std::size_t>(k)]) << " s'";
  }
  if (n == 0) p << "NaN notitle";
  s << render(name, p.str(), o);
  return s.str();
}

/// Script text that renders a multiplot body `plot_cmds` as PNG and SVG (replot
/// does not repeat a multiplot: the commands are written once per terminal).
std::string render_multi(const std::string& name, const std::string& plot_cmds, const PlotOptions& o) {
  std::ostringstream s;
  const int font = font_points(o.width);
  s << "set terminal pngcairo size " << o.width << "," << o.height << " noenhanced font 'Sans," << font
    << "' linewidth 1.5\n"
    << "set output '" << name << ".png'\n"
    << plot_cmds << "\n"
    << "set terminal svg size " << o.width << "," << o.height << " noenhanced font 'Sans," << font
    << "' linewidth 1.5 background '#ffffff'\n"
    << "set output '" << name << ".svg'\n"
    << plot_cmds << "\n"
    << "unset output\n";
  return s.str();
}

std::string fig_spectra(const Run& run, const PlotOptions& o) {
  const std::string name = "spectra";
  std::ostringstream s;
  s << preamble(run, name, "spectra of the sea state's responses and the ship -> fish transfer function");
  s << "sp = '../spectra.csv'\n"
    << "# Blank cells (no body, or a gain where the input has < 1e-3 of its peak energy) are missing data.\n"
    << "set datafile missing ''\n";
  std::ostringstream p;
  p << "set multiplot layout 2,1 title " << quote(run.model + ": spectra (encounter frequencies)") << "\n"
    << "set key inside top right reverse Left box opaque samplen 2\n";
  if (run.spectra_wmax > 0)  // where the sea has energy (wave spectrum >= 1e-4 of its peak)
    p << "set xrange [0:" << num(nice(1.2 * run.spectra_wmax)) << "]\n";
  p << "set title 'one-sided spectral densities'\n"
    << "set xlabel 'omega (rad/s)'\nset ylabel 'S (m^2 s/rad)'\nset logscale y\nset format y '%.0e'\n"
    << "set y2label 'S tension (N^2 s/rad)'\nset logscale y2\nset format y2 '%.0e'\nset y2tics\nset ytics nomirror\n"
    << "plot sp using 'omega':'wave_elevation' with lines lw 2 lc rgb '" << kPalette[0]
    << "' title 'wave elevation', \\\n"
    << "  sp using 'omega':'tow_heave' with lines lw 1.5 lc rgb '" << kPalette[2] << "' title 'tow point heave'";
  if (run.spectra_body)
    p << ", \\\n  sp using 'omega':'body_depth' with lines lw 2 lc rgb '" << kPalette[3] << "' title 'body heave'";
  p << ", \\\n  sp using 'omega':'tow_tension' axes x1y2 with lines lw 1.5 dt 2 lc rgb '" << kPalette[1]
    << "' title 'tow tension (right axis)'\n"
    << "unset logscale y2\nunset y2tics\nunset y2label\nset ytics mirror\nunset logscale y\nset format y '%g'\n"
    << "set title 'transfer functions (sqrt of spectral ratios)'\nset ylabel 'gain (m/m)'\n";
  if (run.spectra_body)
    p << "plot sp using 'omega':'body_heave_per_tow_heave' with linespoints lw 2 pt 7 ps 0.5 lc rgb '" << kPalette[3]
      << "' title 'ship -> fish: body heave per tow point heave', \\\n"
      << "  sp using 'omega':'body_heave_per_wave' with linespoints lw 1.5 pt 6 ps 0.5 lc rgb '" << kPalette[0]
      << "' title 'body heave per metre of wave'\n";
  else
    p << "set label 1 'no body: no transfer function' at graph 0.5, graph 0.5 center\nplot NaN notitle\n";
  p << "unset multiplot";
  s << render_multi(name, p.str(), o);
  return s.str();
}

/// Write the node data the figures read (cable_shapes.dat, tension_map.dat)
/// from ONE pass over nodes.csv. False with `error` set on failure.
bool write_node_data(const fs::path& root, const fs::path& plots, const Run& run, const std::vector<double>& times,
                     std::string& error) {
  // Wanted: the snapshots and up to 200 heat-map columns.
  std::vector<double> map_times;
  for (std::size_t i : spread_indices(times.size(), 200)) map_times.push_back(times[i]);
  std::vector<double> wanted = map_times;
  wanted.insert(wanted.end(), run.snapshot_times.begin(), run.snapshot_times.end());
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  std::vector<NodeFrame> frames;
  if (!read_node_frames((root / "nodes.csv").string(), wanted, frames, error)) return false;
  auto find = [&frames](double t) -> const NodeFrame* {
    for (const auto& f : frames)
      if (std::abs(f.t - t) <= 1e-9 * std::max(1.0, std::abs(t))) return &f;
    return nullptr;
  };
  std::ofstream sh(plots / "cable_shapes.dat", std::ios::trunc);
  sh << "# towsim plot: the cable at the snapshot times, one block per time (gnuplot index k)\n"
     << "# time,node,x,y,z,tension,distance_along_cable\n";
  for (double t : run.snapshot_times) {
    const NodeFrame* f = find(t);
    if (f != nullptr) {
      const auto arc = arc_lengths(*f);
      for (std::size_t k = 0; k < f->x.size(); ++k)
        sh << num(f->t) << ',' << k << ',' << num(f->x[k]) << ',' << num(f->y[k]) << ',' << num(f->z[k]) << ','
           << num(f->tension[k]) << ',' << num(arc[k]) << '\n';
    }
    sh << "\n\n";
  }
  std::ofstream tm(plots / "tension_map.dat", std::ios::trunc);
  tm << "# towsim plot: tension along the cable, one block per output time\n"
     << "# time,distance_along_cable,tension\n";
  for (double t : map_times) {
    const NodeFrame* f = find(t);
    if (f == nullptr) continue;
    const auto arc = arc_lengths(*f);
    for (std::size_t k : spread_indices(f->x.size(), 100))
      tm << num(f->t) << ',' << num(arc[k]) << ',' << num(f->tension[k]) << '\n';
    tm << '\n';
  }
  if (!sh || !tm) {
    error = "cannot write the node data in " + plots.string();
    return false;
  }
  return true;
}

bool exists_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string join(const std::vector<std::string>& v, const std::string& sep, const std::string& last) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out += (i + 1 == v.size() ? last : sep);
    out += v[i];
  }
  return out;
}

/// A sweep's towing table (DIR/towing_table.csv of `towsim sweep`): depth
/// against layback, one point per case labelled with its case number and tow
/// speed, into DIR/plots/towing_table.png and .svg.
int plot_towing_table(const fs::path& root, std::ostream& log, const PlotOptions& o) {
  const fs::path csv = root / "towing_table.csv";
  CsvTable t;
  std::string error;
  if (!read_csv_table(csv.string(), t, error) || !t.has("layback") || !t.has("depth") || !t.has("tow_speed_kn") ||
      !t.has("case")) {
    log << "towsim plot: " << csv.string() << ": cannot read it, or no column case, layback, depth or tow_speed_kn\n";
    return kInvalid;
  }
  long drawn = 0;
  double lmax = 0, dmax = 0;  // largest layback and depth [m]
  for (std::size_t r = 0; r < t.rows.size(); ++r)
    if (std::isfinite(t.at(r, "layback")) && std::isfinite(t.at(r, "depth"))) {
      ++drawn;
      lmax = std::max(lmax, t.at(r, "layback"));
      dmax = std::max(dmax, t.at(r, "depth"));
    }
  if (drawn == 0) {
    log << "towsim plot: " << csv.string() << ": no case with a depth and a layback\n";
    return kInvalid;
  }
  const std::string prog = usable_gnuplot(log);
  if (prog.empty()) return kInvalid;
  const fs::path plots = root / "plots";
  std::error_code ec;
  fs::remove_all(plots, ec);  // towsim's folder: no stale figure
  fs::create_directories(plots, ec);
  if (ec) {
    log << "towsim plot: cannot create " << plots.string() << ": " << ec.message() << "\n";
    return kGnuplotFailed;
  }
  const std::string name = "towing_table";
  std::ostringstream s;
  s << "# " << name << ".gp: depth against layback of each case of a sweep (../towing_table.csv).\n"
    << "# Written by `towsim plot`; re-render from this directory with: gnuplot " << name << ".gp\n"
    << "set datafile separator comma\n"
    << "set datafile columnheaders\n"
    << "set encoding utf8\n"
    << "set style line 100 lt 1 lw 0.6 lc rgb '#d4d4d4'\n"
    << "set grid ls 100\nset border lw 1.2\nset key off\n"
    << "tt = '../towing_table.csv'\n"
    << "set title " << quote("towing table: depth against layback, " + std::to_string(drawn) + " cases") << "\n"
    << "set xlabel 'layback: horizontal distance from the tow point (m)'\n"
    << "set ylabel 'depth of the body (or cable end) (m), downwards'\n"
    << "set xrange [0:" << num(1.12 * lmax + 1) << "]\nset yrange [" << num(1.06 * dmax + 1) << ":0]\n";
  const std::string plot_cmd =
      "plot tt using (column('layback')):(column('depth')) with points pt 7 ps 1.5 lc rgb '" +
      std::string(kPalette[0]) +
      "', \\\n  tt using (column('layback')):(column('depth')):(sprintf('%d: %.3g kn', column('case'), "
      "column('tow_speed_kn'))) with labels offset char 1, char 0.8 left font ',9' tc rgb '#404040'";
  s << render(name, plot_cmd, o);
  return render_scripts(plots, {{name, s.str()}}, prog, log);
}

}  // namespace

std::vector<std::string> plot_names(bool has_body, bool three_d, bool single, bool spectra) {
  if (single) {  // one configuration (towsim statics --out): no time histories
    std::vector<std::string> names{"cable_shapes_xz"};
    if (three_d) names.push_back("cable_shapes_xy");
    names.push_back("tension_along_cable");
    return names;
  }
  std::vector<std::string> names{"trajectories_xz", "tow_force"};
  if (three_d) names.push_back("paths_xy");
  names.push_back("end_depth");
  names.push_back("depth_layback");
  if (has_body) names.push_back("body_angles");
  names.push_back("cable_shapes_xz");
  if (three_d) names.push_back("cable_shapes_xy");
  names.push_back("tension_map");
  if (has_body) names.push_back("link_force");
  if (spectra) names.push_back("spectra");
  return names;
}

int plot_run(const std::string& dir, std::ostream& log) { return plot_run(dir, log, PlotOptions{}); }

int plot_run(const std::string& dir, std::ostream& log, const PlotOptions& opt) {
  const fs::path root(dir);
  const char* kUsage = "expected the output directory of `towsim run --out DIR` or `towsim statics --out DIR`";

  // 1. The run's files.
  std::error_code ec;
  if (!fs::is_directory(root, ec)) {
    log << "towsim plot: " << dir << ": no such directory (" << kUsage
        << ", with timeseries.csv, nodes.csv and summary.json)\n";
    return kInvalid;
  }
  // A sweep's directory (`towsim sweep --out DIR`): its towing table.
  if (!exists_file(root / "timeseries.csv") && exists_file(root / "towing_table.csv"))
    return plot_towing_table(root, log, opt);
  nlohmann::json summary;
  bool summary_ok = false;
  if (exists_file(root / "summary.json")) {
    try {
      std::ifstream in(root / "summary.json");
      summary = nlohmann::json::parse(in);
      summary_ok = summary.is_object();
    } catch (const std::exception& e) {
      log << "towsim plot: " << (root / "summary.json").string() << ": not valid JSON: " << e.what() << "\n";
      return kInvalid;
    }
  }
  Run run;
  if (summary_ok) {  // nodes.csv is optional when the run says it wrote none
    const auto f = summary.find("files");
    if (f != summary.end() && f->is_object() && f->contains("nodes") && (*f)["nodes"].is_null()) run.has_nodes = false;
  }
  std::vector<std::string> missing;
  if (!exists_file(root / "timeseries.csv")) missing.push_back("timeseries.csv");
  if (run.has_nodes && !exists_file(root / "nodes.csv")) missing.push_back("nodes.csv");
  if (!missing.empty()) {
    log << "towsim plot: " << dir << " has no " << join(missing, ", ", " and ") << " (" << kUsage << ")\n";
    return kInvalid;
  }
  if (!summary_ok && exists_file(root / "summary.json")) {
    log << "towsim plot: " << (root / "summary.json").string() << ": not a JSON object\n";
    return kInvalid;
  }
  if (!summary_ok) summary = nlohmann::json::object();  // optional: e.g. an older `towsim statics --out`

  // 2. What the run is.
  run.model = summary.value("model", std::string());
  if (run.model.empty()) run.model = root.filename().string();
  if (run.model.empty()) run.model = "run";
  run.status = summary.value("status", std::string("ok"));
  try {
    const auto sc = summary.find("scenario");
    if (sc != summary.end() && sc->is_object() && sc->contains("body") && (*sc)["body"].is_object()) {
      const auto& body = (*sc)["body"];
      if (body.contains("link_point") && body["link_point"].is_array()) {
        for (const auto& v : body["link_point"])
          if (v.is_number() && v.get<double>() != 0) run.link_at_origin = false;
      }
      if (body.contains("spheres") && body["spheres"].is_array() && body["spheres"].size() >= 2) {
        const auto& c = body["spheres"][1]["center"];
        if (c.is_array() && c.size() == 3) {
          for (int i = 0; i < 3; ++i)
            run.sphere2[static_cast<std::size_t>(i)] = c[static_cast<std::size_t>(i)].get<double>();
          run.second_sphere = true;
        }
      }
    }
  } catch (const std::exception&) {
    // An unusual echo: plot without the body details.
  }

  CsvTable ts;
  std::string read_error;  // the readers' own message (the plot's names the file its way)
  if (!read_csv_table((root / "timeseries.csv").string(), ts, read_error)) {
    log << "towsim plot: " << (root / "timeseries.csv").string() << ": cannot read it or it has no header\n";
    return kInvalid;
  }
  // A network's run (a line column in nodes.csv, no single tow point): its own figures.
  if (!ts.has("tow_x") && is_network_run(root)) return plot_network_run(root, ts, run.model, opt, log);
  run.cut_series = ends_cut(root / "timeseries.csv");
  run.has_body = ts.has("body_x");
  run.has_winch = ts.has("payout_speed");
  run.has_rating = ts.has("winch_load_ratio");
  run.has_layback = ts.has("layback");
  for (std::size_t r = 0; r < ts.rows.size(); ++r) {
    const double v = run.has_winch ? ts.at(r, "payout_speed") : 0.0;
    if (std::isfinite(v)) run.payout_lo = std::min(run.payout_lo, v), run.payout_hi = std::max(run.payout_hi, v);
  }
  std::vector<std::string> need{"time",        "tow_x",       "tow_y", "tow_z", "tow_force_x",
                                "tow_force_y", "tow_force_z", "end_x", "end_y", "end_z"};
  if (run.has_body)
    for (const char* c : {"body_x", "body_y", "body_z", "body_roll_deg", "body_pitch_deg", "body_yaw_deg",
                          "link_force_x", "link_force_y", "link_force_z"})
      need.push_back(c);
  std::vector<std::string> absent;
  for (const auto& c : need)
    if (!ts.has(c)) absent.push_back(c);
  if (!absent.empty()) {
    log << "towsim plot: " << (root / "timeseries.csv").string() << ": no column " << join(absent, ", ", " or ")
        << " in its header\n";
    return kInvalid;
  }
  if (ts.rows.empty()) {
    log << "towsim plot: " << (root / "timeseries.csv").string() << ": no data rows\n";
    return kInvalid;
  }
  if (run.has_nodes) {
    std::vector<std::string> names;  // none when it cannot be read: every column is then reported absent
    read_csv_header((root / "nodes.csv").string(), names, read_error);
    for (const char* c : {"time", "node", "x", "y", "z"})
      if (std::find(names.begin(), names.end(), c) == names.end()) absent.push_back(c);
    if (!absent.empty()) {
      log << "towsim plot: " << (root / "nodes.csv").string() << ": no column " << join(absent, ", ", " or ")
          << " in its header\n";
      return kInvalid;
    }
  }
  if (!run.has_body) run.second_sphere = false;

  // Times, spans, planar or not.
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300, zmin = 1e300, zmax = -1e300;
  std::vector<double> times;
  for (std::size_t r = 0; r < ts.rows.size(); ++r) {
    const double t = ts.at(r, "time");
    if (!std::isfinite(t)) continue;
    times.push_back(t);
    for (const char* p : {"tow_", "end_", "body_"}) {
      const double x = ts.at(r, std::string(p) + "x"), y = ts.at(r, std::string(p) + "y"),
                   z = ts.at(r, std::string(p) + "z");
      if (std::isfinite(x)) xmin = std::min(xmin, x), xmax = std::max(xmax, x);
      if (std::isfinite(y)) ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      if (std::isfinite(z)) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
      if (std::isfinite(y) && std::abs(y) > 1e-9) run.three_d = true;
    }
  }
  if (times.empty()) {
    log << "towsim plot: " << (root / "timeseries.csv").string() << ": no valid time in its rows\n";
    return kInvalid;
  }
  run.t0 = times.front();
  run.t1 = times.back();
  run.t_last = times.back();
  run.rows = static_cast<long>(ts.rows.size());
  run.single = times.size() == 1;
  if (run.t1 <= run.t0) run.t1 = run.t0 + 1;  // a single row: still a valid range
  run.min_dt = 0;
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double d = times[i] - times[i - 1];
    if (d > 0 && (run.min_dt == 0 || d < run.min_dt)) run.min_dt = d;
  }
  run.x_span = xmax > xmin ? xmax - xmin : 0;
  run.y_span = ymax > ymin ? ymax - ymin : 0;
  run.z_span = zmax > zmin ? zmax - zmin : 0;
  run.x_lo = run.x_span > 0 ? xmin : 0;
  run.y_lo = run.y_span > 0 ? ymin : 0;
  run.z_lo = run.z_span > 0 ? zmin : 0;
  run.marker_every = nice((run.t1 - run.t0) / 12);
  const double dt_out = run.min_dt > 0 ? run.min_dt : 1;
  run.marker_rows = std::max(1, static_cast<int>(std::lround(run.marker_every / dt_out)));
  run.marker_every = run.marker_rows * dt_out;
  // Phase boundaries (summary.json `phases`): where a phase other than steady
  // starts or ends within the plotted times (not the run's last time).
  if (const auto ph = summary.find("phases"); ph != summary.end() && ph->is_array()) {
    std::map<double, std::pair<std::vector<std::string>, std::vector<std::string>>> at;  // starts, ends
    for (const auto& p : *ph) {
      if (!p.is_object() || !p.contains("start") || !p["start"].is_number() || !p.contains("end") ||
          !p["end"].is_number() || p.value("kind", std::string()) == "steady")
        continue;
      const std::string name = p.value("name", std::string("phase"));
      const double a = p["start"].get<double>(), b = p["end"].get<double>();
      if (a >= run.t0 && a < times.back()) at[a].first.push_back(name);
      if (b > run.t0 && b < times.back()) at[b].second.push_back(name + " end");
    }
    for (auto& [t, se] : at) {
      std::vector<std::string> all = se.first;
      all.insert(all.end(), se.second.begin(), se.second.end());
      run.marks.emplace_back(t, join(all, ", ", ", "));
    }
  }
  // About opt.snapshots shapes, at a round time step from the first output.
  const int ns = std::max(1, opt.snapshots);
  const double span = times.back() - times.front();
  double step = span;
  if (ns > 1 && span > 0) {
    int best = -1;
    const double k0 = std::floor(std::log10(span / (ns - 1))) - 1;
    for (int k = 0; k < 3; ++k)
      for (double m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0}) {
        const double st = m * std::pow(10.0, k0 + k);
        const int count = static_cast<int>(std::floor(span / st + 1e-9)) + 1;
        const int miss = std::abs(count - ns);
        if (best < 0 || miss < best || (miss == best && st > step)) best = miss, step = st;
      }
  }
  const int count = span > 0 && step > 0 ? static_cast<int>(std::floor(span / step + 1e-9)) + 1 : 1;
  for (int k = 0; k < count && run.has_nodes; ++k) {
    const double target = times.front() + k * step;
    const auto it = std::min_element(times.begin(), times.end(),
                                     [&](double a, double b) { return std::abs(a - target) < std::abs(b - target); });
    if (run.snapshot_times.empty() || *it != run.snapshot_times.back()) run.snapshot_times.push_back(*it);
  }

  // A sea-state run's spectra.csv, with at least one estimate.
  if (exists_file(root / "spectra.csv")) {
    CsvTable sp;
    if (read_csv_table((root / "spectra.csv").string(), sp, read_error) && !sp.rows.empty() && sp.has("omega") &&
        sp.has("tow_heave")) {
      run.has_spectra = true;
      double peak = 0;
      for (std::size_t r = 0; r < sp.rows.size(); ++r) {
        run.spectra_body = run.spectra_body || !std::isnan(sp.at(r, "body_depth"));
        if (sp.at(r, "wave_elevation") > peak) peak = sp.at(r, "wave_elevation");
      }
      for (std::size_t r = 0; r < sp.rows.size(); ++r)
        if (sp.at(r, "wave_elevation") >= 1e-4 * peak) run.spectra_wmax = std::max(run.spectra_wmax, sp.at(r, "omega"));
    }
  }

  // 3. gnuplot, before writing anything.
  const std::string prog = usable_gnuplot(log);
  if (prog.empty()) return kInvalid;

  // 4. Scripts, then figures.
  const fs::path plots = root / "plots";
  fs::remove_all(plots, ec);  // towsim's folder: no stale figure of an earlier run
  fs::create_directories(plots, ec);
  if (ec) {
    log << "towsim plot: cannot create " << plots.string() << ": " << ec.message() << "\n";
    return kGnuplotFailed;
  }
  if (run.status != "ok")
    log << "towsim plot: note: the run ended with status '" << run.status << "'; plotting what it wrote\n";
  if (run.cut_series) {  // a killed run: gnuplot reads the whole rows only
    const std::string text = read_text(root / "timeseries.csv");
    std::ofstream(plots / "timeseries.csv", std::ios::binary) << text.substr(0, text.rfind('\n') + 1);
    log << "towsim plot: note: the last row of timeseries.csv is cut off (the run was killed); left out\n";
  }
  if (run.has_nodes) {  // nodes.csv, read once
    std::string error;
    if (!write_node_data(root, plots, run, times, error)) {
      log << "towsim plot: " << error << "\n";
      return kInvalid;
    }
  }
  const std::string mag_tow = ts.has("tow_tension") ? "tow_tension" : "";
  const std::string mag_link = ts.has("link_tension") ? "link_tension" : "";
  std::vector<std::pair<std::string, std::string>> scripts;
  std::vector<std::string> names = plot_names(run.has_body, run.three_d, run.single, run.has_spectra);
  if (run.has_winch && !run.single) names.push_back("winch");
  for (const auto& name : names) {
    std::string text;
    if (name == "trajectories_xz")
      text = fig_trajectories(run, opt);
    else if (name == "tow_force")
      text = fig_components(run, opt, name, "tow force on the cable at the tow point", "tow_force_", mag_tow, "F_R");
    else if (name == "paths_xy")
      text = fig_paths(run, opt);
    else if (name == "end_depth")
      text = fig_depth(run, opt);
    else if (name == "body_angles")
      text = fig_angles(run, opt);
    else if (name == "cable_shapes_xz" || name == "cable_shapes_xy") {
      if (!run.has_nodes) {
        log << "towsim plot: skipped " << name << " (the run wrote no nodes.csv)\n";
        continue;
      }
      text = fig_shapes(run, opt, name == "cable_shapes_xy");
    } else if (name == "tension_map" || name == "tension_along_cable") {
      if (!run.has_nodes) {
        log << "towsim plot: skipped " << name << " (the run wrote no nodes.csv)\n";
        continue;
      }
      text = name == "tension_map" ? fig_tension_map(run, opt) : fig_tension_along(run, opt);
    } else if (name == "depth_layback")
      text = fig_depth_layback(run, opt);
    else if (name == "winch")
      text = fig_winch(run, opt);
    else if (name == "spectra")
      text = fig_spectra(run, opt);
    else if (name == "link_force")
      text = fig_components(run, opt, name, "link force exerted by the cable on the body", "link_force_", mag_link,
                            "F_L");
    scripts.emplace_back(name, text);
  }
  return render_scripts(plots, scripts, prog, log);
}

namespace plot_render {

std::string style() {
  return "set datafile separator comma\n"
         "set datafile columnheaders\n"
         "set encoding utf8\n"
         "set style line 100 lt 1 lw 0.6 lc rgb '#d4d4d4'\n"
         "set grid ls 100\n"
         "set key outside right top vertical reverse Left samplen 2 spacing 1.1 width 1\n"
         "set border lw 1.2\n";
}
/// A gnuplot single-quoted string literal.
std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else
      out += c;
  }
  return out + "'";
}

/// Script text that renders the current plot (`plot_cmd`) as PNG and SVG.
std::string render(const std::string& name, const std::string& plot_cmd, const PlotOptions& o) {
  std::ostringstream s;
  const int font = font_points(o.width);
  s << "set terminal pngcairo size " << o.width << "," << o.height << " noenhanced font 'Sans," << font
    << "' linewidth 1.5\n"
    << "set output '" << name << ".png'\n"
    << plot_cmd << "\n"
    << "set terminal svg size " << o.width << "," << o.height << " noenhanced font 'Sans," << font
    << "' linewidth 1.5 background '#ffffff'\n"
    << "set output '" << name << ".svg'\n"
    << "replot\n"
    << "unset output\n";
  return s.str();
}

/// The gnuplot program, checked for its pngcairo and svg terminals; "" (the
/// reason in `log`) when it cannot draw.
std::string usable_gnuplot(std::ostream& log) {
  std::string prog = gnuplot_program();  // returned: moved
  int err = 0;
  const int probe = spawn(prog, {"-e", "set terminal pngcairo; set terminal svg"}, "", err);
  if (probe < 0) {
    log << "towsim plot: cannot run the gnuplot program ('" << prog << "': " << std::strerror(err)
        << "); install it (Debian/Ubuntu: apt-get install gnuplot-nox) or set TOWSIM_GNUPLOT to its path\n";
    return "";
  }
  if (probe != 0) {
    log << "towsim plot: '" << prog
        << "' lacks the pngcairo or svg terminal; install a full gnuplot (Debian/Ubuntu: apt-get install "
           "gnuplot-nox)\n";
    return "";
  }
  return prog;
}

/// Write each (name, script) into `plots` and render it with `prog`; gnuplot's
/// messages go to plots/gnuplot.log (and `log` on a failure). Returns kOk or kGnuplotFailed.
int render_scripts(const fs::path& plots, const std::vector<std::pair<std::string, std::string>>& scripts,
                   const std::string& prog, std::ostream& log) {
  std::error_code ec;
  const std::string gp_log = (plots / "gnuplot.log").string();
  std::ofstream(gp_log, std::ios::trunc).close();
  const std::string plots_abs = fs::absolute(plots, ec).string();
  int status = kOk;
  for (const auto& [name, text] : scripts) {
    const fs::path script = plots / (name + ".gp");
    {
      std::ofstream out(script, std::ios::trunc);
      out << text;
      if (!out) {
        log << "towsim plot: cannot write " << script.string() << "\n";
        return kGnuplotFailed;
      }
    }
    const auto before = fs::file_size(gp_log, ec);
    int err = 0;
    const int rc = spawn(prog, {"-e", "cd " + quote(plots_abs), name + ".gp"}, gp_log, err);
    const bool png = exists_file(plots / (name + ".png")) && fs::file_size(plots / (name + ".png"), ec) > 0;
    const bool svg = exists_file(plots / (name + ".svg")) && fs::file_size(plots / (name + ".svg"), ec) > 0;
    if (rc != 0 || !png || !svg) {
      log << "towsim plot: gnuplot failed on " << script.string();
      if (rc < 0)
        log << " (" << std::strerror(err) << ")";
      else if (rc != 0)
        log << " (exit status " << rc << ")";
      log << ":\n";
      std::ifstream in(gp_log);
      in.seekg(static_cast<std::streamoff>(before));
      log << in.rdbuf();
      status = kGnuplotFailed;
      continue;
    }
    log << "towsim plot: wrote " << (plots / (name + ".png")).string() << " and .svg\n";
  }
  return status;
}

}  // namespace plot_render

}  // namespace towsim::cli
