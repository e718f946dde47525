#include "towsim/scenario/yaml_tree.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "scalar.hpp"

namespace towsim::scenario {
namespace {

/// Location of a yaml-cpp mark (0-based) in `file`, shifted by `col_offset` columns.
SourceLoc loc_of(const YAML::Mark& m, const std::string& file, int line_override, int col_offset) {
  if (m.line < 0) return SourceLoc{file, line_override > 0 ? line_override : 0, 0};
  const int line = line_override > 0 ? line_override : m.line + 1;
  return SourceLoc{file, line, m.column + 1 + col_offset};
}

/// Where the source text comes from, for locations.
struct Origin {
  std::string file;
  int line_override = 0;  // --set: the option's rank, used as the line
  int col_offset = 0;     // --set: where VALUE starts in KEY=VALUE
};

/// Most values a document of `bytes` characters may expand to. Aliases are
/// copied into the tree, so a few lines of nested aliases ("billion laughs")
/// could otherwise take all the memory and time there is. Without aliases a
/// document has fewer values than characters, so only alias blow-ups hit it.
std::size_t max_values(std::size_t bytes) { return 1000 + 10 * bytes; }

/// Thrown by convert() past max_values(); `mark` is where it happened.
struct TooManyValues {
  YAML::Mark mark;
};

/// Deepest nesting accepted. A scenario needs about 6 levels; an alias that
/// refers to itself (`a: &a [*a]`) makes a cyclic node, which would otherwise
/// recurse until the stack overflows.
constexpr int kMaxDepth = 64;

/// Largest scenario file read [bytes]: 4 MiB, some 40 000 lines, far beyond a
/// scenario written by hand; its tree then takes at most a few hundred MB.
constexpr std::size_t kMaxFileBytes = std::size_t{4} << 20;

/// Thrown by convert() past kMaxDepth.
struct TooDeep {
  YAML::Mark mark;
};

YNode convert(const YAML::Node& n, const Origin& o, const SourceLoc& fallback, std::size_t& budget, int depth = 0) {
  if (budget == 0) throw TooManyValues{n.Mark()};
  if (depth > kMaxDepth) throw TooDeep{n.Mark()};
  --budget;
  YNode out;
  out.loc = n.Mark().line < 0 ? fallback : loc_of(n.Mark(), o.file, o.line_override, o.col_offset);
  switch (n.Type()) {
    case YAML::NodeType::Scalar:
      out.kind = YNode::Kind::Scalar;
      out.scalar = n.Scalar();
      out.quoted = (n.Tag() == "!");
      break;
    case YAML::NodeType::Sequence:
      out.kind = YNode::Kind::Sequence;
      for (const auto& item : n) out.items.push_back(convert(item, o, out.loc, budget, depth + 1));
      break;
    case YAML::NodeType::Map:
      out.kind = YNode::Kind::Map;
      for (const auto& kv : n) {
        const SourceLoc kl = loc_of(kv.first.Mark(), o.file, o.line_override, o.col_offset);
        // A null value has no useful mark of its own: use its key's.
        YNode v = kv.second.IsNull() ? YNode{} : convert(kv.second, o, kl, budget, depth + 1);
        if (v.is_null()) v.loc = kl;
        v.key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("<complex key>");
        v.key_loc = kl;
        out.items.push_back(std::move(v));
      }
      break;
    default:
      out.kind = YNode::Kind::Null;
  }
  return out;
}

/// The documents of a YAML stream as yaml-cpp's parser reports them, without
/// building them: where the first value of a document after the first one
/// is. yaml-cpp 0.7's LoadAll loops for ever, allocating, on a stream whose
/// next token no node takes (a value starting with ',': ", {"; its issue
/// 1040): such a document starts where the one before it started. That is
/// reported as a syntax error at that character.
class DocumentScan final : public YAML::EventHandler {
 public:
  explicit DocumentScan(const std::string& text) : text_(text) {}
  std::optional<YAML::Mark> later_value;  // the first value of the second or a later document

  void OnDocumentStart(const YAML::Mark& m) override {
    if (documents_ > 0 && m.pos == start_.pos) {
      const char c = m.pos >= 0 && static_cast<std::size_t>(m.pos) < text_.size()
                         ? text_[static_cast<std::size_t>(m.pos)]
                         : ' ';
      throw YAML::ParserException(m,
                                  c > ' ' && c < 0x7f ? std::string("unexpected '") + c + "'" : "unexpected character");
    }
    start_ = m;
    ++documents_;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { value(m); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t, const std::string&) override { value(m); }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    value(m);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    value(m);
  }
  void OnMapEnd() override {}

