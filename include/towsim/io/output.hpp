// Run outputs (INTERFACE.md): timeseries.csv, nodes.csv, summary.json.
//
// Number format (docs/scenario.md "Number format"): a magnitude below
// kZeroBelow is written as 0 (round-off where 0 is meant, e.g. 1.6e-145);
// other values with 12 significant digits in the shortest form that reads
// back to them; times rounded to the nanosecond first (k * 0.1 s is written
// 7088.4, not 7088.400000000001). summary.json holds the same values.
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
  Extreme min_depth, max_depth;  // -z of the body origin, or of P_n without a body [m]
  Extreme max_layback;        // horizontal distance tow point -> body origin (or P_n) [m]
  Extreme min_body_deg[3], max_body_deg[3];  // roll, pitch, yaw [deg] (body)
  /// Update with one sample.
  void add(const Sample& s);
};

/// Writes timeseries.csv (and nodes.csv) row by row, each sample's rows
/// complete and flushed to the OS before the next, so that a crash leaves
/// whole rows. Numbers are written with 12 significant digits.
class RunWriter : public OutputSink {
 public:
  /// Create the files in the existing directory `dir` and write their
  /// headers; throws std::runtime_error when a file cannot be created.
  /// `deployed_length`: the cable length written in every row [m].
  RunWriter(const std::string& dir, bool has_body, bool write_nodes,
            double deployed_length = std::numeric_limits<double>::quiet_NaN());
  ~RunWriter() override;
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  /// Append the sample's rows and flush them.
  void write(const Sample& s) override;
  /// Flush both files.
  void flush() override;
  /// Extremes of the samples written so far.
  const Extremes& extremes() const { return extremes_; }
  /// Number of samples written.
  long samples() const { return samples_; }
  /// The last row's values by column name, as written (null before any row).
  nlohmann::ordered_json final_row() const;

 private:
  bool has_body_;
  double deployed_length_;    // [m]
  std::vector<double> last_;  // the last timeseries row, as written
  std::FILE* series_ = nullptr;
  std::FILE* nodes_ = nullptr;
  std::string buf_;
  Extremes extremes_;
  long samples_ = 0;
};

/// Magnitudes below this are written as 0 [any unit: m, N, deg, m/s].
/// 1e-9 is far below any physical resolution of these quantities (a
/// nanometre, a nanonewton) and far above the round-off of exact zeros.
inline constexpr double kZeroBelow = 1e-9;

/// A value as written: 0 below kZeroBelow, else rounded to 12 significant digits.
double tidy(double v);
/// A time as written: rounded to the nanosecond [s].
double tidy_time(double t);
/// Append `v` as written (0 below kZeroBelow, else 12 significant digits) to `out`.
void put_number(std::string& out, double v);
/// Append a time as written (tidy_time, shortest round-trip form) to `out`.
void put_time(std::string& out, double t);

/// The timeseries.csv header for a run with or without a body (no newline).
std::string timeseries_header(bool has_body);
/// The same as a list of column names.
std::vector<std::string> timeseries_columns(bool has_body);

/// Horizontal distance from the tow point to the body origin (or to the
/// cable's lower end without a body) [m].
double layback(const Sample& s);

/// Remove what towsim writes into an output directory (timeseries.csv,
/// nodes.csv, summary.json, plots/, report.html) and nothing else, so that a
/// reused directory keeps no stale file. Throws std::runtime_error on failure.
void remove_run_outputs(const std::string& dir);

/// summary.json content: model name, RunStats, extremes, the scenario echo.
nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const Extremes& ex, long samples,
                                    bool has_body, bool write_nodes,
                                    const nlohmann::ordered_json& final_row = nullptr);

/// Write `summary` as DIR/summary.json (pretty-printed); false on I/O error.
bool write_summary(const std::string& dir, const nlohmann::ordered_json& summary);

}  // namespace towsim::io
