// The subcommands of the `towsim` program, one function each, so that the
// command-line front end (app/main.cpp) only parses arguments. To add a
// subcommand, write a function here and register it in app/main.cpp.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/model/network.hpp"
#include "towsim/output/output.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim::cli {

/// Exit statuses of the program (docs/contract.md §U3).
enum ExitStatus : int {
  kExitOk = 0,             // success
  kExitError = 1,          // I/O or internal error (e.g. the output directory cannot be created)
  kExitInvalid = 2,        // invalid input: nothing written
  kExitFailed = 3,         // the simulation failed numerically (files so far kept)
  kExitInterrupted = 130,  // stopped by SIGINT/SIGTERM (files so far kept)
};

/// What to load: a scenario file or a built-in example, with overrides.
struct InputOptions {
  std::string scenario;           // path of a scenario YAML file, or ""
  std::string example;            // name of a built-in example, or ""
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
};

/// Options of `towsim run`.
struct RunOptions {
  InputOptions input;
  std::string out_dir;    // output directory (created if missing)
  bool quiet = false;     // print nothing but errors
  bool progress = false;  // draw a progress bar on `err`
};

/// Options of `towsim statics`.
struct StaticsOptions {
  InputOptions input;
  std::string out_dir;                 // where to write timeseries.csv and nodes.csv of the configuration ("" = none)
  std::optional<double> target_depth;  // --target-depth D: find the deployed length for this depth [m]
  std::string trim_body;               // --trim NAME: find the link point x for the body's pitch ("" = none)
  double trim_pitch = 0;               // --trim-pitch DEG: the pitch --trim looks for [deg]
  std::string line;                    // --line NAME: a network's line from the vessel that --target-depth varies
};

/// Load, override, check and compile the scenario named by `in` (exactly one
/// of a file or an example); every problem is in the result's diagnostics.
scenario::LoadedScenario load_input(const InputOptions& in);

/// Create the output directory `dir` (and its parents) when missing; false,
/// with "towsim: cannot create the output directory ..." on `err`, when it
/// cannot be or is not a directory.
bool create_output_dir(const std::string& dir, std::ostream& err);

/// `towsim run`: simulate and write timeseries.csv, nodes.csv and
/// summary.json into the output directory. Invalid input writes nothing.
/// `stop_flag` (may be null) interrupts the run when set. Returns an ExitStatus.
int run_command(const RunOptions& opts, std::ostream& out, std::ostream& err, const volatile int* stop_flag = nullptr);

/// `towsim run` on a network (the scenario's `lines:`): as run_command,
/// with the network's files (docs/scenario.md "Networks").
int run_network(const scenario::LoadedScenario& sc, const Network& net, const RunOptions& opts, std::ostream& out,
                std::ostream& err, const volatile int* stop_flag);

/// `towsim statics`: the steady-tow equilibrium at the tow law's final
/// velocity; prints tow force, end and body depth, link force, element
/// angles; writes the configuration when an output directory is given.
/// Returns an ExitStatus (3 when the solver does not converge).
int statics_command(const StaticsOptions& opts, std::ostream& out, std::ostream& err,
                    const volatile int* stop_flag = nullptr);

/// `towsim statics` on a network: its steady tow at the tow law's final
/// velocity (network_statics), printed per line, body and junction and
/// written as a one-sample network run with an output directory.
int statics_network(const scenario::LoadedScenario& sc, const Network& net, const StaticsOptions& opts,
                    std::ostream& out, std::ostream& err, const volatile int* stop_flag);

/// Why `towsim statics` refuses a valid scenario (a tow in force mode: the
/// steady speed comes from the tow law), as an error at its key; nullopt when
/// it can be solved.
std::optional<scenario::Diagnostic> statics_refusal(const scenario::LoadedScenario& sc);

/// The summary of a steady tow as `towsim statics --out` writes it: the
/// equilibrium written to `rec` (of the model solved: the deployed one after
/// --target-depth) as its one sample (t = 0), status `ok`, `failed` or
/// `interrupted`, `steps` = solver iterations.
nlohmann::ordered_json statics_summary(const scenario::LoadedScenario& sc, const StaticsResult& r,
                                       output::RunRecord& rec);

/// The warnings of a steady tow's body equilibria, one sentence each: a
/// body with more than one stable balance ("trim of body depressor: two
/// stable equilibria, +24.3 and -13.0 deg pitch; reported +24.3, ..."), or
/// whose balance reported is statically unstable.
std::vector<std::string> equilibria_warnings(const Model& model, const StaticsResult& r);

/// summary.json `bodies` of a steady tow: per body its name, `equilibria`
/// (roll_deg, pitch_deg, yaw_deg, stable, roll/pitch/yaw_stiffness,
/// min_stiffness [N m/rad]) and `chosen`, the index of the one reported
/// (both null when not analysed: not converged, or on the seabed).
nlohmann::ordered_json bodies_json(const Model& model, const StaticsResult& r);

/// The line `towsim run` prints at the end of a successful run: final
/// layback, depth of the body (or cable end) and tow tension, the maximum
/// tow tension and when, then samples, steps and wall time.
std::string end_of_run_line(const Model& model, const RunStats& stats, const nlohmann::ordered_json& final_row,
                            const output::Extremes& ex, long samples, const std::string& out_dir);

/// `towsim check`: validate and print the derived quantities. Returns an ExitStatus.
int check_command(const InputOptions& in, std::ostream& out, std::ostream& err);

/// `towsim examples [NAME]`: list the built-in examples ("" = all, one per
/// line with a description), or print one as YAML. Returns an ExitStatus.
int examples_command(const std::string& name, std::ostream& out, std::ostream& err);

/// Print a compiled model's derived quantities (element length, masses,
/// apparent weights, added mass, drag factors, body, tow law, run settings)
/// and, with `accuracy`, the discretisation error estimate and the element
/// count advised (steady solves: their cost grows with the element count).
void describe_model(const Model& model, std::ostream& out, bool accuracy = true);

/// Print a compiled network (sc.network): its lines (ends, lengths, elements,
/// tow points or nodes), junctions and loops, the settings common to the
/// lines once, and each line's derived quantities as describe_model prints
/// a chain's.
void describe_network(const scenario::LoadedScenario& sc, std::ostream& out);

}  // namespace towsim::cli
