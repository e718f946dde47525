// Run outputs (docs/scenario.md "Output files"): timeseries.csv, nodes.csv,
// summary.json. The columns depend on the model's chain: the end body keeps
// the `body_*` / `link_*` columns, each in-line body adds columns prefixed
// with its name.
//
// Number format (docs/scenario.md "Number format"): a magnitude below
// kZeroBelow is written as 0 (round-off where 0 is meant, e.g. 1.6e-145);
// other values with 12 significant digits in the shortest form that reads
// back to them; times rounded to the nanosecond first (k * 0.1 s is written
// 7088.4, not 7088.400000000001). summary.json holds the same values.
#pragma once

#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/output/row_file.hpp"
#include "towsim/output/sea_statistics.hpp"
#include "towsim/output/transients.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::output {

/// A maximum (or minimum) over the run and the time it was reached.
struct Extreme {
  double value = std::numeric_limits<double>::quiet_NaN();
  double time = std::numeric_limits<double>::quiet_NaN();
  /// Keep (v, t) when v > value (or the first time).
  void max(double v, double t);
  /// Keep (v, t) when v < value (or the first time).
  void min(double v, double t);
};

/// Extremes of one body.
struct BodyExtremes {
  Extreme max_link_force;          // |F_L| [N]
  Extreme max_lower_link_force;    // |force at Q2| [N] (in-line body)
  Extreme max_depth;               // -z of O_t [m]
  Extreme min_deg[3], max_deg[3];  // roll, pitch, yaw [deg]
};

/// Utilisation above which a run warns: a safety factor of 3 on the breaking load [-].
inline constexpr double kUtilisationWarning = 1.0 / 3.0;
/// Utilisation above which the cable is flagged as failed (the run goes on) [-].
inline constexpr double kUtilisationFailure = 1.0;

/// The first sample where a node's utilisation went above a threshold.
struct Crossing {
  double time = std::numeric_limits<double>::quiet_NaN();         // [s]
  long node = -1;                                                 // nodes.csv index, -1 = never
  double arc_length = std::numeric_limits<double>::quiet_NaN();   // of the node from the tow point [m]
  double utilisation = std::numeric_limits<double>::quiet_NaN();  // there and then [-]
  bool happened() const { return node >= 0; }
};

/// Figures of one depth controller (docs/outputs: summary.json "depth_control").
struct ControlExtremes {
  Extreme max_abs_deflection;                                       // |delta| [deg]
  Extreme max_abs_rate;                                             // |d delta/dt| [deg/s]
  Extreme max_abs_error;                                            // |depth - target| [m]
  double first_error = std::numeric_limits<double>::quiet_NaN();    // e of the first sample [m]
  double band = std::numeric_limits<double>::quiet_NaN();           // settling band [m]
  double settled_since = std::numeric_limits<double>::quiet_NaN();  // first time of the current run of
                                                                    // samples with |e| <= band; NaN when outside [s]
  double final_error = std::numeric_limits<double>::quiet_NaN();    // e of the last sample [m]
};

/// Extremes over all written samples.
struct Extremes {
  Extreme max_tow_tension;         // |F_R| [N]
  Extreme max_cable_tension;       // largest joint tension anywhere [N]
  Extreme max_end_depth;           // -z of the cable's end [m]
  Extreme min_axial_force;         // smallest axial force in any joint, < 0 in compression [N]
  Extreme min_depth, max_depth;    // -z of the end body's origin, or of the cable end without one [m]
  Extreme max_layback;             // horizontal distance tow point -> end body origin (or cable end) [m]
  Extreme max_utilisation;         // largest tension / breaking load at a node [-] (sections with breaking_load)
  Crossing utilisation_warning;    // first utilisation > kUtilisationWarning
  Crossing cable_failure;          // first utilisation > kUtilisationFailure
  Extreme max_contact_length;      // cable length on the seabed [m] (with a seabed)
  Extreme max_seabed_normal;       // sum of |normal force| of the seabed [N]
  Extreme max_seabed_friction;     // sum of |friction force| of the seabed [N]
  BodyExtremes end_body_extremes;  // the end body's (if any)
  std::vector<BodyExtremes> inline_bodies;  // per Model::bodies entry (in-line ones used)
  std::vector<ControlExtremes> controls;    // per depth controller (bodies, then surfaces, in order)
  /// Update with one sample of `model`.
  void add(const Model& model, const Sample& s);
  /// The depth controllers' part of add().
  void add_controls(const Model& model, const Sample& s);
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
/// The same, under the name the Python module uses.
inline void append_number(std::string& out, double v) { put_number(out, v); }
/// Append a time as written (tidy_time, shortest round-trip form) to `out`.
void put_time(std::string& out, double t);

/// The columns of timeseries.csv, in order, for the model's chain.
std::vector<std::string> timeseries_columns(const Model& model);
/// The timeseries.csv header (no newline).
std::string timeseries_header(const Model& model);
/// One sample's timeseries.csv values as written (tidied), in the order of
/// timeseries_columns() (the files and the Python API both use this).
void timeseries_values(const Model& model, const Sample& s, std::vector<double>& v);

/// The per-node columns of nodes.csv (after `time,node`): x, y, z, vx, vy, vz, tension, axial_force, strain.
const std::vector<std::string>& node_columns();
/// Node k's nodes.csv values of one sample as written (tidied), in the order of node_columns().
void node_values(const Sample& s, std::size_t k, std::vector<double>& out);
/// The per-node columns of a model's nodes.csv: node_columns(), then
/// `utilisation` (with breaking loads) and `seabed_force` (with a seabed).
std::vector<std::string> node_columns(const Model& model);
/// Node k's values in the order of node_columns(model).
void node_values(const Model& model, const Sample& s, std::size_t k, std::vector<double>& out);
/// Arc length of each node (nodes.csv order) from the tow point [m].
std::vector<double> node_arc_lengths(const Model& model);

/// The strength warnings of a run, one sentence each: utilisation above 1/3
/// (a safety factor below 3), above 1 (the cable would break there).
std::vector<std::string> strength_warnings(const Extremes& ex);

/// A rigid cable pushed (negative axial force: a real cable would go slack
/// there): the warning with the most negative force and its time, or "".
std::string compression_warning(const Model& model, const Extremes& ex);

/// Horizontal distance from the tow point to the end body's origin (or to
/// the cable's lower end without an end body) [m].
double layback(const Model& model, const Sample& s);
/// Largest tension / breaking load over the nodes of one sample (0 when no
/// section gives a breaking load) [-].
double utilisation(const Model& model, const Sample& s);

/// Remove what towsim writes into an output directory (the regular files
/// timeseries.csv, nodes.csv, summary.json, spectra.csv, report.html and those
/// in plots/) and nothing else, so that a reused directory keeps no stale
/// file. Throws std::runtime_error on failure, and when one of those names is
/// something else (a directory, a link), which it leaves alone.
void remove_run_outputs(const std::string& dir);

/// A sink that keeps what summary.json needs: the extremes, the number of
/// samples and the last timeseries row. The base of the file writer; used
/// alone where no file is written (sweeps, Python).
class RunRecord : public OutputSink {
 public:
  explicit RunRecord(const Model& model);
  /// Account for one sample.
  void write(const Sample& s) override;
  void flush() override {}
  /// Extremes of the samples written so far.
  const Extremes& extremes() const { return extremes_; }
  /// Number of samples written.
  long samples() const { return samples_; }
  /// The last sample's timeseries values as written (empty before the first).
  const std::vector<double>& last_row() const;
  /// The last row's values by column name (null before any row).
  nlohmann::ordered_json final_row() const;
  const Model& model() const { return model_; }
  /// Sea-state statistics of the samples so far (a model with waves or a vessel).
  const SeaStatistics& sea_statistics() const { return sea_; }
  /// The run's phases (run_phases) and their figures over the samples so far.
  const TransientRecord& transients() const { return transients_; }

