// One sweep case of a network (docs/sweeps.md): `towsim run` or `towsim
// statics` on a network, its figures those of the network's summary.json
// (max_<line>_top_tension, max_<body>_depth, final_<column>, ...).
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "sweep.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/network_output.hpp"
#include "towsim/sim/network_discretisation.hpp"
#include "towsim/sim/simulate_network.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;

namespace {

/// The record of a case: a writer of the network's files in out_dir, or
/// (no out_dir) a record in memory. Takes the directory's lock.
struct CaseFiles {
  CaseFiles(const Network& net, const std::string& out_dir, bool nodes) {
    if (out_dir.empty()) {
      record = std::make_unique<NetworkRecord>(net);
      return;
    }
    std::filesystem::create_directories(out_dir);
    lock = std::make_unique<DirLock>(out_dir);  // one towsim at a time in a directory
    remove_run_outputs(out_dir);
    auto w = std::make_unique<NetworkWriter>(out_dir, net, nodes);
    writer = w.get();
    record = std::move(w);
  }
  /// Write summary.json (with out_dir) and fail on any file's error.
  void finish(const std::string& out_dir, const nlohmann::ordered_json& summary) const {
    std::string why;
    if (!out_dir.empty() && !write_summary(out_dir, summary, &why)) throw std::runtime_error(why);
    if (writer != nullptr && !writer->error().empty()) throw std::runtime_error(writer->error());
  }
  std::unique_ptr<DirLock> lock;
  std::unique_ptr<NetworkRecord> record;
  NetworkWriter* writer = nullptr;
};

/// A case's outcome from its summary.
CaseResult from_summary(const nlohmann::ordered_json& summary) {
  CaseResult res;
  res.status = summary["status"].get<std::string>();
  res.message = summary["message"].is_string() ? summary["message"].get<std::string>() : std::string();
  res.figures = summary_figures(summary);
  return res;
}

}  // namespace

std::vector<std::string> network_figure_names(const Network& net) {
  auto summary = make_network_summary(nlohmann::ordered_json::object(), RunStats{}, NetworkRecord(net), false);
  summary["final"] = nlohmann::ordered_json::object();
  for (const auto& c : network_timeseries_columns(net)) summary["final"][c] = nullptr;
  std::vector<std::string> names;
  for (const auto& f : summary_figures(summary)) names.push_back(f.first);
  return names;
}

CaseResult run_network_case(const LoadedScenario& sc, const std::string& out_dir, const volatile int* stop_flag,
                            const ProgressFn& progress) {
  const Network& net = *sc.network;
  if (net.settings().initial.kind == Initial::Kind::Steady)
    if (const std::string why = network_steady_refusal(net); !why.empty())
      return {"invalid", "initial: steady: " + why, {}, {}};
  try {
    const bool nodes = net.settings().sim.write_nodes;
    CaseFiles files(net, out_dir, nodes);
    RunStats stats;
    try {
      stats = simulate_network(net, *files.record, progress, stop_flag);
      record_network_discretisation_estimate(net, stats, stop_flag);
    } catch (const std::exception& e) {
      stats.status = "failed";
      stats.message = std::string("internal error: ") + e.what();
    }
    files.record->flush();
    const auto summary = make_network_summary(to_json(sc.tree), stats, *files.record, nodes);
    files.finish(out_dir, summary);
    return from_summary(summary);
  } catch (const std::exception& e) {
    return {"failed", e.what(), {}, {}};
  }
}

CaseResult statics_network_case(const LoadedScenario& sc, const std::string& out_dir, const volatile int* stop_flag) {
  const Network& net = *sc.network;
  NetworkSteady st;
  try {
    st = network_statics(net, stop_flag);
  } catch (const std::invalid_argument& e) {
    return {"invalid", e.what(), {}, {}};
  } catch (const std::exception& e) {
    return {stop_flag != nullptr && *stop_flag ? "interrupted" : "failed", e.what(), {}, {}};
  }
  try {
    CaseFiles files(net, out_dir, true);
    RunStats stats = write_network_steady(net, st, *files.record);
    stats.steps = st.steps;
    files.record->flush();
    const auto summary = make_network_summary(to_json(sc.tree), stats, *files.record, true);
    files.finish(out_dir, summary);
    return from_summary(summary);
  } catch (const std::exception& e) {
    return {"failed", e.what(), {}, {}};
  }
}

}  // namespace towsim::cli
