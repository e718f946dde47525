// Reading a run's output files back (for `towsim plot` and `towsim report`):
// nodes.csv is read ONCE, keeping only the rows of the wanted times.
#pragma once

#include <istream>
#include <string>
#include <vector>

namespace towsim::cli {

/// std::getline for towsim's files: a last line without its newline is not
/// read. The writers end every row with one, so such a line is a row cut off
/// by a kill (SIGKILL, power loss) during a write (docs/reliability.md).
bool whole_line(std::istream& in, std::string& line);

/// A CSV file with a header row and numeric cells (NaN where not a number).
struct CsvTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  /// Index of column `name`, -1 when absent.
  int col(const std::string& name) const;
  /// Row r's value in column c (NaN when c < 0 or the row is short).
  double at(std::size_t r, int c) const;
  /// True when the header names column `name`.
  bool has(const std::string& name) const { return col(name) >= 0; }
  /// Row r's value in column `name` (NaN when absent or the row is short).
  double at(std::size_t r, const std::string& name) const { return at(r, col(name)); }
};

/// Read a whole CSV file (timeseries.csv). False with `error` set when it
/// cannot be opened or has no header.
bool read_csv_table(const std::string& path, CsvTable& table, std::string& error);

/// Read only the header of a CSV file into `names`. False with `error` set
/// when it cannot be opened or has no header.
bool read_csv_header(const std::string& path, std::vector<std::string>& names, std::string& error);

/// The nodes of one output time (nodes.csv rows of that time, in node order).
struct NodeFrame {
  double t = 0;                 // [s]
  std::vector<double> x, y, z;  // joint positions [m, R_g]
  std::vector<double> tension;  // [N] (NaN when the file has no tension column)
  /// A network's frame (nodes.csv with a `line` column): the index of each
  /// line's first joint after the first line's, where the node number goes
  /// back to 0 (empty for a chain).
  std::vector<std::size_t> line_starts;
};

/// Read `path` (nodes.csv: header with at least time, node, x, y, z) in one
/// pass and return the frames whose time is in `wanted` (ascending; a row
/// matches a wanted time within 1e-9 relative, as both come from the same
/// writer). Returns false with `error` set when the file cannot be read or
/// lacks a column.
bool read_node_frames(const std::string& path, const std::vector<double>& wanted, std::vector<NodeFrame>& frames,
                      std::string& error);

/// About `count` indices spread evenly over 0..n-1, always with the first and
/// the last (all of them when n <= count).
std::vector<std::size_t> spread_indices(std::size_t n, std::size_t count);

/// Distance along the polyline (x, y, z) from its first point [m].
std::vector<double> arc_lengths(const NodeFrame& f);

}  // namespace towsim::cli
