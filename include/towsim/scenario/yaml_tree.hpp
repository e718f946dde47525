// A YAML document as a plain tree that remembers where every key and value
// was written (file or --set option, line, column). Built with yaml-cpp.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/scenario/diagnostics.hpp"

namespace towsim::scenario {

/// One YAML node: null, scalar, sequence or mapping, with its location.
struct YNode {
  enum class Kind { Null, Scalar, Sequence, Map };
  Kind kind = Kind::Null;
  std::string scalar;        // Scalar: the text as written (without quotes)
  bool quoted = false;       // Scalar: written in quotes (always a string)
  std::vector<YNode> items;  // Sequence: the items; Map: the values, in file order
  std::string key;           // when this node is a value in a Map: its key
  SourceLoc key_loc;         // ... and where that key is written
  SourceLoc loc;             // where the value starts

  bool is_null() const { return kind == Kind::Null; }
  bool is_scalar() const { return kind == Kind::Scalar; }
  bool is_seq() const { return kind == Kind::Sequence; }
  bool is_map() const { return kind == Kind::Map; }
  /// Map: the first value with this key, or nullptr.
  const YNode* find(const std::string& key) const;
  /// Map: the first value with this key, or nullptr.
  YNode* find(const std::string& key);
  /// A short description for messages: "'text'", "a list", "a mapping", "nothing".
  std::string describe() const;
};

/// Parse YAML text. `file` names the source in locations. A syntax error is
/// reported (path "(yaml)") and gives a Null tree.
YNode parse_yaml(const std::string& text, const std::string& file, Diagnostics& diags);

/// Read and parse a YAML file; an unreadable file is reported (path "(file)").
YNode load_yaml_file(const std::string& path, Diagnostics& diags);

/// Apply one `--set KEY=VALUE` override to `root`: KEY is a dotted path (a
/// number indexes a list, e.g. body.spheres.0.radius), VALUE is parsed as
/// YAML (e.g. 0.005, [0,0,10], {law: skin}). Missing mappings on the way are
/// created. `rank` (1-based) is the option's rank among the --set options;
/// locations of the new nodes are "--set:rank:column". Errors go to `diags`.
void apply_set(YNode& root, const std::string& assignment, int rank, Diagnostics& diags);

/// The tree as JSON: plain scalars become numbers, booleans or null when they
/// read as such, quoted scalars stay strings; mappings keep their order.
nlohmann::ordered_json to_json(const YNode& node);

}  // namespace towsim::scenario
