#include "report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "plot.hpp"
#include "run_files.hpp"
#include "towsim/output/output.hpp"

namespace towsim::cli {

using namespace towsim::output;
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

constexpr int kOk = 0;
constexpr int kWriteFailed = 1;
constexpr int kInvalid = 2;

/// Text safe inside HTML elements and attribute values.
std::string html(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Text safe inside a <script> element: no "</" can close it early ("<\/" is
/// the same in JSON strings and in JavaScript strings and regular expressions).
std::string script_safe(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '<' && i + 1 < s.size() && s[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8) |
                       static_cast<unsigned char>(in[i + 2]);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = static_cast<unsigned char>(in[i]) << 16;
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A number for a person: 6 significant digits, 0 for round-off.
std::string fmt(double v) {
  if (!std::isfinite(v)) return "&ndash;";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", std::abs(v) < output::kZeroBelow ? 0.0 : v);
  return b;
}

/// A number for the 3-D view as JSON (null when not finite): 7 significant
/// digits (a millimetre on a kilometre of cable) keep the page small.
json jnum(double v) {
  if (!std::isfinite(v)) return nullptr;
  if (std::abs(v) < output::kZeroBelow) return 0.0;
  char b[32];
  std::snprintf(b, sizeof b, "%.7g", v);
  return std::strtod(b, nullptr);
}

/// What each figure shows, in page order.
const std::vector<std::pair<std::string, std::string>>& figure_captions() {
  static const std::vector<std::pair<std::string, std::string>> c{
      {"trajectories_xz", "Trajectories of the tow point, cable end and body in the vertical x-z plane"},
      {"paths_xy", "Horizontal paths (plan view)"},
      {"depth_layback", "Depth of the body (or cable end) against layback"},
      {"tension_map", "Tension along the cable against time"},
      {"tension_along_cable", "Tension along the cable"},
      {"tow_force", "Tow force at the tow point"},
      {"end_depth", "Depth of the cable's lower end"},
      {"body_angles", "Body roll, pitch and yaw"},
      {"link_force", "Link force on the body"},
      {"spectra", "Spectra of wave elevation, tow point heave, body heave and tension; ship -> fish transfer function"},
      {"cable_shapes_xz", "Cable shapes, side view"},
      {"cable_shapes_xy", "Cable shapes, plan view"},
  };
  return c;
}

}  // namespace

std::string summary_unit(const std::string& key) {
  auto ends = [&key](const std::string& e) {
    return key.size() >= e.size() && key.compare(key.size() - e.size(), e.size(), e) == 0;
  };
  if (key == "end_time" || key == "wall_seconds") return "s";
  if (key == "steps" || key == "rejected_steps" || key == "rhs_evaluations") return "count";
  if (key == "samples") return "output times";
  if (key == "max_utilisation") return "fraction of the breaking load";
  if (ends("_deg")) return "deg";
  if (ends("_force") || ends("_tension")) return "N";
  if (ends("_depth") || ends("_length") || ends("layback")) return "m";
  return "";
}

namespace {

/// The summary's key results as table rows (label, value, unit, time or "").
std::vector<std::array<std::string, 4>> summary_rows(const json& sm) {
  std::vector<std::array<std::string, 4>> rows;
  auto value = [](const json& j) { return j.is_number() ? fmt(j.get<double>()) : std::string("&ndash;"); };
  const auto fin = sm.value("final", json::object());
  auto final_row = [&](const char* key, const std::string& label) {
    if (fin.is_object() && fin.contains(key)) rows.push_back({label, value(fin[key]), summary_unit(key), ""});
  };
  if (sm.contains("status"))
    rows.push_back({"status", html(sm["status"].is_string() ? sm["status"].get<std::string>() : ""), "", ""});
  if (sm.contains("end_time")) rows.push_back({"simulated time", value(sm["end_time"]), "s", ""});
  final_row("layback", "final layback");
  final_row("body_depth", "final body depth");
  final_row("end_depth", "final cable end depth");
  final_row("tow_tension", "final tow tension");
  final_row("link_tension", "final link tension");
  final_row("deployed_length", "final deployed cable length");
  const auto ex = sm.value("extremes", json::object());
  if (ex.is_object())
    for (const auto& [k, v] : ex.items()) {
      const std::string unit = summary_unit(k);
      if (v.is_object() && v.contains("value")) {
        rows.push_back({html(k), value(v["value"]), unit, value(v.value("time", json()))});
      } else if (v.is_object() && v.contains("min") && v.contains("max")) {
        rows.push_back(
            {html(k) + " min", value(v["min"].value("value", json())), unit, value(v["min"].value("time", json()))});
        rows.push_back(
            {html(k) + " max", value(v["max"].value("value", json())), unit, value(v["max"].value("time", json()))});
      }
    }
  if (sm.contains("max_utilisation") && sm["max_utilisation"].is_number())
    rows.push_back({"max_utilisation", value(sm["max_utilisation"]), summary_unit("max_utilisation"),
                    value(sm.value("max_utilisation_time", json()))});
  for (const char* k : {"steps", "rhs_evaluations", "wall_seconds", "samples"})
    if (sm.contains(k)) rows.push_back({k, value(sm[k]), summary_unit(k), ""});
  return rows;
}

/// The "Phases" section (summary.json `phases`): one row per phase, its
/// extremes and settle times; "" without phases (a statics configuration).
std::string phases_table(const json& sm) {
  const auto ph = sm.find("phases");
  if (ph == sm.end() || !ph->is_array() || ph->empty()) return "";
  auto value = [](const json& j) { return j.is_number() ? fmt(j.get<double>()) : std::string("&ndash;"); };
  auto field = [](const json& o, const char* k) { return o.is_object() && o.contains(k) ? o[k] : json(); };
  bool link = false;
  for (const auto& p : *ph) link = link || (p.is_object() && p.contains("link_tension"));
  std::ostringstream h;
  h << "<h2>Phases</h2>\n<div class=\"wide\"><table id=\"phases\">\n<tr><th>phase</th><th>source</th>"
    << "<th>start [s]</th><th>end [s]</th>"
    << "<th>min tow tension [N]</th><th>at t [s]</th><th>max tow tension [N]</th><th>at t [s]</th>"
    << "<th>min depth [m]</th><th>at t [s]</th><th>max depth [m]</th><th>at t [s]</th>";
  if (link) h << "<th>max link tension [N]</th><th>at t [s]</th>";
  h << "<th>tow tension settle time [s]</th><th>depth settle time [s]</th>"
    << "<th>settled tow tension [N]</th><th>settled depth [m]</th><th>settle window end [s]</th></tr>\n";
  for (const auto& p : *ph) {
    if (!p.is_object()) continue;
    const json T = field(p, "tow_tension"), d = field(p, "depth"), L = field(p, "link_tension");
    auto cell = [&](const json& v) { h << "<td class=\"n\">" << value(v) << "</td>"; };
    auto ext = [&](const json& q, const char* which) {
      const json e = field(q, which);
      cell(field(e, "value"));
      cell(field(e, "time"));
    };
    const json name = field(p, "name"), src = field(p, "source");
    h << "<tr><td>" << html(name.is_string() ? name.get<std::string>() : "") << "</td><td>"
      << (src.is_string() ? html(src.get<std::string>()) : std::string("&ndash;")) << "</td>";
    cell(field(p, "start"));
    cell(field(p, "end"));
    ext(T, "min");
    ext(T, "max");
    ext(d, "min");
    ext(d, "max");
    if (link) ext(L, "max");
    cell(field(T, "settle_time"));
    cell(field(d, "settle_time"));
    cell(field(T, "settled_value"));
    cell(field(d, "settled_value"));
    cell(field(p, "settle_end"));
    h << "</tr>\n";
  }
  h << "</table></div>\n<p class=\"small\">Depth: of the body's origin, or of the cable's end without a body. "
    << "Extremes over the output times from the phase's start up to its end (an output time on a boundary "
       "belongs to the phase starting there). The settle window runs from the phase's start to the next time "
       "an input changes (or the run's end); the settled values are the last ones before its end. A settle "
       "time is counted from the phase's start to the first output time after which the value stays within its "
       "band (summary.json <code>band</code>) of the settled value; &ndash;: it does not settle in the window "
       "(docs/scenario.md, Outputs).</p>\n";
  return h.str();
}

/// Frames of two points, the tow point and the cable's end, read from
/// timeseries.csv rows `rows[pick[i]]` (tension: the tow tension at both).
bool chord_frames(const CsvTable& ts, const std::vector<std::size_t>& pick, const std::vector<double>& times,
                  const std::vector<std::size_t>& rows, std::vector<NodeFrame>& frames, std::string& error) {
  const int tx = ts.col("tow_x"), ty = ts.col("tow_y"), tz = ts.col("tow_z"), ex = ts.col("end_x"),
            ey = ts.col("end_y"), ez = ts.col("end_z"), tT = ts.col("tow_tension");
  if (tx < 0 || ty < 0 || tz < 0 || ex < 0 || ey < 0 || ez < 0) {
    error = "timeseries.csv: no nodes.csv and no tow_x..z, end_x..z columns to draw the cable";
    return false;
  }
  for (std::size_t i : pick) {
    const std::size_t r = rows[i];
    const double T = tT >= 0 ? ts.at(r, tT) : std::numeric_limits<double>::quiet_NaN();
    frames.push_back({times[i],
                      {ts.at(r, tx), ts.at(r, ex)},
                      {ts.at(r, ty), ts.at(r, ey)},
                      {ts.at(r, tz), ts.at(r, ez)},
                      {T, T},
                      {}});
  }
  return true;
}

/// The animation data: frames of node positions and tensions, body pose.
/// A network's frames (NodeFrame::line_starts) when every frame has the same
/// lines (a winch may change a line's joints from frame to frame): each
/// line's first joint in each frame, and its fewest joints over the frames.
struct NetworkLines {
  std::vector<std::vector<std::size_t>> first;  // per frame, per line: its first joint's index
  std::vector<std::size_t> fewest;              // per line: its fewest joints in a frame
  bool empty() const { return fewest.empty(); }
};

NetworkLines network_lines(const std::vector<NodeFrame>& frames) {
  NetworkLines out;
  const std::size_t nl = frames.front().line_starts.size() + 1;
  if (nl < 2) return out;  // a chain
  for (const NodeFrame& f : frames)
    if (f.line_starts.size() + 1 != nl) return {};
  out.fewest.assign(nl, static_cast<std::size_t>(-1));
  for (const NodeFrame& f : frames) {
    std::vector<std::size_t> first{0};
    first.insert(first.end(), f.line_starts.begin(), f.line_starts.end());
    for (std::size_t i = 0; i < nl; ++i) {
      const std::size_t end = i + 1 < nl ? first[i + 1] : f.x.size();
      out.fewest[i] = std::min(out.fewest[i], end - first[i]);
    }
    out.first.push_back(std::move(first));
  }
  return out;
}

/// A body's shapes at their true size, body axes, metres, from its scenario
/// echo: the load spheres, the hull cylinders and the fins (`surfaces`,
/// drawn as squares of their area); none when the echo has none or cannot
/// be read (the viewer then draws a marker ball and says so).
json body_shapes(const json& b) {
  json spheres = json::array(), cylinders = json::array(), surfaces = json::array();
  try {
    if (b.is_object() && b.contains("spheres"))
      for (const auto& s : b.at("spheres")) spheres.push_back({{"center", s.at("center")}, {"radius", s.at("radius")}});
    if (b.is_object() && b.contains("cylinders"))
      for (const auto& c : b.at("cylinders"))
        cylinders.push_back({{"center", c.at("center")},
                             {"axis", c.at("axis")},
                             {"length", c.at("length")},
                             {"diameter", c.at("diameter")}});
    if (b.is_object() && b.contains("surfaces"))
      for (const auto& f : b.at("surfaces"))
        surfaces.push_back(
            {{"center", f.at("center")}, {"chord", f.at("chord")}, {"normal", f.at("normal")}, {"area", f.at("area")}});
  } catch (const std::exception&) {
    spheres = cylinders = surfaces = json::array();
  }
  return {{"spheres", spheres}, {"cylinders", cylinders}, {"surfaces", surfaces}};
}

/// The viewer's body: its poses per frame, then its shapes.
json with_pose(const json& pos, const json& rpy, const json& shapes) {
  json b = {{"pos", pos}, {"rpy", rpy}};
  for (const auto& [k, v] : shapes.items()) b[k] = v;
  return b;
}

/// A network's body in timeseries.csv: its name, its pose's columns (x, y,
/// z, roll, pitch, yaw) and its scenario echo (null when none is found).
struct NetworkBodyTrack {
  std::string name;
  std::array<int, 6> col{};
  json echo;
};

/// Every body of a network's run (summary.json's scenario has `lines`):
/// the `bodies:` list, then the in-line bodies of the lines' sections, in
/// the order their columns come; those without pose columns are left out.
std::vector<NetworkBodyTrack> network_bodies(const CsvTable& ts, const json& sm) {
  std::vector<NetworkBodyTrack> out;
  if (!sm.contains("scenario") || !sm.at("scenario").is_object() || !sm.at("scenario").contains("lines")) return out;
  const json& sc = sm.at("scenario");
  std::vector<std::pair<std::string, json>> named;
  if (sc.contains("bodies") && sc.at("bodies").is_array())
    for (const auto& b : sc.at("bodies"))
      if (b.is_object() && b.contains("name") && b.at("name").is_string()) named.emplace_back(b.at("name"), b);
  if (sc.at("lines").is_array())
    for (const auto& l : sc.at("lines"))
      if (l.is_object() && l.contains("sections") && l.at("sections").is_array())
        for (const auto& sec : l.at("sections"))
          if (sec.is_object() && sec.contains("body") && sec.at("body").is_object() &&
              sec.at("body").contains("name") && sec.at("body").at("name").is_string())
            named.emplace_back(sec.at("body").at("name"), sec.at("body"));
  for (const auto& [name, echo] : named) {
    NetworkBodyTrack t{name, {}, echo};
    const char* suffix[6] = {"_x", "_y", "_z", "_roll_deg", "_pitch_deg", "_yaw_deg"};
    bool all = true;
    for (int k = 0; k < 6; ++k) all = all && (t.col[static_cast<std::size_t>(k)] = ts.col(name + suffix[k])) >= 0;
    if (all) out.push_back(std::move(t));
  }
  return out;
}

bool animation_data(const fs::path& root, const CsvTable& ts, const json& sm, const ReportOptions& opt, json& data,
                    std::string& error) {
  const int ct = ts.col("time");
  std::vector<double> times;
  std::vector<std::size_t> rows;
  for (std::size_t r = 0; r < ts.rows.size(); ++r)
    if (std::isfinite(ts.at(r, ct))) times.push_back(ts.at(r, ct)), rows.push_back(r);
  const auto pick = spread_indices(times.size(), static_cast<std::size_t>(std::max(1, opt.max_frames)));
  std::vector<double> wanted;
  for (std::size_t i : pick) wanted.push_back(times[i]);
  std::vector<NodeFrame> frames;
  std::error_code ec;
  if (!fs::is_regular_file(root / "nodes.csv", ec)) {
    // No nodes.csv (write_nodes: false): each frame is the chord from the tow
    // point to the cable's end, from timeseries.csv.
    if (!chord_frames(ts, pick, times, rows, frames, error)) return false;
  } else if (!read_node_frames((root / "nodes.csv").string(), wanted, frames, error)) {
    return false;
  }
  if (frames.empty()) {
    error = (root / "nodes.csv").string() + ": no rows at the times of timeseries.csv";
    return false;
  }
  // Every frame the same number of points (the viewer draws a fixed count):
  // with a winch the joints per frame change, so each frame keeps as many of
  // its joints, spread along it (ends included), as the smallest frame has.
  std::size_t n = frames.front().x.size();
  for (const auto& f : frames) n = std::min(n, f.x.size());
  const std::size_t n_keep = spread_indices(n, static_cast<std::size_t>(std::max(2, opt.max_nodes))).size();
  // A network's lines: each line's joints spread on their own, as many in
  // every frame (its fewest, within its share of the budget), and the
  // viewer breaks the drawn line between lines.
  const NetworkLines lines = network_lines(frames);
  std::vector<std::size_t> per_line;
  if (!lines.empty()) {
    const std::size_t share = std::max<std::size_t>(2, static_cast<std::size_t>(opt.max_nodes) / lines.fewest.size());
    json breaks = json::array();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < lines.fewest.size(); ++i) {
      per_line.push_back(spread_indices(lines.fewest[i], share).size());
      if (i > 0) breaks.push_back(kept);
      kept += per_line.back();
    }
    data["breaks"] = breaks;
  }
  // Frame j's joints kept: a network's line by line, a chain's n_keep along it.
  const auto kept_joints = [&](std::size_t j, const NodeFrame& f) {
    if (lines.empty()) return spread_indices(f.x.size(), n_keep);
    std::vector<std::size_t> keep;
    const auto& first = lines.first[j];
    for (std::size_t i = 0; i < per_line.size(); ++i) {
      const std::size_t a = first[i], b = i + 1 < first.size() ? first[i + 1] : f.x.size();
      for (std::size_t k : spread_indices(b - a, per_line[i])) keep.push_back(a + k);
    }
    return keep;
  };
  const bool body = ts.col("body_x") >= 0;
  const int bx = ts.col("body_x"), by = ts.col("body_y"), bz = ts.col("body_z"), br = ts.col("body_roll_deg"),
            bp = ts.col("body_pitch_deg"), byaw = ts.col("body_yaw_deg"), cl = ts.col("layback"),
            cT = ts.col("tow_tension"), cd = body ? ts.col("body_depth") : ts.col("end_depth");
  json jt = json::array(), jn = json::array(), jT = json::array(), jpos = json::array(), jrpy = json::array(),
       jinfo = json::array();
  double tmax = 0;
  std::size_t w = 0;  // index into `pick` of the frame's timeseries row
  for (std::size_t j = 0; j < frames.size(); ++j) {
    const NodeFrame& f = frames[j];
    const auto keep = kept_joints(j, f);
    while (w < pick.size() && std::abs(times[pick[w]] - f.t) > 1e-9 * std::max(1.0, std::abs(f.t))) ++w;
    const std::size_t r = w < pick.size() ? rows[pick[w]] : rows.back();
    json p = json::array(), T = json::array();
    for (std::size_t k : keep) {
      p.push_back(jnum(f.x[k]));
      p.push_back(jnum(f.y[k]));
      p.push_back(jnum(f.z[k]));
      T.push_back(jnum(f.tension[k]));
      if (std::isfinite(f.tension[k])) tmax = std::max(tmax, f.tension[k]);
    }
    jt.push_back(output::tidy_time(f.t));
    jn.push_back(std::move(p));
    jT.push_back(std::move(T));
    std::string info;
    if (cl >= 0) info += "layback " + fmt(ts.at(r, cl)) + " m";
    if (cd >= 0) info += std::string(info.empty() ? "" : ", ") + "depth " + fmt(ts.at(r, cd)) + " m";
    if (cT >= 0) info += std::string(info.empty() ? "" : ", ") + "tow tension " + fmt(ts.at(r, cT)) + " N";
    jinfo.push_back(info);
    if (body) {
      jpos.push_back({jnum(ts.at(r, bx)), jnum(ts.at(r, by)), jnum(ts.at(r, bz))});
      jrpy.push_back({jnum(ts.at(r, br)), jnum(ts.at(r, bp)), jnum(ts.at(r, byaw))});
    }
  }
  data["times"] = jt;
  data["nodes"] = jn;
  data["tension"] = jT;
  data["tension_max"] = jnum(tmax);
  data["info"] = jinfo;
  data["body"] = nullptr;
  if (body) {
    const json echo = sm.contains("scenario") && sm.at("scenario").contains("body") ? sm.at("scenario").at("body")
                                                                                    : json();
    data["body"] = with_pose(jpos, jrpy, body_shapes(echo));
  }
  // A network's bodies (`<name>_x`, ..., `<name>_yaw_deg` in timeseries.csv), each with its pose per frame.
  const std::vector<NetworkBodyTrack> tracks = network_bodies(ts, sm);
  if (!tracks.empty()) {
    json bodies = json::array();
    for (const NetworkBodyTrack& b : tracks) {
      json pos = json::array(), rpy = json::array();
      std::size_t wb = 0;
      for (const auto& f : frames) {
        while (wb < pick.size() && std::abs(times[pick[wb]] - f.t) > 1e-9 * std::max(1.0, std::abs(f.t))) ++wb;
        const std::size_t r = wb < pick.size() ? rows[pick[wb]] : rows.back();
        pos.push_back({jnum(ts.at(r, b.col[0])), jnum(ts.at(r, b.col[1])), jnum(ts.at(r, b.col[2]))});
        rpy.push_back({jnum(ts.at(r, b.col[3])), jnum(ts.at(r, b.col[4])), jnum(ts.at(r, b.col[5]))});
      }
      json one = with_pose(pos, rpy, body_shapes(b.echo));
      one["name"] = b.name;
      bodies.push_back(one);
    }
    data["bodies"] = bodies;
  }
  // The camera's framing: on the cable (and body) of the frame shown, at a
  // distance for the largest extent the cable takes in any frame (the
  // diagonal of the box around its joints and the body origin), so the view
  // follows the cable at one zoom; and the whole run (every frame's box).
  double cable_extent = 0;
  std::array<double, 3> all_lo{1e300, 1e300, 1e300}, all_hi{-1e300, -1e300, -1e300};
  std::vector<std::array<double, 3>> centres;
  for (std::size_t i = 0; i < jn.size(); ++i) {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    auto add = [&](double x, double y, double z) {
      const std::array<double, 3> p{x, y, z};
      for (std::size_t d = 0; d < 3; ++d)
        if (std::isfinite(p[d])) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
    };
    const auto& p = jn[i];
    for (std::size_t k = 0; k + 2 < p.size(); k += 3)
      if (p[k].is_number() && p[k + 1].is_number() && p[k + 2].is_number())
        add(p[k].get<double>(), p[k + 1].get<double>(), p[k + 2].get<double>());
    if (body && jpos[i][0].is_number() && jpos[i][1].is_number() && jpos[i][2].is_number())
      add(jpos[i][0].get<double>(), jpos[i][1].get<double>(), jpos[i][2].get<double>());
    if (data.contains("bodies"))
      for (const auto& b : data["bodies"]) {
        const auto& q = b["pos"][i];
        if (q[0].is_number() && q[1].is_number() && q[2].is_number())
          add(q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
      }
    if (lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]) {
      centres.push_back(centres.empty() ? std::array<double, 3>{0, 0, 0} : centres.back());
      continue;
    }
    cable_extent = std::max(cable_extent, std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
    centres.push_back({0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])});
    for (std::size_t d = 0; d < 3; ++d) all_lo[d] = std::min(all_lo[d], lo[d]), all_hi[d] = std::max(all_hi[d], hi[d]);
  }
  if (all_lo[0] > all_hi[0]) all_lo = all_hi = {0, 0, 0};
  json jc = json::array();
  for (const auto& c : centres) jc.push_back({jnum(c[0]), jnum(c[1]), jnum(c[2])});
  data["view"] = {
      {"cable_centres", jc},
      {"cable_extent", jnum(std::max(cable_extent, 1e-3))},
      {"all_centre",
       {jnum(0.5 * (all_lo[0] + all_hi[0])), jnum(0.5 * (all_lo[1] + all_hi[1])), jnum(0.5 * (all_lo[2] + all_hi[2]))}},
      {"all_extent",
       jnum(std::max(std::hypot(all_hi[0] - all_lo[0], all_hi[1] - all_lo[1], all_hi[2] - all_lo[2]), 1e-3))}};
  return true;
}

const char* kStyle = R"(
body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;margin:0 auto;max-width:1200px;padding:0 16px 40px;color:#222}
h1{font-size:1.5em;margin:18px 0 4px}h2{font-size:1.2em;margin:28px 0 8px;border-bottom:1px solid #ddd}
.sub{color:#666;margin:0 0 12px}
#view3d{width:100%;height:560px;background:#eef3f8;border:1px solid #ccd;position:relative}
#controls{display:flex;gap:12px;align-items:center;margin:8px 0}
#frame{flex:1}#frame-label{font-variant-numeric:tabular-nums;min-width:22em}
.note{background:#fff6e0;border:1px solid #e8c76a;padding:10px 14px;border-radius:4px}
.small{color:#666;font-size:.9em}
table{border-collapse:collapse}td,th{border-bottom:1px solid #e4e4e4;padding:4px 12px;text-align:left}
td.n{text-align:right;font-variant-numeric:tabular-nums}
.wide{overflow-x:auto}#phases th{font-weight:600;font-size:.9em}
figure{margin:16px 0}figure img{max-width:100%;border:1px solid #eee}figcaption{color:#444;margin-top:4px}
pre{background:#f6f6f6;padding:10px;overflow:auto;max-height:400px;font-size:.85em}
)";

}  // namespace

ReportOptions default_report_options() {
  ReportOptions o;
  o.viewer_js = embedded_viewer_js();
  o.viewer_note = embedded_viewer_note();
  return o;
}

int report_run(const std::string& dir, std::ostream& log, const ReportOptions& opt) {
  const fs::path root(dir);
  std::error_code ec;
  const char* kUsage = "expected the output directory of `towsim run --out DIR` or `towsim statics --out DIR`";
  if (!fs::is_directory(root, ec)) {
    log << "towsim report: " << dir << ": no such directory (" << kUsage << ")\n";
    return kInvalid;
  }
  if (!fs::is_regular_file(root / "timeseries.csv", ec)) {
    log << "towsim report: " << dir << " has no timeseries.csv (" << kUsage << ")\n";
    return kInvalid;
  }
  const bool has_nodes = fs::is_regular_file(root / "nodes.csv", ec);
  json sm = json::object();
  if (fs::is_regular_file(root / "summary.json", ec)) {
    try {
      std::ifstream in(root / "summary.json");
      sm = json::parse(in);
    } catch (const std::exception& e) {
      log << "towsim report: " << (root / "summary.json").string() << ": not valid JSON: " << e.what() << "\n";
      return kInvalid;
    }
    if (!sm.is_object()) sm = json::object();
  }
  CsvTable ts;
  std::string error;
  if (!read_csv_table((root / "timeseries.csv").string(), ts, error)) {
    log << "towsim report: " << error << "\n";
    return kInvalid;
  }
  if (ts.col("time") < 0 || ts.rows.empty()) {
    log << "towsim report: " << (root / "timeseries.csv").string() << ": no time column or no rows\n";
    return kInvalid;
  }
  json data;
  if (!animation_data(root, ts, sm, opt, data, error)) {
    log << "towsim report: " << error << "\n";
    return kInvalid;
  }
  std::string model = sm.is_object() && sm.contains("model") && sm["model"].is_string() ? sm["model"].get<std::string>()
                                                                                        : root.filename().string();
  if (model.empty()) model = "run";

  // The figures: `towsim plot` first (its messages kept for the page).
  std::string plot_note;
  if (opt.plots) {
    std::ostringstream plog;
    const int rc = plot_run(dir, plog);
    if (rc != 0) {
      plot_note = plog.str();
      log << plot_note;
    }
  }

  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>towsim report: " << html(model) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
  h << "<h1>towsim report: " << html(model) << "</h1>\n<p class=\"sub\">" << html(fs::absolute(root, ec).string())
    << " &middot; " << ts.rows.size() << " output times";
  if (sm.contains("status") && sm["status"].is_string())
    h << " &middot; status " << html(sm["status"].get<std::string>());
  h << "</p>\n";

  // 1. The 3-D view.
  h << "<h2>3-D view</h2>\n";
  if (!opt.viewer_js.empty()) {
    h << "<div id=\"view3d\"></div>\n<div id=\"controls\"><button id=\"play\" type=\"button\">Play</button>"
      << "<button id=\"fit\" type=\"button\">Whole run</button>"
      << "<input id=\"frame\" type=\"range\" min=\"0\" max=\"0\" value=\"0\" aria-label=\"time\">"
      << "<span id=\"frame-label\"></span></div>\n<p class=\"small\" id=\"scale-note\"></p>\n";
    if (!has_nodes)
      h << "<p class=\"note\" id=\"no-nodes\">This run wrote no nodes.csv (simulation.write_nodes: false): "
        << "the view shows the straight chord from the tow point to the cable's end, not the cable's shape.</p>\n";
  } else {
    h << "<p class=\"note\" id=\"no3d\">No 3-D view in this report: "
      << html(opt.viewer_note.empty() ? std::string("the viewer was not built") : std::string(opt.viewer_note))
      << ". The figures and the summary below are complete.</p>\n";
  }

  // 2. The summary.
  h << "<h2>Summary</h2>\n<table id=\"summary\">\n<tr><th>quantity</th><th>value</th><th>unit</th><th>at t "
       "(s)</th></tr>\n";
  for (const auto& r : summary_rows(sm))
    h << "<tr><td>" << r[0] << "</td><td class=\"n\">" << r[1] << "</td><td>" << html(r[2]) << "</td><td class=\"n\">"
      << r[3] << "</td></tr>\n";
  h << "</table>\n";
  if (sm.empty()) h << "<p class=\"small\">No summary.json in this directory.</p>\n";
  h << phases_table(sm);

  // 3. The figures, as PNG data URIs.
  h << "<h2>Figures</h2>\n";
  if (!plot_note.empty())
    h << "<p class=\"note\">The figures could not all be rendered (towsim plot):</p><pre>" << html(plot_note)
      << "</pre>\n";
  int figures = 0;
  for (const auto& [name, caption] : figure_captions()) {
    const fs::path png = root / "plots" / (name + ".png");
    if (!fs::is_regular_file(png, ec)) continue;
    h << "<figure id=\"fig-" << name << "\"><img alt=\"" << html(caption) << "\" src=\"data:image/png;base64,"
      << base64(read_file(png)) << "\"><figcaption>" << html(caption) << " (plots/" << name
      << ".png)</figcaption></figure>\n";
    ++figures;
  }
  if (figures == 0) h << "<p class=\"small\">No figures (run `towsim plot " << html(dir) << "`).</p>\n";

  // 4. The scenario echo.
  if (sm.contains("scenario")) {
    h << "<h2>Scenario</h2>\n<pre>" << html(sm["scenario"].dump(2, ' ', false, json::error_handler_t::replace))
      << "</pre>\n";
  }
  h << "<p class=\"small\">Written by towsim report. Self-contained: no network access is needed to view it.</p>\n";

  // 5. The data and the viewer.
  if (!opt.viewer_js.empty()) {
    h << "<script id=\"towsim-data\" type=\"application/json\">"
      << script_safe(data.dump(-1, ' ', false, json::error_handler_t::replace)) << "</script>\n"
      << "<script>\n"
      << script_safe(opt.viewer_js) << "\n</script>\n";
  } else {
    h << "<script>document.documentElement.setAttribute('data-ready','no-3d');</script>\n";
  }
  h << "</body>\n</html>\n";

  const fs::path out = root / "report.html";
  const fs::path tmp = root / "report.html.tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f << h.str();
    if (!f) {
      log << "towsim report: cannot write " << tmp.string() << "\n";
      return kWriteFailed;
    }
  }
  fs::rename(tmp, out, ec);
  if (ec) {
    log << "towsim report: cannot write " << out.string() << ": " << ec.message() << "\n";
    return kWriteFailed;
  }
  log << "towsim report: wrote " << out.string() << " (" << (fs::file_size(out, ec) + 512) / 1024 << " KiB"
      << (opt.viewer_js.empty() ? ", without the 3-D view" : "") << ")\n";
  return kOk;
}

}  // namespace towsim::cli
