#include "commands.hpp"
#include "towsim/waves/vessel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "towsim/integrators/system.hpp"
#include "towsim/output/async_sink.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/output.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/sim/discretisation.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;
namespace {

/// "unknown example (did you mean 'y'?); ..." for an example name not built in.
std::string unknown_example(const std::string& name) {
  std::vector<std::string> names;
  for (const auto& e : examples()) names.push_back(e.name);
  const std::string hint = closest_match(name, names);
  std::string msg = "unknown example";
  if (!hint.empty()) msg += " (did you mean '" + hint + "'?)";
  return msg + "; `towsim examples` lists them";
}

/// A progress bar on `err`, redrawn when the percentage changes: the
/// simulated time reached and the estimated wall time left.
class ProgressBar {
 public:
  ProgressBar(std::ostream& err, double duration)
      : err_(err), duration_(duration), start_(std::chrono::steady_clock::now()) {}
  void operator()(double fraction) {
    const double f = std::clamp(fraction, 0.0, 1.0);
    const int pct = static_cast<int>(f * 100.0);
    if (pct == last_) return;
    last_ = pct;
    const int filled = pct * kWidth / 100;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    char eta[32] = "";
    if (f > 0.01 && f < 1) std::snprintf(eta, sizeof eta, ", ETA %.0f s", wall * (1 - f) / f);
    char t[64];
    std::snprintf(t, sizeof t, " t = %.6g / %.6g s", tidy_time(f * duration_), duration_);
    err_ << "\r[" << std::string(static_cast<std::size_t>(filled), '#')
         << std::string(static_cast<std::size_t>(kWidth - filled), ' ') << "] " << pct << "%" << t << eta << "   "
         << std::flush;
  }
  void done() {
    if (last_ >= 0) err_ << "\n" << std::flush;
  }

 private:
  static constexpr int kWidth = 40;
  std::ostream& err_;
  double duration_;  // [s] simulated
  std::chrono::steady_clock::time_point start_;
  int last_ = -1;
};

/// Run the simulation into `writer`; exceptions become a failed run.
RunStats simulate_safely(const Model& model, OutputSink& writer, const RunOptions& opts, std::ostream& err,
                         const volatile int* stop_flag) {
  ProgressBar bar(err, model.sim.duration);
  ProgressFn progress;
  if (opts.progress && !opts.quiet) progress = [&bar](double f) { bar(f); };
  RunStats stats;
  try {
    stats = simulate(model, writer, progress, stop_flag);
  } catch (const std::exception& e) {
    stats.status = "failed";
    stats.message = std::string("internal error: ") + e.what();
  }
  bar.done();
  writer.flush();
  return stats;
}

/// `name` of the final row as text with its unit, "?" when absent.
std::string final_value(const nlohmann::ordered_json& row, const char* name, const char* unit) {
  if (!row.is_object() || !row.contains(name) || !row[name].is_number()) return "?";
  return fmt_num(row[name].get<double>()) + unit;
}

/// An extreme as "V unit at t = T s".
std::string extreme_text(const Extreme& e, const char* unit) {
  if (std::isnan(e.value)) return "?";
  return fmt_num(e.value) + unit + " at t = " + fmt_num(e.time) + " s";
}

}  // namespace

std::string end_of_run_line(const Model& model, const RunStats& stats, const nlohmann::ordered_json& final_row,
                            const Extremes& ex, long samples, const std::string& out_dir) {
  // The results an engineer reads first, then the run's cost.
  const bool body = end_body(model) != nullptr;
  std::string s = model.name + ": t = " + fmt_num(tidy_time(stats.end_time)) + " s: layback " +
                  final_value(final_row, "layback", " m") + ", " + (body ? "body" : "end") + " depth " +
                  final_value(final_row, body ? "body_depth" : "end_depth", " m") + ", tow tension " +
                  final_value(final_row, "tow_tension", " N") + "; max tow tension " +
                  extreme_text(ex.max_tow_tension, " N") + "; " + std::to_string(samples) + " samples to " + out_dir +
                  " (" + std::to_string(stats.steps) + " steps, " + std::to_string(stats.rhs_evaluations) +
                  " RHS evaluations, " + fmt_num(std::round(stats.wall_seconds * 1e3) / 1e3) + " s wall)";
  return s;
}