 private:
  void value(const YAML::Mark& m) {
    if (documents_ > 1 && !later_value) later_value = m;
  }
  const std::string& text_;
  YAML::Mark start_;
  int documents_ = 0;
};

/// The first document of `text` (a null node when empty), after a scan of
/// the whole stream: a later document holding a value sets `later_value`.
YAML::Node first_document(const std::string& text, std::optional<YAML::Mark>& later_value) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentScan scan(text);
  while (parser.HandleNextDocument(scan)) {
  }
  later_value = scan.later_value;
  return YAML::Load(text);
}

/// " (line N is indented with a tab: ...)" when a line up to the error's
/// (0-based `err_line`) has a tab in its indentation, else "".
std::string tab_hint(const std::string& text, int err_line, const Origin& o) {
  std::size_t pos = 0;
  for (int line = 0; line <= err_line && pos <= text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    for (std::size_t i = pos; i < end && (text[i] == ' ' || text[i] == '\t'); ++i)
      if (text[i] == '\t')
        return " (line " + std::to_string(o.line_override > 0 ? o.line_override : line + 1) +
               " is indented with a tab: YAML indentation must use spaces)";
    pos = end + 1;
  }
  return {};
}

/// Parse text with the given origin; syntax errors go to diags.
YNode parse_with_origin(const std::string& text, const Origin& o, Diagnostics& diags, const std::string& err_path) {
  try {
    // One document: what follows a second `---` would be silently ignored.
    std::optional<YAML::Mark> later;
    const YAML::Node n = first_document(text, later);
    if (later) {
      diags.error(loc_of(*later, o.file, o.line_override, o.col_offset), err_path,
                  "a second YAML document (after ---): a scenario is one document");
      return YNode{};
    }
    const SourceLoc start{o.file, o.line_override > 0 ? o.line_override : 1, 1 + o.col_offset};
    std::size_t budget = max_values(text.size());
    return convert(n, o, start, budget);
  } catch (const TooManyValues& e) {
    diags.error(loc_of(e.mark, o.file, o.line_override, o.col_offset), err_path,
                "the document has more than " + std::to_string(max_values(text.size())) +
                    " values (counting each use of an alias)");
    return YNode{};
  } catch (const TooDeep& e) {
    diags.error(loc_of(e.mark, o.file, o.line_override, o.col_offset), err_path,
                "nested more than " + std::to_string(kMaxDepth) + " levels deep (or an alias refers to itself)");
    return YNode{};
  } catch (const YAML::Exception& e) {
    diags.error(loc_of(e.mark, o.file, o.line_override, o.col_offset), err_path,
                "YAML syntax error: " + e.msg + tab_hint(text, e.mark.line, o));
    return YNode{};
  }
}

/// Split a dotted path into its components ("" components are kept, to be reported).
std::vector<std::string> split_path(const std::string& key) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : key) {
    if (c == '.') {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

/// A non-negative list index, or -1.
long parse_index(const std::string& s) {
  long v = -1;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return (r.ec == std::errc{} && r.ptr == s.data() + s.size() && v >= 0) ? v : -1;
}

/// Walk one step of a --set path from `cur`, creating a mapping entry when
/// missing. Returns the child, or nullptr after reporting an error.
YNode* step(YNode* cur, const std::string& part, const std::string& path, const SourceLoc& at, Diagnostics& diags) {
  // Nothing there yet: a list when the key is an index (body.spheres.0.radius
  // on a body without spheres starts the list), else a mapping.
  if (cur->is_null()) cur->kind = parse_index(part) >= 0 ? YNode::Kind::Sequence : YNode::Kind::Map;
  if (cur->is_map()) {
    if (YNode* child = cur->find(part)) return child;
    YNode fresh;
    fresh.key = part;
    fresh.key_loc = at;
    fresh.loc = at;
    cur->items.push_back(std::move(fresh));
    return &cur->items.back();
  }
  if (cur->is_seq()) {
    const long i = parse_index(part);
    if (i < 0 || i > static_cast<long>(cur->items.size())) {
      diags.error(at, path,
                  "no list item " + part + " (the list has " + std::to_string(cur->items.size()) +
                      (cur->items.size() == 1 ? " item" : " items") + "; an index equal to that adds one)");
      return nullptr;
    }
    if (i == static_cast<long>(cur->items.size())) {
      cur->items.emplace_back();
      cur->items.back().loc = at;
    }
    return &cur->items[static_cast<std::size_t>(i)];
  }
  diags.error(at, path, "cannot go into " + cur->describe() + ": it is a single value");
  return nullptr;
}

}  // namespace

const YNode* YNode::find(const std::string& k) const {
  if (!is_map()) return nullptr;
  for (const auto& v : items)
    if (v.key == k) return &v;
  return nullptr;
}

YNode* YNode::find(const std::string& k) { return const_cast<YNode*>(static_cast<const YNode&>(*this).find(k)); }

std::string YNode::describe() const {
  switch (kind) {
    case Kind::Scalar:
      return "'" + scalar + "'";
    case Kind::Sequence:
      return "a list of " + std::to_string(items.size());
    case Kind::Map:
      return "a mapping";
    default:
      return "nothing";
  }
}

YNode parse_yaml(const std::string& text, const std::string& file, Diagnostics& diags) {
  return parse_with_origin(text, Origin{file, 0, 0}, diags, "(yaml)");
}

YNode load_yaml_file(const std::string& path, Diagnostics& diags) {
  const SourceLoc at{path, 0, 0};
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    diags.error(at, "(file)", "is a directory, not a scenario file");
    return YNode{};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diags.error(at, "(file)", std::string("cannot open the file (") + std::strerror(errno) + ")");
    return YNode{};
  }
  // At most kMaxFileBytes, read in chunks: a device or a pipe (/dev/zero) may
  // have no end, and the tree costs ~100 times the text's size in memory.
  std::string text;
  std::array<char, 65536> chunk{};
  while (in && text.size() <= kMaxFileBytes) {
    in.read(chunk.data(), chunk.size());
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (text.size() > kMaxFileBytes) {
    diags.error(at, "(file)",
                "larger than " + std::to_string(kMaxFileBytes / (1024 * 1024)) +
                    " MiB (give long tables, such as tracks and vessel motions, as CSV files)");
    return YNode{};
  }
  return parse_yaml(text, path, diags);
}

void apply_set(YNode& root, const std::string& assignment, int rank, Diagnostics& diags) {
  const SourceLoc at{"--set", rank, 1};
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    diags.error(at, eq == 0 ? "(key)" : assignment, "expected KEY=VALUE (e.g. cable.elements=40)");
    return;
  }
  const std::string key = assignment.substr(0, eq);
  const auto parts = split_path(key);
  std::string path;
  YNode* cur = &root;
  YNode* parent = nullptr;  // the mapping or list that holds cur
  for (const auto& part : parts) {
    path += (path.empty() ? "" : ".") + part;
    if (part.empty()) {
      diags.error(at, key, "empty component in the key path");
      return;
    }
    parent = cur;
    cur = step(cur, part, path, at, diags);
    if (cur == nullptr) return;
  }
  const Origin o{"--set", rank, static_cast<int>(eq) + 1};
  Diagnostics local;
  YNode value = parse_with_origin(assignment.substr(eq + 1), o, local, key);
  for (const auto& d : local.list()) diags.error(d.loc, d.path, d.message);
  if (!local.ok()) return;
  value.key = cur->key;
  value.key_loc = cur->key_loc;
  if (value.is_null()) value.loc = SourceLoc{"--set", rank, static_cast<int>(eq) + 2};
  *cur = std::move(value);
  // A key and its `_kn` twin (the same speed in knots) name one value: the
  // override replaces both.
  if (parent != nullptr && parent->is_map()) {
    const std::string& k = parts.back();
    const std::string twin = k.size() > 3 && k.compare(k.size() - 3, 3, "_kn") == 0 ? k.substr(0, k.size() - 3)
                                                                                    : k + "_kn";
    auto& items = parent->items;
    items.erase(std::remove_if(items.begin(), items.end(), [&](const YNode& v) { return v.key == twin; }), items.end());
  }
}

nlohmann::ordered_json to_json(const YNode& node) {
  using J = nlohmann::ordered_json;
  switch (node.kind) {
    case YNode::Kind::Scalar: {
      if (node.quoted) return node.scalar;
      if (auto b = scalar_to_bool(node.scalar)) return *b;
      if (scalar_is_null(node.scalar)) return nullptr;
      if (auto i = scalar_to_integer(node.scalar)) return *i;
      if (auto d = scalar_to_double(node.scalar)) return *d;
      return node.scalar;
    }
    case YNode::Kind::Sequence: {
      J arr = J::array();
      for (const auto& it : node.items) arr.push_back(to_json(it));
      return arr;
    }
    case YNode::Kind::Map: {
      J obj = J::object();
      for (const auto& it : node.items) obj[it.key] = to_json(it);
      return obj;
    }
    default:
      return nullptr;
  }
}

}  // namespace towsim::scenario
