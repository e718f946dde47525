#include "run_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

namespace towsim::cli {

namespace {

/// The fields of one CSV line, as views (no copies).
void split_views(const std::string& line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t pos = 0;
  while (true) {
    const std::size_t c = line.find(',', pos);
    std::string_view f(line.data() + pos, (c == std::string::npos ? line.size() : c) - pos);
    while (!f.empty() && (f.back() == '\r' || f.back() == ' ')) f.remove_suffix(1);
    while (!f.empty() && f.front() == ' ') f.remove_prefix(1);
    out.push_back(f);
    if (c == std::string::npos) return;
    pos = c + 1;
  }
}

double to_double(std::string_view f) {
  double v = std::nan("");
  const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
  return r.ec == std::errc() ? v : std::nan("");
}

bool same_time(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

/// Open a CSV file and read its header line into `header`; false with a
/// message naming the file when it cannot be opened or is empty.
bool open_csv(const std::string& path, std::ifstream& in, std::string& header, std::string& error) {
  in.open(path);
  if (!in) {
    error = path + ": cannot open it";
    return false;
  }
  if (!whole_line(in, header)) {
    error = path + ": empty file (no header)";
    return false;
  }
  return true;
}

}  // namespace

bool whole_line(std::istream& in, std::string& line) {
  // getline stops at the end of the file without a newline: eof is set then.
  return std::getline(in, line) && !in.eof();
}

int CsvTable::col(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

double CsvTable::at(std::size_t r, int c) const {
  if (c < 0 || r >= rows.size() || static_cast<std::size_t>(c) >= rows[r].size()) return std::nan("");
  return rows[r][static_cast<std::size_t>(c)];
}

bool read_csv_table(const std::string& path, CsvTable& table, std::string& error) {
  table = CsvTable{};
  std::ifstream in;
  std::string line;
  if (!open_csv(path, in, line, error)) return false;
  std::vector<std::string_view> f;
  split_views(line, f);
  for (auto v : f) table.names.emplace_back(v);
  while (whole_line(in, line)) {
    if (line.empty() || line == "\r") continue;
    split_views(line, f);
    std::vector<double> row;
    row.reserve(f.size());
    for (auto v : f) row.push_back(to_double(v));
    table.rows.push_back(std::move(row));
  }
  return true;
}

bool read_csv_header(const std::string& path, std::vector<std::string>& names, std::string& error) {
  names.clear();
  std::ifstream in;
  std::string line;
  if (!open_csv(path, in, line, error)) return false;
  std::vector<std::string_view> f;
  split_views(line, f);
  for (auto v : f) names.emplace_back(v);
  return true;
}

bool read_node_frames(const std::string& path, const std::vector<double>& wanted, std::vector<NodeFrame>& frames,
                      std::string& error) {
  frames.clear();
  std::ifstream in;
  std::string line;
  if (!open_csv(path, in, line, error)) return false;
  std::vector<std::string_view> f;
  split_views(line, f);
  auto col = [&f](const char* name) {
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f[i] == name) return static_cast<int>(i);
    return -1;
  };
  const int ct = col("time"), cx = col("x"), cy = col("y"), cz = col("z"), cT = col("tension"), cn = col("node");
  const bool network = col("line") == 0;  // lines one after the other, each from node 0
  if (ct < 0 || cx < 0 || cy < 0 || cz < 0 || col("node") < 0) {
    error = path + ": no column time, node, x, y or z in its header";
    return false;
  }
  const int last = std::max({ct, cx, cy, cz, cT});
  std::size_t w = 0;  // next wanted time
  double current = std::nan("");
  bool keep = false;
  while (whole_line(in, line) && w <= wanted.size()) {
    if (line.empty() || line == "\r") continue;
    // The time is the first thing to look at: most rows are skipped.
    const std::size_t c0 = ct == 0 ? line.find(',') : std::string::npos;
    double t;
    if (ct == 0) {
      t = to_double(std::string_view(line.data(), c0 == std::string::npos ? line.size() : c0));
    } else {
      split_views(line, f);
      t = static_cast<int>(f.size()) > ct ? to_double(f[static_cast<std::size_t>(ct)]) : std::nan("");
    }
    if (std::isnan(t)) continue;
    if (!(t == current)) {  // a new time block
      current = t;
      if (keep) ++w;
      while (w < wanted.size() && wanted[w] < t && !same_time(t, wanted[w])) ++w;
      keep = w < wanted.size() && same_time(t, wanted[w]);
      if (keep) frames.push_back(NodeFrame{t, {}, {}, {}, {}, {}});
      if (w >= wanted.size()) break;
    }
    if (!keep) continue;
    split_views(line, f);
    if (static_cast<int>(f.size()) <= last && static_cast<int>(f.size()) <= std::max({ct, cx, cy, cz})) continue;
    NodeFrame& fr = frames.back();
    if (network && !fr.x.empty() && static_cast<int>(f.size()) > cn && to_double(f[static_cast<std::size_t>(cn)]) == 0)
      fr.line_starts.push_back(fr.x.size());
    fr.x.push_back(to_double(f[static_cast<std::size_t>(cx)]));
    fr.y.push_back(to_double(f[static_cast<std::size_t>(cy)]));
    fr.z.push_back(to_double(f[static_cast<std::size_t>(cz)]));
    fr.tension.push_back(cT >= 0 && static_cast<int>(f.size()) > cT ? to_double(f[static_cast<std::size_t>(cT)])
                                                                    : std::nan(""));
  }
  return true;
}

std::vector<std::size_t> spread_indices(std::size_t n, std::size_t count) {
  std::vector<std::size_t> out;
  if (n == 0) return out;
  if (n <= count || count < 2) {
    if (count < 2 && n > count) return {n - 1};
    for (std::size_t i = 0; i < n; ++i) out.push_back(i);
    return out;
  }
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(
        std::llround(static_cast<double>(k) * static_cast<double>(n - 1) / static_cast<double>(count - 1)));
    if (out.empty() || i != out.back()) out.push_back(i);
  }
  return out;
}

std::vector<double> arc_lengths(const NodeFrame& f) {
  std::vector<double> s(f.x.size(), 0.0);
  for (std::size_t k = 1; k < f.x.size(); ++k)
    s[k] = s[k - 1] +
           std::sqrt((f.x[k] - f.x[k - 1]) * (f.x[k] - f.x[k - 1]) + (f.y[k] - f.y[k - 1]) * (f.y[k] - f.y[k - 1]) +
                     (f.z[k] - f.z[k - 1]) * (f.z[k] - f.z[k - 1]));
  return s;
}

}  // namespace towsim::cli
