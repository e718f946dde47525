#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

#include "parse_sections.hpp"
#include "scalar.hpp"
#include "towsim/scenario/parse.hpp"

namespace towsim::scenario {
namespace {

/// Split one CSV line at commas, remembering each field's 1-based column.
std::vector<std::pair<std::string, int>> split_csv(const std::string& line) {
  std::vector<std::pair<std::string, int>> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string f = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const std::size_t b = f.find_first_not_of(" \t\r");
    const std::size_t e = f.find_last_not_of(" \t\r");
    const int col = static_cast<int>(start + (b == std::string::npos ? 0 : b)) + 1;
    fields.emplace_back(b == std::string::npos ? "" : f.substr(b, e - b + 1), col);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

/// The columns of a track file, in the order time, x, y, z.
constexpr std::array<const char*, 4> kTrackColumns{"time", "x", "y", "z"};

/// Read a track file's header line: for each of time, x, y, z the index of
/// its field. False after reporting an unknown, repeated or missing name.
bool parse_track_header(const std::string& line, const SourceLoc& at, const std::string& path, Diagnostics& d,
                        std::array<std::size_t, 4>& order) {
  const auto fields = split_csv(line);
  constexpr std::size_t kUnset = static_cast<std::size_t>(-1);
  order.fill(kUnset);
  bool ok = true;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const std::string& name = fields[f].first;  // no structured binding: clang 14 cannot capture one
    const auto col = fields[f].second;
    const SourceLoc here{at.file, at.line, col};
    const auto it = std::find_if(kTrackColumns.begin(), kTrackColumns.end(), [&](const char* c) { return name == c; });
    if (it == kTrackColumns.end()) {
      d.error(here, path, "unknown column '" + name + "' in the track header (expected time, x, y, z)");
      ok = false;
      continue;
    }
    const auto c = static_cast<std::size_t>(it - kTrackColumns.begin());
    if (order[c] != kUnset) {
      d.error(here, path, "column '" + name + "' appears twice in the track header");
      ok = false;
      continue;
    }
    order[c] = f;
  }
  for (std::size_t c = 0; c < order.size() && ok; ++c)
    if (order[c] == kUnset) {
      d.error(at, path,
              std::string("the track header has no column '") + kTrackColumns[c] + "' (expected time, x, y, z)");
      ok = false;
    }
  return ok;
}

/// Parse one data line of a track file into a row {t, x, y, z}, its fields
/// taken in `order` (see parse_track_header); false after reporting.
bool parse_track_line(const std::string& line, const SourceLoc& at, const std::string& path,
                      const std::array<std::size_t, 4>& order, Diagnostics& d, RowSpec& row) {
  const auto fields = split_csv(line);
  if (fields.size() != 4) {
    d.error(at, path, "expected 4 values time,x,y,z (got " + std::to_string(fields.size()) + ")");
    return false;
  }
  std::array<double, 4> values{};
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const auto& [text, col] = fields[f];
    const auto v = scalar_to_double(text);
    if (!v) {
      d.error(SourceLoc{at.file, at.line, col}, path, "expected a number (got '" + text + "')");
      return false;
    }
    values[f] = *v;
  }
  row.values.clear();
  for (const std::size_t f : order) row.values.push_back(values[f]);
  row.where = Where{at, path};
  return true;
}

/// track: exactly one of `file` (CSV, relative to base_dir; a --set one to the current directory) or `points`.
void parse_track(MapReader& r, PieceSpec& p, const std::string& base_dir, Diagnostics& d) {
  const YNode* file = r.get("file");
  const YNode* points = r.get("points");
  if ((file == nullptr) == (points == nullptr)) {
    d.error(p.where.loc, p.where.path, "a track needs exactly one of 'file' or 'points'");
    return;
  }
  if (points != nullptr) {
    p.track_where = r.where(*points, "points");
    if (!read_table(*points, p.track_where.path, 4, d, p.track)) p.track.clear();
    return;
  }
  p.track_where = r.where(*file, "file");
  std::string name;
  if (!convert(*file, p.track_where.path, d, name)) return;
  p.track = read_track_csv(resolve_file(name, *file, base_dir), p.track_where, d);
}

void parse_piece(MapReader& r, PieceSpec& p, const std::string& base_dir, Diagnostics& d) {
  p.where = r.where();
  r.choice("type", p.type, {"ramp", "heave", "turn", "speed", "track"}, true);
  const std::string& t = p.type.value;
  if (t == "ramp") {
    r.read("direction", p.direction, true);
    r.read_speed("speed", p.speed, true);
    r.read("ramp_time", p.ramp_time, true);
  } else if (t == "heave") {
    r.read("amplitude", p.amplitude, true);
    r.read("period", p.period, true);
    r.read("start_time", p.start_time);
  } else if (t == "turn") {
    r.read("radius", p.radius, true);
    r.read("start_time", p.start_time);
    r.choice("side", p.side, {"port", "starboard"});
    r.read("angle_deg", p.angle_deg);
  } else if (t == "speed") {
    r.read_speed("speed", p.speed, true);
    r.read("start_time", p.start_time);
    r.read("ramp_time", p.ramp_time, true);
  } else if (t == "track") {
    parse_track(r, p, base_dir, d);
    r.read("speed_scale", p.speed_scale);
  }
}

/// force: [Fx, Fy, Fz] (constant) or a table [[t, Fx, Fy, Fz], ...].
void parse_force(MapReader& r, TowSpec& tow, Diagnostics& d) {
  const YNode* n = r.get("force");
  if (n == nullptr) return;
  tow.force_given = true;
  tow.force_where = r.where(*n, "force");
  if (n->is_seq() && !n->items.empty() && n->items[0].is_seq()) {
    if (!read_table(*n, tow.force_where.path, 4, d, tow.force)) tow.force.clear();
    return;
  }
  Vec3 f;
  if (convert(*n, tow.force_where.path, d, f))
    tow.force.push_back(RowSpec{{0.0, f.x(), f.y(), f.z()}, tow.force_where});
}

}  // namespace

