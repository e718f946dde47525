// Reading winch: (docs/scenario.md "winch").
#include <optional>
#include <utility>

#include "parse_sections.hpp"
#include "scalar.hpp"

namespace towsim::scenario {

namespace {

/// A number (constant, one row at t = 0) or a table [[t, value], ...].
void read_number_or_table(MapReader& r, const YNode* n, const std::string& key, bool& given, Where& where,
                          std::vector<RowSpec>& rows, bool table_only, Diagnostics& d) {
  if (n == nullptr) return;
  given = true;
  where = r.where(*n, key);
  if (n->is_seq()) {
    if (!read_table(*n, where.path, 2, d, rows)) rows.clear();
    return;
  }
  if (table_only) {
    d.error(n->loc, where.path, "expected a table [[t, value], ...] (got " + n->describe() + ")");
    return;
  }
  // A scalar that is not a number: say that a table is accepted too.
  const std::optional<double> v = n->is_scalar() ? scalar_to_double(n->scalar) : std::nullopt;
  if (!v) {
    d.error(n->loc, where.path, "expected a number or a table [[t, value], ...] (got " + n->describe() + ")");
    return;
  }
  rows.push_back(RowSpec{{0.0, *v}, where});
}

}  // namespace

void parse_winch(MapReader& r, WinchSpec& w, Diagnostics& d) {
  w.where = r.where();
  read_number_or_table(r, r.get("rate"), "rate", w.rate_given, w.rate_where, w.rate, false, d);
  // The pay-out speed in knots (any speed key: `<key>_kn`), converted to m/s.
  bool kn_given = false;
  Where kn_where;
  std::vector<RowSpec> kn_rows;
  read_number_or_table(r, r.alias("rate_kn"), "rate_kn", kn_given, kn_where, kn_rows, false, d);
  if (kn_given && w.rate_given) {
    d.error(kn_where.loc, kn_where.path, "give either 'rate' or 'rate_kn', not both");
  } else if (kn_given) {
    for (RowSpec& row : kn_rows)
      if (row.values.size() == 2) row.values[1] = knots_to_mps(row.values[1]);
    w.rate_given = true;
    w.rate_where = kn_where;
    w.rate = std::move(kn_rows);
  }
  read_number_or_table(r, r.get("length"), "length", w.length_given, w.length_where, w.length, true, d);
  r.read("tension", w.tension);
  r.read_speed("max_speed", w.max_speed);
  r.read("max_acceleration", w.max_acceleration);
  r.read("min_length", w.min_length);
  r.read("max_length", w.max_length);
  r.read("drum_inertia", w.drum_inertia);
  r.read("damping", w.damping);
  r.read("rating", w.rating);
  r.read("split_at", w.split_at);
  r.read("remove_at", w.remove_at);
}

}  // namespace towsim::scenario
