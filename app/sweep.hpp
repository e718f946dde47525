// Parameter sweeps (issue 16): many runs of one base scenario over a grid or
// list of `--set` overrides, one row of key results per case. Used by
// `towsim sweep` and by the Python module (towsim.sweep).
#pragma once

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/scenario/diagnostics.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::cli {

/// A summary figure: its name (the summary.json name, flattened) and value (NaN for null).
using Figure = std::pair<std::string, double>;

/// The numbers of a summary.json, flattened to one name each: `end_time`;
/// each extreme by its name (its value; `body_roll_deg_min`/`_max` for the
/// min/max pairs); any other top-level `max_*`/`min_*` figure; and each
/// `final` value as `final_<column>`. Names in that order.
std::vector<Figure> summary_figures(const nlohmann::ordered_json& summary);

/// A body's trim in a steady-tow case: the balance reported and how many are stable.
struct BodyTrim {
  std::string body;          // "body depressor", "the body"
  Vec3 rpy_deg;              // roll, pitch, yaw of the balance reported [deg]
  std::size_t stable_count;  // stable balances found (BodyEquilibria)
};

/// How one case ended and its figures.
struct CaseResult {
  std::string status;           // ok | failed | interrupted | invalid | not_run
  std::string message;          // why it failed, or "" (invalid: every error, one per line)
  std::vector<Figure> figures;  // summary_figures() of its summary (empty when invalid)
  std::vector<BodyTrim> trims;  // statics cases: each analysed body's trim
};

/// Simulate a loaded, valid scenario. With `out_dir` non-empty, write the
/// files of `towsim run` there (created if missing); otherwise nothing is
/// written. Never throws: internal errors become a failed case. `progress`
/// is called after each output sample (as by simulate()).
CaseResult run_case(const scenario::LoadedScenario& sc, const std::string& out_dir, const volatile int* stop_flag,
                    const ProgressFn& progress = {});

/// Solve a loaded, valid scenario's steady tow as `towsim statics` does; the
/// figures are those of the summary `towsim statics --out` writes (`final_*`:
/// the equilibrium's). With `out_dir` non-empty, write its files there.
/// Status `ok`, `failed` (not converged), `interrupted` or `invalid` (a tow in
/// force mode). Never throws.
CaseResult statics_case(const scenario::LoadedScenario& sc, const std::string& out_dir, const volatile int* stop_flag);

/// run_case and statics_case on a network (`lines:`): its figures those of
/// the network's summary.json; network_figure_names: their names, in order.
CaseResult run_network_case(const scenario::LoadedScenario& sc, const std::string& out_dir,
                            const volatile int* stop_flag, const ProgressFn& progress = {});
CaseResult statics_network_case(const scenario::LoadedScenario& sc, const std::string& out_dir,
                                const volatile int* stop_flag);
std::vector<std::string> network_figure_names(const Network& net);

/// The columns of a towing table (DIR/towing_table.csv) after the case's
/// overrides and status: tow speed [m/s] and [kn], depth of the end body (or
/// the cable end) [m], layback [m], tow tension [N], top angle (the cable's
/// angle below the horizontal at the tow point, from the tow force) [deg], and
/// the end body's (or cable end's) offsets from the tow point aft of and to
/// starboard of the tow's heading [m].
const std::vector<std::string>& towing_table_columns();

/// A case's towing-table values from its figures (the `final_*` ones), in the
/// order of towing_table_columns(); NaN where a figure is missing.
std::vector<double> towing_row(const std::vector<Figure>& figures);

/// One case of a sweep: its overrides as (dotted key, YAML value text).
struct SweepCase {
  std::vector<std::pair<std::string, std::string>> sets;
};

/// A trim jump: more than this change of roll, pitch or yaw between neighbouring cases [deg].
constexpr double kTrimJumpDeg = 10;

/// The warnings of a statics sweep's trim jumps, one sentence each: for two
/// neighbouring cases (consecutive, their overrides differing in one value
/// only, both ok), each body whose reported roll, pitch or yaw differs by more
/// than kTrimJumpDeg, or whose number of stable balances differs (a branch
/// appears or disappears), naming both cases and their overrides.
std::vector<std::string> trim_jumps(const std::vector<SweepCase>& cases, const std::vector<CaseResult>& results);

/// A sweep file as read: the base scenario, the overrides every case
/// shares, the varied keys (in column order) and the cases.
struct SweepSpec {
  std::string scenario;             // scenario file path (relative to the working directory), or ""
  std::string example;              // built-in example name, or ""
  std::vector<std::string> common;  // `set`: KEY=VALUE for every case
  std::vector<std::string> keys;    // the keys the cases vary, in order
  std::vector<SweepCase> cases;
  bool write_cases = false;  // also write each case's files into DIR/case-NNNN/
  bool statics = false;      // each case a `towsim statics` (the steady tow), not a run
};

/// Most cases a sweep file may expand to.
constexpr std::size_t kMaxSweepCases = 100000;

/// Read a sweep file; every problem goes to `diags` as FILE:LINE:COL: key: problem.
SweepSpec read_sweep(const std::string& path, scenario::Diagnostics& diags);

/// Read a sweep file and load its base scenario and its first `max_cases`
/// cases as `towsim sweep` does before it runs anything: true when all are
/// valid; else false with every problem in `err` (FILE:LINE:COL: key: problem,
/// a case's override errors at the override in the sweep file).
bool check_sweep_file(const std::string& file, std::ostream& err, std::size_t max_cases);

/// Options of `towsim sweep`.
struct SweepOptions {
  std::string file;     // the sweep file
  std::string out_dir;  // where sweep.csv (and case-NNNN/) go
  int jobs = 0;         // parallel cases (0 = every core)
  bool quiet = false;   // print nothing but errors
};

/// `towsim sweep`: run the cases on `jobs` threads, write DIR/sweep.csv (one
/// row per case, in case order, flushed as they complete) and, at the end,
/// DIR/towing_table.csv (the same rows, towing_table_columns()). A failing case is
/// a row, not a failed sweep. `stop_flag` stops it: running cases end
/// `interrupted`, the rest are `not_run` rows. Returns an ExitStatus.
int sweep_command(const SweepOptions& opts, std::ostream& out, std::ostream& err,
                  const volatile int* stop_flag = nullptr);

}  // namespace towsim::cli
