// Parsing `waves:` and `vessel:` (INTERFACE.md "Ship motion from waves").
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "parse_sections.hpp"
#include "scalar.hpp"

namespace towsim::scenario {
namespace {

const std::vector<std::string> kDofs = {"surge", "sway", "heave", "roll", "pitch", "yaw"};

/// Split a CSV line at commas: (text, 1-based column) per field.
std::vector<std::pair<std::string, int>> split_fields(const std::string& line) {
  std::vector<std::pair<std::string, int>> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string f = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const std::size_t b = f.find_first_not_of(" \t\r"), e = f.find_last_not_of(" \t\r");
    out.emplace_back(b == std::string::npos ? "" : f.substr(b, e - b + 1),
                     static_cast<int>(start + (b == std::string::npos ? 0 : b)) + 1);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// One RAO row from its five texts; false after reporting.
bool rao_row(const std::vector<std::pair<std::string, int>>& f, const SourceLoc& at, const std::string& path,
             Diagnostics& d, RaoRowSpec& row) {
  if (f.size() != 5) {
    d.error(at, path,
            "expected 5 values period,heading_deg,dof,amplitude,phase_deg (got " + std::to_string(f.size()) + ")");
    return false;
  }
  double v[5] = {0, 0, 0, 0, 0};
  for (int i : {0, 1, 3, 4}) {
    const auto x = scalar_to_double(f[static_cast<std::size_t>(i)].first);
    if (!x) {
      d.error(SourceLoc{at.file, at.line, f[static_cast<std::size_t>(i)].second}, path,
              "expected a number (got '" + f[static_cast<std::size_t>(i)].first + "')");
      return false;
    }
    v[i] = *x;
  }
  std::string dof = f[2].first;
  std::transform(dof.begin(), dof.end(), dof.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto it = std::find(kDofs.begin(), kDofs.end(), dof);
  if (it == kDofs.end()) {
    d.error(SourceLoc{at.file, at.line, f[2].second}, path,
            "unknown dof '" + dof + "' (expected surge, sway, heave, roll, pitch or yaw)");
    return false;
  }
  row = RaoRowSpec{v[0], v[1], v[3], v[4], static_cast<int>(it - kDofs.begin()), Where{at, path}};
  return true;
}

/// Read a CSV file of `width` columns (a header line and '#' comments
/// skipped); each data line goes to `each` with its fields and location.
void read_csv(const std::string& file, const Where& where, const std::string& what, Diagnostics& d,
              const std::function<void(const std::vector<std::pair<std::string, int>>&, const SourceLoc&)>& each) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    d.error(where.loc, where.path, "the " + what + " file '" + file + "' is not a regular file");
    return;
  }
  std::ifstream in(file);
  if (!in) {
    d.error(where.loc, where.path, "cannot open the " + what + " file '" + file + "'");
    return;
  }
  std::string line;
  int lineno = 0, rows = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++lineno;
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    const auto fields = split_fields(line);
    const bool header = first && !scalar_to_double(fields[0].first);
    first = false;
    if (header) continue;
    ++rows;
    each(fields, SourceLoc{file, lineno, 1});
  }
  if (rows == 0) d.error(SourceLoc{file, std::max(lineno, 1), 1}, where.path, "the " + what + " file has no data rows");
}

}  // namespace

void parse_waves(MapReader& r, WavesSpec& w, Diagnostics& d) {
  w.where = r.where();
  const YNode* reg = r.get("regular");
  const YNode* spec = r.get("spectrum");
  r.read("water_depth", w.water_depth);
  r.read("statistics_start", w.statistics_start);
  r.read("ramp_time", w.ramp_time);
  r.choice("stretching", w.stretching, {"none", "wheeler"});
  if ((reg == nullptr) == (spec == nullptr)) {
    d.error(w.where.loc, w.where.path.empty() ? "waves" : w.where.path, "give exactly one of 'regular' or 'spectrum'");
    return;
  }
  w.regular = reg != nullptr;
  w.kind_where = r.where(w.regular ? *reg : *spec, w.regular ? "regular" : "spectrum");
  MapReader k(w.regular ? reg : spec, w.kind_where.path, d);
  if (w.regular) {
    k.read("height", w.height, true);
    k.read("period", w.period, true);
  } else {
    k.choice("type", w.type, {"jonswap", "pierson_moskowitz"}, true);
    k.read("hs", w.hs, true);
    k.read("tp", w.tp, true);
    if (w.type.value != "pierson_moskowitz") k.read("gamma", w.gamma);
    k.read("components", w.components);
    k.read("seed", w.seed);
    k.read("spreading", w.spreading);
  }
  k.read("heading_deg", w.heading_deg);
  k.finish();
}

void parse_vessel(MapReader& r, VesselSpec& v, const std::string& base_dir, Diagnostics& d) {
  v.where = r.where();
  r.read("tow_point", v.tow_point);
  r.choice("rotations", v.rotations, {"small_angle", "exact"});
  if (const YNode* n = r.get("raos")) {
    v.raos_given = true;
    v.raos_where = r.where(*n, "raos");
    const std::string& path = v.raos_where.path;
    const std::size_t before = d.size();
    if (n->is_seq()) {  // inline rows [period, heading_deg, dof, amplitude, phase_deg]
      for (std::size_t i = 0; i < n->items.size(); ++i) {
        const YNode& row = n->items[i];
        const std::string rp = join_path(path, std::to_string(i));
        if (!row.is_seq() ||
            !std::all_of(row.items.begin(), row.items.end(), [](const YNode& c) { return c.is_scalar(); })) {
          d.error(row.loc, rp,
                  "expected a row [period, heading_deg, dof, amplitude, phase_deg] (got " + row.describe() + ")");
          continue;
        }
        std::vector<std::pair<std::string, int>> f;
        for (const auto& c : row.items) f.emplace_back(c.scalar, c.loc.col);
        RaoRowSpec out;
        if (rao_row(f, row.loc, rp, d, out)) v.raos.push_back(out);
      }
      if (n->items.empty()) d.error(n->loc, path, "the RAO table has no rows");
    } else {
      std::string name;
      if (convert(*n, path, d, name))
        read_csv(resolve_file(name, *n, base_dir), v.raos_where, "RAO", d, [&](const auto& f, const SourceLoc& at) {
          RaoRowSpec out;
          if (rao_row(f, at, path, d, out)) v.raos.push_back(out);
        });
    }
    if (d.size() != before) v.raos.clear();  // reported: no grid checks on a partial table
  }
  if (const YNode* n = r.get("motions")) {
    v.motions_given = true;
    v.motions_where = r.where(*n, "motions");
    const std::string& path = v.motions_where.path;
    const std::size_t before = d.size();
    std::string name;
    if (convert(*n, path, d, name))
      read_csv(resolve_file(name, *n, base_dir), v.motions_where, "motion", d, [&](const auto& f, const SourceLoc& at) {
        if (f.size() != 7) {
          d.error(at, path,
                  "expected 7 values time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg (got " +
                      std::to_string(f.size()) + ")");
          return;
        }
        RowSpec row{{}, Where{at, path}};
        for (const auto& [text, col] : f) {
          const auto x = scalar_to_double(text);
          if (!x) {
            d.error(SourceLoc{at.file, at.line, col}, path, "expected a number (got '" + text + "')");
            return;
          }
          row.values.push_back(*x);
        }
        v.motions.push_back(row);
      });
    if (d.size() != before) v.motions.clear();
  }
}

}  // namespace towsim::scenario
