// Internal helpers turning YNode values into typed spec fields, reporting
// type errors, missing keys and unknown keys (with a "did you mean" hint).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "towsim/scenario/spec.hpp"
#include "towsim/scenario/yaml_tree.hpp"

namespace towsim::scenario {

/// "a.b" + "c" -> "a.b.c"; "" + "c" -> "c".
std::string join_path(const std::string& parent, const std::string& key);

/// The path a file key names: as written when absolute or given with --set
/// (relative to the current directory, like any command-line path), else
/// relative to base_dir (the scenario file's folder).
std::string resolve_file(const std::string& name, const YNode& node, const std::string& base_dir);

/// Read a finite number; report "expected a number (got ...)" otherwise.
bool convert(const YNode& n, const std::string& path, Diagnostics& d, double& out);
/// Read an integer.
bool convert(const YNode& n, const std::string& path, Diagnostics& d, long long& out);
/// Read true/false.
bool convert(const YNode& n, const std::string& path, Diagnostics& d, bool& out);
/// Read a single scalar as text.
bool convert(const YNode& n, const std::string& path, Diagnostics& d, std::string& out);
/// Read [x, y, z].
bool convert(const YNode& n, const std::string& path, Diagnostics& d, Vec3& out);
/// Read [a, b, c] (diagonal) or a 3x3 list of rows.
bool convert(const YNode& n, const std::string& path, Diagnostics& d, Mat3& out);
/// Read 6 numbers (diagonal) or a 6x6 list of rows.
bool convert(const YNode& n, const std::string& path, Diagnostics& d, Mat6& out);

/// Read a table: a list of rows of exactly `width` numbers each.
bool read_table(const YNode& n, const std::string& path, std::size_t width, Diagnostics& d, std::vector<RowSpec>& rows);

/// Reads the keys of one mapping, remembers which keys are known, and reports
/// the others as unknown in finish().
class MapReader {
 public:
  /// `node` null: an absent section (every key absent, no "missing" reports).
  /// A non-null node that is not a mapping is reported and read as absent.
  MapReader(const YNode* node, std::string path, Diagnostics& d);

  /// The dotted path of `key` in this mapping.
  std::string sub(const std::string& key) const { return join_path(path_, key); }
  /// Mark `key` as known; its non-null value or nullptr (reported if required).
  const YNode* get(const std::string& key, bool required = false);
  /// True when `key` has a non-null value (does not mark it known).
  bool has(const std::string& key) const {
    const YNode* v = node_ == nullptr ? nullptr : node_->find(key);
    return v != nullptr && !v->is_null();
  }
  /// Where `key`'s value is.
  Where where(const YNode& value, const std::string& key) const { return {value.loc, sub(key)}; }
  /// Where this mapping is.
  Where where() const;
  /// True when the section exists as a mapping.
  bool present() const { return node_ != nullptr; }

  /// Read a typed field (number, integer, bool, text, vector, matrix).
  template <class T>
  void read(const std::string& key, Field<T>& f, bool required = false) {
    const YNode* v = get(key, required);
    if (v == nullptr) return;
    f.where = where(*v, key);
    T tmp{};
    if (convert(*v, f.where.path, d_, tmp)) {
      f.value = tmp;
      f.given = true;
    }
  }
  /// Read a speed [m/s] given as `key` (m/s) or `key`_kn (knots, 1 kn =
  /// 1852/3600 m/s exactly); both is an error.
  void read_speed(const std::string& key, Field<double>& f, bool required = false);
  /// The value of an accepted alias key (a `_kn` form) that "expected one
  /// of" does not list, or nullptr when absent.
  const YNode* alias(const std::string& key);
  /// Read a text field that must be one of `choices`.
  void choice(const std::string& key, Field<std::string>& f, const std::vector<std::string>& choices,
              bool required = false);
  /// Read a list of mappings, calling `each(reader, index)` for every item.
  void list(const std::string& key, const std::function<void(MapReader&, std::size_t)>& each);
  /// Report every key that was never asked for.
  void finish();

 private:
  const YNode* node_;
  std::string path_;
  Diagnostics& d_;
  std::vector<std::string> known_;
  std::vector<std::string> aliases_;  // accepted keys not listed in "expected one of" (`_kn`)
};

/// Knots to metres per second: 1 kn = 1852 m / 3600 s exactly [m/s].
inline double knots_to_mps(double kn) { return kn * 1852.0 / 3600.0; }

/// Report `got` unless it is one of `choices` (with a "did you mean" hint).
bool check_choice(const std::string& got, const std::vector<std::string>& choices, const Where& w, Diagnostics& d);

}  // namespace towsim::scenario
