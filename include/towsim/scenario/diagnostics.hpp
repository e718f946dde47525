// Input errors with their source location, in the compiler style
// "FILE:LINE:COL: KEY.PATH: problem" (one per line).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace towsim::scenario {

/// A position in an input: a file name (or "--set"), 1-based line and column.
/// For a `--set` option, LINE is its rank among the --set options (1 = first)
/// and COL the column in its KEY=VALUE text. 0 means unknown.
struct SourceLoc {
  std::string file;
  int line = 0;
  int col = 0;
};

/// One input error: where it is, which key, what is wrong.
struct Diagnostic {
  SourceLoc loc;
  std::string path;     // dotted key path, e.g. "cable.diameter" or "body.spheres.0.radius"
  std::string message;  // e.g. "must be > 0 (got -0.01)"

  /// The error as "FILE:LINE:COL: KEY.PATH: problem".
  std::string str() const;
};

/// Collects every error found while reading and checking a scenario, so that
/// all of them can be reported at once.
class Diagnostics {
 public:
  /// Record one error.
  void error(const SourceLoc& loc, const std::string& path, const std::string& message);
  /// True when no error was recorded.
  bool ok() const { return list_.empty(); }
  /// Number of errors recorded.
  std::size_t size() const { return list_.size(); }
  /// The errors in the order they were found.
  const std::vector<Diagnostic>& list() const { return list_; }
  /// All errors, one per line (each ending in '\n'), ordered by file (the
  /// primary file first, then others in order of first appearance, --set
  /// options last), then line, then column.
  std::string str() const;
  /// Name the main input file, listed first by str().
  void set_primary(const std::string& file) { primary_ = file; }
  const std::string& primary() const { return primary_; }

 private:
  std::vector<Diagnostic> list_;
  std::string primary_;
};

/// Levenshtein edit distance between two strings (insert, delete, substitute).
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The candidate closest to `word` when it is close enough to be a likely
/// typo (distance <= 2, or <= a third of the word's length), or the shortest
/// candidate that extends it (a word of 3+ characters); "" otherwise.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

/// A number as written in messages and outputs ("%.10g").
std::string fmt_num(double v);

}  // namespace towsim::scenario
