#include "towsim/scenario/diagnostics.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>

namespace towsim::scenario {

namespace {

/// Control bytes (quoted from a binary file) as \xNN: they would act on the terminal.
std::string printable(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\t') || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string Diagnostic::str() const {
  return printable(loc.file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col) + ": " + path + ": " +
                   message);
}

void Diagnostics::error(const SourceLoc& loc, const std::string& path, const std::string& message) {
  list_.push_back(Diagnostic{loc, path, message});
}

std::string Diagnostics::str() const {
  // Files in order of first appearance, the --set options last.
  std::map<std::string, std::size_t> rank;
  rank.emplace(primary_, 0);
  for (const auto& d : list_) rank.emplace(d.loc.file, d.loc.file == "--set" ? list_.size() + 1 : rank.size());
  std::vector<const Diagnostic*> sorted;
  for (const auto& d : list_) sorted.push_back(&d);
  std::stable_sort(sorted.begin(), sorted.end(), [&](const Diagnostic* a, const Diagnostic* b) {
    const auto ka = std::make_tuple(rank.at(a->loc.file), a->loc.line, a->loc.col);
    const auto kb = std::make_tuple(rank.at(b->loc.file), b->loc.line, b->loc.col);
    return ka < kb;
  });
  std::string out;
  for (const auto* d : sorted) out += d->str() + "\n";
  return out;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const std::size_t cost = (a[i - 1] == b[j - 1]) ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + cost});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  std::string shortest_extension;  // a candidate that starts with the word ("paper-3d" -> "paper-3d-turn")
  for (const auto& c : candidates)
    if (word.size() >= 3 && c.size() > word.size() && c.compare(0, word.size(), word) == 0 &&
        (shortest_extension.empty() || c.size() < shortest_extension.size()))
      shortest_extension = c;
  if (!shortest_extension.empty()) return shortest_extension;
  std::string best;
  std::size_t best_d = static_cast<std::size_t>(-1);
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  const bool close = best_d <= 2 || 3 * best_d <= word.size();
  return (close && best_d < std::max(word.size(), best.size())) ? best : std::string{};
}

std::string fmt_num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace towsim::scenario