namespace {

/// An elastic cable that went slack: how often, where first, the snap after it.
void elastic_warnings(const SlackRecord& r, std::ostream& err) {
  if (r.episodes == 0 || r.events().empty()) return;
  const SlackEvent& ev = r.events().front();
  err << "towsim: warning: the cable went slack " << r.episodes << (r.episodes == 1 ? " time" : " times") << " ("
      << fmt_num(tidy_time(r.slack_time)) << " s in all); first at t = " << fmt_num(tidy_time(ev.start))
      << " s, elements " << ev.first_element << "-" << ev.last_element << " (" << fmt_num(tidy(ev.from)) << "-"
      << fmt_num(tidy(ev.to)) << " m from the tow point), for " << fmt_num(tidy_time(ev.end - ev.start)) << " s";
  if (ev.ended)
    err << ", snap " << fmt_num(tidy(ev.snap_tension)) << " N at t = " << fmt_num(tidy_time(ev.snap_time)) << " s";
  err << "; peak element tension " << fmt_num(tidy(r.max_tension))
      << " N at t = " << fmt_num(tidy_time(r.max_tension_time)) << " s (see elastic in summary.json)\n";
}

/// Print the outcome and map RunStats.status to an exit status.
int report_run(const RunStats& stats, const Model& model, const RunOptions& opts, long samples,
               const nlohmann::ordered_json& final_row, const Extremes& ex, std::ostream& out, std::ostream& err) {
  if (stats.status == "failed") {
    err << "towsim: simulation failed (t = " << fmt_num(stats.end_time) << " s reached): " << stats.message
        << " (results up to then are in " << opts.out_dir << ")\n";
    return kExitFailed;
  }
  if (stats.status == "interrupted") {
    err << "towsim: interrupted at t = " << fmt_num(stats.end_time) << " s (results up to then are in " << opts.out_dir
        << ")\n";
    return kExitInterrupted;
  }
  if (!opts.quiet) out << end_of_run_line(model, stats, final_row, ex, samples, opts.out_dir) << "\n";
  return kExitOk;
}

}  // namespace

bool create_output_dir(const std::string& dir, std::ostream& err) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!ec && std::filesystem::is_directory(dir)) return true;
  err << "towsim: cannot create the output directory '" << dir << "'" << (ec ? ": " + ec.message() : std::string())
      << "\n";
  return false;
}

LoadedScenario load_input(const InputOptions& in) {
  if (in.scenario.empty() == in.example.empty()) {
    LoadedScenario s;
    s.diags.error(SourceLoc{"(command line)", 1, 1}, "SCENARIO",
                  "give exactly one of a SCENARIO file or --example NAME");
    return s;
  }
  if (!in.scenario.empty()) return load_scenario_file(in.scenario, in.sets);
  const Example* ex = find_example(in.example);
  if (ex == nullptr) {
    LoadedScenario s;
    s.diags.error(SourceLoc{"--example", 1, 1}, in.example, unknown_example(in.example));
    return s;
  }
  return load_scenario_text(ex->yaml, ex->name + ".yaml", ex->name, "", in.sets);
}

