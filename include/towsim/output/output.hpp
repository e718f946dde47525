// Run outputs (README "Output files"; docs/contract.md §U5): timeseries.csv, nodes.csv, summary.json.
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

/// Extremes of one body.
struct BodyExtremes {
  Extreme max_link_force;        // |F_L| [N]
  Extreme max_lower_link_force;  // |force at Q2| [N] (in-line body)
  Extreme max_depth;             // -z of O_t [m]
  Extreme min_deg[3], max_deg[3];// roll, pitch, yaw [deg]
};

/// Extremes over all written samples.
struct Extremes {
  Extreme max_tow_tension;    // |F_R| [N]
  Extreme max_cable_tension;  // largest joint tension anywhere [N]
  Extreme max_end_depth;      // -z of P_n [m]
  Extreme min_axial_force;    // smallest axial force in any joint, < 0 in compression [N]
  BodyExtremes end_body_extremes;           // the end body's (if any)
  std::vector<BodyExtremes> inline_bodies;  // per Model::bodies entry (in-line ones used)
  /// Update with one sample of `model`.
  void add(const Model& model, const Sample& s);
};

/// Writes timeseries.csv (and nodes.csv) row by row, each sample's rows
/// complete and flushed to the OS before the next, so that a crash leaves
/// whole rows. Numbers are written with 12 significant digits.
class RunWriter : public OutputSink {
 public:
  /// Create the files in the existing directory `dir` and write their
  /// headers; throws std::runtime_error when a file cannot be created.
  RunWriter(const std::string& dir, const Model& model, bool write_nodes);
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

 private:
  const Model& model_;
  std::FILE* series_ = nullptr;
  std::FILE* nodes_ = nullptr;
  std::string buf_;
  Extremes extremes_;
  long samples_ = 0;
};

/// The timeseries.csv header for the model's chain (no newline).
std::string timeseries_header(const Model& model);

/// summary.json content: model name, RunStats, extremes, the scenario echo.
nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const Extremes& ex, long samples,
                                    const Model& model, bool write_nodes);

/// Write `summary` as DIR/summary.json (pretty-printed); false on I/O error.
bool write_summary(const std::string& dir, const nlohmann::ordered_json& summary);

}  // namespace towsim::io
