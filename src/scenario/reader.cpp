#include "reader.hpp"

#include <algorithm>
#include <filesystem>

#include "scalar.hpp"

namespace towsim::scenario {
namespace {

std::string expected(const std::string& what, const YNode& n) {
  return "expected " + what + " (got " + n.describe() + ")";
}

/// Read the items of a list of exactly `count` numbers.
bool read_numbers(const YNode& n, const std::string& path, std::size_t count, Diagnostics& d,
                  std::vector<double>& out) {
  const std::string what = "a list of " + std::to_string(count) + " numbers";
  if (!n.is_seq() || n.items.size() != count) {
    d.error(n.loc, path, expected(what, n));
    return false;
  }
  out.assign(count, 0.0);
  bool ok = true;
  for (std::size_t i = 0; i < count; ++i) ok = convert(n.items[i], join_path(path, std::to_string(i)), d, out[i]) && ok;
  return ok;
}

/// Read a square matrix given as `dim` diagonal numbers or as dim rows of dim numbers.
template <int Dim>
bool read_square(const YNode& n, const std::string& path, Diagnostics& d, Eigen::Matrix<double, Dim, Dim>& out) {
  const std::string dims = std::to_string(Dim);
  if (!n.is_seq() || n.items.size() != static_cast<std::size_t>(Dim)) {
    d.error(n.loc, path, expected("a list of " + dims + " numbers or " + dims + " rows of " + dims, n));
    return false;
  }
  out.setZero();
  std::vector<double> row;
  bool ok = true;
  const bool rows = n.items[0].is_seq();
  for (int i = 0; i < Dim; ++i) {
    const YNode& item = n.items[static_cast<std::size_t>(i)];
    const std::string p = join_path(path, std::to_string(i));
    if (rows) {
      if (!read_numbers(item, p, Dim, d, row)) {
        ok = false;
        continue;
      }
      for (int j = 0; j < Dim; ++j) out(i, j) = row[static_cast<std::size_t>(j)];
    } else {
      ok = convert(item, p, d, out(i, i)) && ok;
    }
  }
  return ok;
}

}  // namespace

std::string resolve_file(const std::string& name, const YNode& node, const std::string& base_dir) {
  const std::filesystem::path fp(name);
  const bool as_is = fp.is_absolute() || base_dir.empty() || node.loc.file == "--set";
  return as_is ? name : (std::filesystem::path(base_dir) / fp).string();
}

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, double& out) {
  if (n.is_scalar()) {
    if (auto v = scalar_to_double(n.scalar)) {
      out = *v;
      return true;
    }
  }
  d.error(n.loc, path, expected("a number", n));
  return false;
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, long long& out) {
  if (n.is_scalar()) {
    if (auto v = scalar_to_integer(n.scalar)) {
      out = *v;
      return true;
    }
  }
  d.error(n.loc, path, expected("an integer", n));
  return false;
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, bool& out) {
  if (n.is_scalar() && !n.quoted) {
    if (auto v = scalar_to_bool(n.scalar)) {
      out = *v;
      return true;
    }
  }
  d.error(n.loc, path, expected("true or false", n));
  return false;
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, std::string& out) {
  if (n.is_scalar()) {
    out = n.scalar;
    return true;
  }
  d.error(n.loc, path, expected("a single value", n));
  return false;
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, Vec3& out) {
  std::vector<double> v;
  if (!read_numbers(n, path, 3, d, v)) return false;
  out = Vec3(v[0], v[1], v[2]);
  return true;
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, Mat3& out) {
  return read_square<3>(n, path, d, out);
}

bool convert(const YNode& n, const std::string& path, Diagnostics& d, Mat6& out) {
  return read_square<6>(n, path, d, out);
}

bool read_table(const YNode& n, const std::string& path, std::size_t width, Diagnostics& d,
                std::vector<RowSpec>& rows) {
  if (!n.is_seq() || n.items.empty()) {
    d.error(n.loc, path, expected("a list of rows of " + std::to_string(width) + " numbers", n));
    return false;
  }
  bool ok = true;
  for (std::size_t i = 0; i < n.items.size(); ++i) {
    RowSpec row;
    row.where = Where{n.items[i].loc, join_path(path, std::to_string(i))};
    if (read_numbers(n.items[i], row.where.path, width, d, row.values))
      rows.push_back(std::move(row));
    else
      ok = false;
  }
  return ok;
}

