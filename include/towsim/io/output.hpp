// Run outputs (INTERFACE.md): timeseries.csv, nodes.csv, summary.json.
#pragma once

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/sim/simulate.hpp"

namespace towsim::io {

/// A maximum (or minimum) over the run and the time it was reached.
struct Extreme {
  double value = std::numeric_limits<double>::quiet_NaN();
  double time = std::numeric_limits<double>::quiet_NaN();
  /// Keep (v, t) when v > value (or the first time).
  void max(double v, double t);
  /// Keep (v, t) when v < value (or the first time).
  void min(double v, double t);
};

/// Extremes over all written samples.
struct Extremes {
  Extreme max_tow_tension;    // |F_R| [N]
  Extreme max_cable_tension;  // largest joint tension anywhere [N]
  Extreme max_end_depth;      // -z of P_n [m]
  Extreme min_axial_force;    // smallest axial force in any joint, < 0 in compression [N]
  Extreme max_link_force;     // |F_L| [N] (body)
  Extreme max_body_depth;     // -z of O_t [m] (body)
  Extreme min_body_deg[3], max_body_deg[3];  // roll, pitch, yaw [deg] (body)
  /// Update with one sample.
  void add(const Sample& s);
};

/// Append a number as the output files write it (12 significant digits, no "-0").
void append_number(std::string& out, double v);

/// The columns of timeseries.csv, in order, for a run with or without a body.
std::vector<std::string> timeseries_columns(bool has_body);

/// Append one sample's timeseries.csv values to `out`, in the order of
/// timeseries_columns() (the files and the Python API both use this).
void timeseries_values(const Sample& s, bool has_body, std::vector<double>& out);

/// The timeseries.csv header for a run with or without a body (no newline).
std::string timeseries_header(bool has_body);

/// The per-joint columns of nodes.csv (after `time,node`): x, y, z, vx, vy, vz, tension, axial_force.
const std::vector<std::string>& node_columns();

/// Append joint k's nodes.csv values of one sample to `out`, in the order of node_columns().
void node_values(const Sample& s, std::size_t k, std::vector<double>& out);

/// A sink that keeps what summary.json needs: the extremes, the number of
/// samples and the last timeseries row. The base of the file writer; used
/// alone where no file is written (sweeps).
class RunRecord : public OutputSink {
 public:
  explicit RunRecord(bool has_body) : has_body_(has_body) {}
  /// Account for one sample.
  void write(const Sample& s) override;
  void flush() override {}
  /// Extremes of the samples written so far.
  const Extremes& extremes() const { return extremes_; }
  /// Number of samples written.
  long samples() const { return samples_; }
  /// The last sample's timeseries values (empty before the first).
  const std::vector<double>& last_row() const { return last_row_; }
  bool has_body() const { return has_body_; }

 private:
  bool has_body_;
  Extremes extremes_;
  long samples_ = 0;
  std::vector<double> last_row_;
};

/// Writes timeseries.csv (and nodes.csv) row by row, each sample's rows
/// complete and flushed to the OS before the next, so that a crash leaves
/// whole rows. Numbers are written with 12 significant digits.
class RunWriter : public RunRecord {
 public:
  /// Create the files in the existing directory `dir` and write their
  /// headers; throws std::runtime_error when a file cannot be created.
  RunWriter(const std::string& dir, bool has_body, bool write_nodes);
  ~RunWriter() override;
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  /// Append the sample's rows and flush them.
  void write(const Sample& s) override;
  /// Flush both files.
  void flush() override;

 private:
  std::FILE* series_ = nullptr;
  std::FILE* nodes_ = nullptr;
  std::string buf_;
  std::vector<double> values_;
};

/// summary.json content: model name, RunStats, extremes, `final` (the last
/// row's values by column name, when `final_row` is not empty), the scenario echo.
nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const Extremes& ex, long samples,
                                    bool has_body, bool write_nodes, const std::vector<double>& final_row = {});

/// Write `summary` as DIR/summary.json (pretty-printed); false on I/O error.
bool write_summary(const std::string& dir, const nlohmann::ordered_json& summary);

}  // namespace towsim::io