 private:
  const Model& model_;
  SeaStatistics sea_;
  TransientRecord transients_;
  Extremes extremes_;
  long samples_ = 0;
  std::vector<double> raw_row_;           // the last row before tidy (time rounded)
  mutable std::vector<double> last_row_;  // raw_row_ tidied, on demand
  mutable bool row_tidied_ = true;

 protected:
  /// The last row unrounded (the time rounded): written as last_row() reads.
  const std::vector<double>& raw_row() const { return raw_row_; }
};

/// Writes timeseries.csv (and nodes.csv): each sample's rows are formatted
/// into a buffer and handed to the OS whole, once the buffers hold
/// kWriteBytes or kWriteEvery after the last write (and at flush() and at
/// the end), so that a crash leaves whole rows, all but at most the last
/// kWriteEvery of them.
class RunWriter : public RunRecord {
 public:
  /// Create the files in the existing directory `dir` and write their
  /// headers; throws std::runtime_error when a file cannot be created.
  RunWriter(const std::string& dir, const Model& model, bool write_nodes);
  ~RunWriter() override;
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  /// Append the sample's rows (written out as the class comment says).
  void write(const Sample& s) override;
  /// Write out the rows buffered so far and flush both files.
  void flush() override;

  /// "" while every row went to the disk; else the first file's failure
  /// ("cannot write PATH: cause"), after which that file gets no more rows.
  std::string error() const;

  /// Buffered rows are written out from this size on [bytes]
  static constexpr std::size_t kWriteBytes = 64 * 1024;
  /// ... or this long after the last write [s of wall time]
  static constexpr std::chrono::milliseconds kWriteEvery{100};

 private:
  std::unique_ptr<RowFile> series_;
  std::unique_ptr<RowFile> nodes_;  // null without nodes.csv
  bool node_ids_ = false;           // nodes.csv has a node_id column (a model with a winch)
  std::string series_buf_;          // timeseries.csv rows not yet written
  std::string nodes_buf_;           // nodes.csv rows not yet written
  std::chrono::steady_clock::time_point last_write_;
  std::string time_;  // the sample's time as written
  std::vector<double> values_;
};

/// JSON for an extreme: {value, time} as written, nulls when never set.
nlohmann::ordered_json json_of(const Extreme& e);
/// A finite number as JSON, anything else as null.
nlohmann::ordered_json num(double v);
/// summary.json's run part: model name, version, status and message, end
/// time, cost (steps, evaluations, wall time), error estimates, warnings.
nlohmann::ordered_json run_json(const std::string& model_name, const RunStats& stats);

/// summary.json content: model name, RunStats, extremes, `phases` (the
/// manoeuvre phases and their transient figures), `final` (the last row by
/// column name), the scenario echo.
nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const RunRecord& record, bool write_nodes);

/// Write `summary` as DIR/summary.json (pretty-printed), whole or not at all
/// (through DIR/summary.json.part); false on I/O error, with `error` (when
/// given) set to "cannot write PATH: cause".
bool write_summary(const std::string& dir, const nlohmann::ordered_json& summary, std::string* error = nullptr);

}  // namespace towsim::output