bool check_choice(const std::string& got, const std::vector<std::string>& choices, const Where& w, Diagnostics& d) {
  for (const auto& c : choices)
    if (c == got) return true;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  std::string msg = "expected one of " + list + " (got '" + got + "'";
  const std::string hint = closest_match(got, choices);
  if (!hint.empty()) msg += "; did you mean '" + hint + "'?";
  d.error(w.loc, w.path, msg + ")");
  return false;
}

MapReader::MapReader(const YNode* node, std::string path, Diagnostics& d) : node_(node), path_(std::move(path)), d_(d) {
  if (node_ != nullptr && !node_->is_map()) {
    d_.error(node_->loc, path_.empty() ? "(root)" : path_, expected("a mapping of keys", *node_));
    node_ = nullptr;
  }
}

Where MapReader::where() const { return Where{node_ != nullptr ? node_->loc : SourceLoc{}, path_}; }

const YNode* MapReader::get(const std::string& key, bool required) {
  bool seen = false;
  for (const auto& k : known_) seen = seen || k == key;
  if (!seen) known_.push_back(key);
  if (node_ == nullptr) return nullptr;
  const YNode* v = node_->find(key);
  if (v != nullptr && !v->is_null()) return v;
  if (required) {
    if (v != nullptr)
      d_.error(v->key_loc, sub(key), "missing value");
    else
      d_.error(node_->key_loc.file.empty() ? node_->loc : node_->key_loc, sub(key), "missing required key");
  }
  return nullptr;
}

void MapReader::read_speed(const std::string& key, Field<double>& f, bool required) {
  const std::string kn = key + "_kn";
  if (std::find(aliases_.begin(), aliases_.end(), kn) == aliases_.end()) aliases_.push_back(kn);
  const YNode* v = node_ != nullptr ? node_->find(kn) : nullptr;
  if (v == nullptr || v->is_null()) {
    read(key, f, required);
    return;
  }
  get(key);  // known, whether given or not
  if (node_->find(key) != nullptr) {
    d_.error(v->key_loc, sub(kn), "give either '" + key + "' or '" + kn + "', not both");
    return;
  }
  f.where = where(*v, kn);
  double value = 0;
  if (convert(*v, f.where.path, d_, value)) {
    f.value = knots_to_mps(value);
    f.given = true;
  }
}

const YNode* MapReader::alias(const std::string& key) {
  if (std::find(aliases_.begin(), aliases_.end(), key) == aliases_.end()) aliases_.push_back(key);
  const YNode* v = node_ != nullptr ? node_->find(key) : nullptr;
  return v == nullptr || v->is_null() ? nullptr : v;
}

void MapReader::choice(const std::string& key, Field<std::string>& f, const std::vector<std::string>& choices,
                       bool required) {
  Field<std::string> tmp = f;
  read(key, tmp, required);
  if (tmp.given && check_choice(tmp.value, choices, tmp.where, d_)) f = tmp;
}

void MapReader::list(const std::string& key, const std::function<void(MapReader&, std::size_t)>& each) {
  const YNode* v = get(key);
  if (v == nullptr) return;
  if (!v->is_seq()) {
    d_.error(v->loc, sub(key), expected("a list", *v));
    return;
  }
  for (std::size_t i = 0; i < v->items.size(); ++i) {
    MapReader item(&v->items[i], join_path(sub(key), std::to_string(i)), d_);
    if (!item.present()) continue;
    each(item, i);
    item.finish();
  }
}

void MapReader::finish() {
  if (node_ == nullptr) return;
  for (std::size_t i = 0; i < node_->items.size(); ++i) {
    const YNode& v = node_->items[i];
    const YNode* first = node_->find(v.key);
    if (first != &v) {
      d_.error(v.key_loc, sub(v.key),
               "duplicate key (first given at line " + std::to_string(first->key_loc.line) + ")");
      continue;
    }
    bool is_known = false;
    for (const auto& k : known_) is_known = is_known || k == v.key;
    for (const auto& k : aliases_) is_known = is_known || k == v.key;
    if (is_known) continue;
    std::vector<std::string> accepted = known_;
    accepted.insert(accepted.end(), aliases_.begin(), aliases_.end());
    const std::string hint = closest_match(v.key, accepted);
    std::string msg = "unknown key";
    if (!hint.empty()) {
      msg += " (did you mean '" + hint + "'?)";
    } else {
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      msg += " (expected one of: " + list + ")";
    }
    d_.error(v.key_loc, sub(v.key), msg);
  }
}

}  // namespace towsim::scenario
