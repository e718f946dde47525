// Reading YAML plain scalars as numbers, booleans or null (YAML 1.2 core schema).
#pragma once

#include <charconv>
#include <cmath>
#include <optional>
#include <string>

namespace towsim::scenario {

/// "true"/"True"/"TRUE" or "false"/... as a bool.
inline std::optional<bool> scalar_to_bool(const std::string& s) {
  if (s == "true" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "False" || s == "FALSE") return false;
  return std::nullopt;
}

/// "null", "Null", "NULL", "~" or "".
inline bool scalar_is_null(const std::string& s) {
  return s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL";
}

/// A decimal integer ("-3", "+40"), or nothing.
inline std::optional<long long> scalar_to_integer(const std::string& s) {
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+') ++b;
  long long v = 0;
  const auto r = std::from_chars(b, e, v);
  if (b == e || r.ec != std::errc{} || r.ptr != e) return std::nullopt;
  return v;
}

/// A finite decimal number ("1", "-0.5", "1e-3", ".5", "+2"), or nothing.
inline std::optional<double> scalar_to_double(const std::string& s) {
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+') ++b;
  double v = 0;
  const auto r = std::from_chars(b, e, v, std::chars_format::general);
  if (b == e || r.ec != std::errc{} || r.ptr != e || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace towsim::scenario