int run_command(const RunOptions& opts, std::ostream& out, std::ostream& err, const volatile int* stop_flag) {
  const LoadedScenario sc = load_input(opts.input);
  if (!sc.ok()) {
    err << sc.diags.str();
    return kExitInvalid;
  }
  if (sc.is_network()) return run_network(sc, *sc.network, opts, out, err, stop_flag);
  const Model& model = *sc.model;
  if (!create_output_dir(opts.out_dir, err)) return kExitError;
  try {
    const DirLock lock(opts.out_dir);  // one towsim at a time in a directory
    remove_run_outputs(opts.out_dir);  // no stale file of a previous run
    RunWriter writer(opts.out_dir, model, model.sim.write_nodes);
    RunStats stats;
    if (evaluation_threads(model) > 1) {
      stats = simulate_safely(model, writer, opts, err, stop_flag);  // the second core evaluates
    } else {
      // The files are formatted and written on a thread of their own;
      // simulate_safely's last flush() waits for them.
      AsyncSink async(writer);
      stats = simulate_safely(model, async, opts, err, stop_flag);
    }
    record_discretisation_estimate(model, stats, stop_flag);  // two steady tows, O(n) each
    auto summary = make_summary(to_json(sc.tree), model.name, stats, writer, model.sim.write_nodes);
    if (has_sea(model)) {
      summary["statistics"] = writer.sea_statistics().json();
      if (!writer.sea_statistics().write_spectra((std::filesystem::path(opts.out_dir) / "spectra.csv").string()))
        throw std::runtime_error("cannot write spectra.csv");
      summary["files"]["spectra"] = "spectra.csv";
      // A maximum above its Rayleigh mpm: the Gaussian assumption fails (said in summary.json and on stderr).
      for (const std::string& w : writer.sea_statistics().warnings()) {
        summary["warnings"].push_back(w);
        if (!opts.quiet) err << "towsim: warning: " << w << "\n";
      }
    }
    // A file the disk could not take (full, I/O error): said in summary.json and on exit (status 1).
    const std::string csv_error = writer.error();
    if (!csv_error.empty()) summary["warnings"].push_back(csv_error + " (the file ends at the last whole row written)");
    std::string why;
    if (!write_summary(opts.out_dir, summary, &why))
      throw std::runtime_error(why + (csv_error.empty() ? "" : "; " + csv_error));
    if (!csv_error.empty()) throw std::runtime_error(csv_error + " (the file ends at the last whole row written)");
    if (!opts.quiet)
      for (const std::string& w : stats.warnings) err << "towsim: warning: " << w << "\n";
    // Rigid elements can push; a real cable would go slack there. An
    // elastic cable goes slack instead: its episodes are reported.
    if (!opts.quiet && lengths_in_state(model)) elastic_warnings(stats.slack, err);
    if (const std::string w = compression_warning(model, writer.extremes()); !opts.quiet && !w.empty())
      err << "towsim: warning: " << w << "\n";  // also in summary.json "warnings"
    // An extreme attitude usually means a design that does not fly (stalled
    // fins, a body hanging nose down): say when, so the user need not dig.
    constexpr double kAttitudeWarnDeg = 30;  // |roll| or |pitch| beyond this [deg]
    if (!opts.quiet && end_body(model) != nullptr) {
      const BodyExtremes& be = writer.extremes().end_body_extremes;
      static const char* kAngle[2] = {"roll", "pitch"};
      for (int i = 0; i < 2; ++i) {
        const Extreme& e = std::abs(be.min_deg[i].value) > std::abs(be.max_deg[i].value) ? be.min_deg[i]
                                                                                         : be.max_deg[i];
        if (std::abs(e.value) > kAttitudeWarnDeg)
          err << "towsim: warning: the body's " << kAngle[i] << " reached " << fmt_num(e.value)
              << " deg at t = " << fmt_num(e.time) << " s (beyond " << kAttitudeWarnDeg
              << " deg: check its fins, link point and "
              << "weights; body_" << kAngle[i] << "_deg in timeseries.csv)\n";
      }
    }
    // Strength: utilisation above 1/3 and above 1 (also in summary.json "warnings").
    if (!opts.quiet)
      for (const std::string& w : strength_warnings(writer.extremes())) err << "towsim: warning: " << w << "\n";
    return report_run(stats, model, opts, writer.samples(), writer.final_row(), writer.extremes(), out, err);
  } catch (const std::exception& e) {
    err << "towsim: " << e.what() << "\n";
    return kExitError;
  }
}

int check_command(const InputOptions& in, std::ostream& out, std::ostream& err) {
  const LoadedScenario sc = load_input(in);
  if (!sc.ok()) {
    err << sc.diags.str();
    return kExitInvalid;
  }
  if (sc.is_network())
    describe_network(sc, out);
  else
    describe_model(*sc.model, out);
  return kExitOk;
}

int examples_command(const std::string& name, std::ostream& out, std::ostream& err) {
  if (name.empty()) {
    std::size_t width = 0;
    for (const auto& e : examples()) width = std::max(width, e.name.size());
    for (const auto& e : examples())
      out << e.name << std::string(width + 2 - e.name.size(), ' ') << e.description
          << (e.name == kDefaultExample ? " (default)" : "") << "\n";
    return kExitOk;
  }
  const Example* ex = find_example(name);
  if (ex == nullptr) {
    err << "towsim: examples: " << name << ": " << unknown_example(name) << "\n";
    return kExitInvalid;
  }
  out << ex->yaml;
  return kExitOk;
}

}  // namespace towsim::cli