std::vector<RowSpec> read_track_csv(const std::string& file, const Where& where, Diagnostics& d) {
  std::vector<RowSpec> rows;
  // Only regular files: a device or a FIFO (e.g. /dev/zero) could be endless.
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    d.error(where.loc, where.path, "the track file '" + file + "' is not a regular file");
    return rows;
  }
  std::ifstream in(file);
  if (!in) {
    d.error(where.loc, where.path, "cannot open the track file '" + file + "'");
    return rows;
  }
  const std::size_t errors_before = d.size();
  std::string line;
  int lineno = 0;
  bool first = true;
  std::array<std::size_t, 4> order{0, 1, 2, 3};  // without a header: time, x, y, z
  while (std::getline(in, line)) {
    ++lineno;
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    // A first line that does not start with a number is the header: columns by name.
    const bool header = first && !scalar_to_double(split_csv(line)[0].first);
    first = false;
    if (header) {
      if (!parse_track_header(line, SourceLoc{file, lineno, 1}, where.path, d, order)) return {};
      continue;
    }
    RowSpec row;
    if (parse_track_line(line, SourceLoc{file, lineno, 1}, where.path, order, d, row)) rows.push_back(row);
  }
  if (d.size() != errors_before) return {};  // reported: no further checks on a partial track
  if (rows.empty()) d.error(SourceLoc{file, std::max(lineno, 1), 1}, where.path, "the track file has no data rows");
  return rows;
}

void parse_tow(MapReader& r, TowSpec& tow, const std::string& base_dir, Diagnostics& d) {
  tow.where = r.where();
  r.choice("mode", tow.mode, {"motion", "force"});
  r.read("start", tow.start);
  r.list("motion", [&](MapReader& item, std::size_t) {
    tow.motion.emplace_back();
    parse_piece(item, tow.motion.back(), base_dir, d);
  });
  parse_force(r, tow, d);
}

}  // namespace towsim::scenario
