// `towsim run` on a network of lines (docs/scenario.md "Networks").
#include <cmath>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "commands.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/network_output.hpp"
#include "towsim/sim/network_discretisation.hpp"
#include "towsim/sim/simulate_network.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;

namespace {

/// `name` of the final row as text with its unit, "?" when absent.
std::string final_of(const nlohmann::ordered_json& row, const std::string& name, const char* unit) {
  if (!row.is_object() || !row.contains(name) || !row[name].is_number()) return "?";
  return fmt_num(row[name].get<double>()) + unit;
}

/// The line printed at the end of a network run: each line's top tension,
/// each body's depth, the cost.
std::string network_end_line(const Network& net, const RunStats& stats, const NetworkRecord& rec,
                             const std::string& out_dir) {
  const nlohmann::ordered_json row = rec.final_row();
  std::string s = net.name + ": t = " + fmt_num(tidy_time(stats.end_time)) + " s:";
  for (std::size_t i = 0; i < net.line_names.size(); ++i)
    s += (i ? ", " : " ") + net.line_names[i] + " top tension " +
         final_of(row, net.line_names[i] + "_top_tension", " N");
  for (const NetworkBody& b : net.bodies) s += ", " + b.name + " depth " + final_of(row, b.name + "_depth", " m");
  return s + "; " + std::to_string(rec.samples()) + " samples to " + out_dir + " (" + std::to_string(stats.steps) +
         " steps, " + std::to_string(stats.rhs_evaluations) + " RHS evaluations, " +
         fmt_num(std::round(stats.wall_seconds * 1e3) / 1e3) + " s wall)";
}

}  // namespace

int run_network(const LoadedScenario& sc, const Network& net, const RunOptions& opts, std::ostream& out,
                std::ostream& err, const volatile int* stop_flag) {
  // What a network's run does not do yet: refused before anything is written.
  if (net.settings().initial.kind == Initial::Kind::Steady)
    if (const std::string why = network_steady_refusal(net); !why.empty()) {
      err << "towsim: run: initial: steady: " << why << "\n";
      return kExitInvalid;
    }
  if (!create_output_dir(opts.out_dir, err)) return kExitError;
  try {
    const DirLock lock(opts.out_dir);  // one towsim at a time in a directory
    remove_run_outputs(opts.out_dir);  // no stale file of a previous run
    const bool nodes = net.settings().sim.write_nodes;
    NetworkWriter writer(opts.out_dir, net, nodes);
    RunStats stats;
    try {
      stats = simulate_network(net, writer, {}, stop_flag);
      record_network_discretisation_estimate(net, stats, stop_flag);  // the element count's share of the error
    } catch (const std::exception& e) {
      stats.status = "failed";
      stats.message = std::string("internal error: ") + e.what();
    }
    writer.flush();
    auto summary = make_network_summary(to_json(sc.tree), stats, writer, nodes);
    const std::string csv_error = writer.error();
    if (!csv_error.empty()) summary["warnings"].push_back(csv_error + " (the file ends at the last whole row written)");
    std::string why;
    if (!write_summary(opts.out_dir, summary, &why)) throw std::runtime_error(why);
    if (!csv_error.empty()) throw std::runtime_error(csv_error);
    if (!opts.quiet)
      for (const std::string& w : stats.warnings) err << "towsim: warning: " << w << "\n";
    if (stats.status == "failed") {
      err << "towsim: simulation failed (t = " << fmt_num(stats.end_time) << " s reached): " << stats.message
          << " (results up to then are in " << opts.out_dir << ")\n";
      return kExitFailed;
    }
    if (stats.status == "interrupted") {
      err << "towsim: interrupted at t = " << fmt_num(stats.end_time) << " s (results up to then are in "
          << opts.out_dir << ")\n";
      return kExitInterrupted;
    }
    if (!opts.quiet) out << network_end_line(net, stats, writer, opts.out_dir) << "\n";
    return kExitOk;
  } catch (const std::exception& e) {
    err << "towsim: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace towsim::cli
