// A network run's files (docs/scenario.md "Networks", "Output files"):
// timeseries.csv with each line's, body's and junction's columns by name,
// nodes.csv with the line as its first column, and summary.json's figures
// per line and per body.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "towsim/output/output.hpp"
#include "towsim/output/row_file.hpp"
#include "towsim/sim/simulate_network.hpp"

namespace towsim::output {

/// The columns of a network's timeseries.csv, in order: time; per line
/// (tree order) <line>_top_x/y/z, <line>_top_force_x/y/z, <line>_top_tension,
/// <line>_end_x/y/z, <line>_end_depth, <line>_deployed_length (a line with
/// a winch: <line>_payout_speed); per body
/// <body>_x/y/z, _roll_deg, _pitch_deg, _yaw_deg, _depth, _link_force_x/y/z,
/// _link_tension (in-line bodies also _lower_link_force_x/y/z,
/// _lower_link_tension); per junction <junction>_x/y/z, _depth; with waves
/// wave_elevation; with a seabed per line <line>_contact_length, <line>_lying_length.
std::vector<std::string> network_timeseries_columns(const Network& net);
/// One sample's values in the order of network_timeseries_columns (not tidied; the time tidied).
void network_timeseries_values(const Network& net, const NetworkSample& s, std::vector<double>& v);
/// The per-node columns of a network's nodes.csv after `line,time,node`
/// (and `node_id` when a line has a winch): node_columns(), then
/// utilisation, seabed_force, bending_moment where a line has them.
std::vector<std::string> network_node_columns(const Network& net);
/// Joint k of a line's sample in the columns of network_node_columns, appended to `values`.
void network_node_values(const Network& net, const Sample& line, std::size_t k, std::vector<double>& values);

/// A network sink that keeps what summary.json needs: each line's extremes,
/// the number of samples and the last row.
class NetworkRecord : public NetworkSink {
 public:
  explicit NetworkRecord(const Network& net);
  void write(const NetworkSample& s) override;
  void flush() override {}
  const Network& network() const { return net_; }
  /// Per line: the extremes of its samples (its top is its "tow point").
  const std::vector<Extremes>& extremes() const { return extremes_; }
  long samples() const { return samples_; }
  /// The last row by column name (null before any row).
  nlohmann::ordered_json final_row() const;
  /// The last row as written: every value tidied but the time (as RunRecord::last_row).
  std::vector<double> last_row() const;

 protected:
  /// The last row before tidy (the time tidied).
  const std::vector<double>& raw_row() const { return row_; }

 private:
  const Network& net_;
  std::vector<Extremes> extremes_;
  long samples_ = 0;
  std::vector<double> row_;  // the last row before tidy (time tidied)
};

/// Writes a network's timeseries.csv (and nodes.csv) in DIR.
class NetworkWriter : public NetworkRecord {
 public:
  /// Create the files and write their headers; throws std::runtime_error when one cannot be created.
  NetworkWriter(const std::string& dir, const Network& net, bool write_nodes);
  ~NetworkWriter() override;
  NetworkWriter(const NetworkWriter&) = delete;
  NetworkWriter& operator=(const NetworkWriter&) = delete;
  void write(const NetworkSample& s) override;
  void flush() override;
  /// "" while every row went to the disk; else the first file's failure.
  std::string error() const;

 private:
  std::unique_ptr<RowFile> series_, nodes_;
  std::string series_buf_, nodes_buf_;
  std::vector<double> values_;
};

/// summary.json of a network run: run_json's part, then per line
/// max_<line>_top_tension and max_<line>_cable_tension, per body its depth,
/// link force and attitude extremes, `final`, the scenario echo.
nlohmann::ordered_json make_network_summary(const nlohmann::ordered_json& scenario, const RunStats& stats,
                                            const NetworkRecord& record, bool write_nodes);

}  // namespace towsim::output
