// towsim._towsim: the C++ core of the Python package `towsim`
// (python/towsim/__init__.py turns its plain results into Result objects and
// exceptions). Columns and figures come from the code that writes the files
// (io/output, io/sweep), so Python and the CLI agree by construction.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <future>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "sweep.hpp"
#include "towsim/output/network_output.hpp"
#include "towsim/output/output.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/sim/discretisation.hpp"
#include "towsim/sim/network_discretisation.hpp"
#include "towsim/sim/network_target_depth.hpp"
#include "towsim/sim/simulate_network.hpp"
#include "towsim/sim/statics.hpp"
#include "towsim/sim/touchdown.hpp"

namespace py = pybind11;
using namespace towsim;
using namespace towsim::scenario;
using namespace towsim::output;
using namespace towsim::cli;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Load a scenario: kind "file" (source = path), "example" (source = name) or
/// "text" (source = YAML, `label` names it in messages; relative track files
/// are read from the working directory).
LoadedScenario load(const std::string& kind, const std::string& source, const std::string& label,
                    const std::vector<std::string>& sets) {
  if (kind == "file") return load_scenario_file(source, sets);
  if (kind == "example") return load_input(InputOptions{"", source, sets});
  return load_scenario_text(source, label, "scenario", "", sets);
}

/// A NumPy array owning `v`, of the given shape (C order).
py::array_t<double> to_array(std::vector<double>&& v, const std::vector<py::ssize_t>& shape) {
  auto* owned = new std::vector<double>(std::move(v));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(shape, owned->data(), owner);
}

/// Every sample's timeseries row and nodes, in the columns of the files.
class ArraySink : public RunRecord {
 public:
  ArraySink(const Model& model, bool nodes) : RunRecord(model), keep_nodes_(nodes) {}
  void write(const Sample& s) override {
    RunRecord::write(s);
    series.insert(series.end(), last_row().begin(), last_row().end());
    if (!keep_nodes_) return;
    std::vector<double> row;
    for (std::size_t k = 0; k < s.node_pos.size(); ++k) node_values(model(), s, k, row);
    joints = std::max(joints, s.node_pos.size());
    nodes.push_back(std::move(row));
  }
  /// The nodes as one time x joint x component block (NaN where a sample has fewer joints).
  std::vector<double> node_block() const {
    const std::size_t c = node_columns(model()).size();
    std::vector<double> out(nodes.size() * joints * c, kNaN);
    for (std::size_t t = 0; t < nodes.size(); ++t)
      std::copy(nodes[t].begin(), nodes[t].end(), out.begin() + t * joints * c);
    return out;
  }

  std::vector<double> series;
  std::vector<std::vector<double>> nodes;
  std::size_t joints = 0;

 private:
  bool keep_nodes_;
};

/// A network's samples: every timeseries row, and each line's nodes.
class NetworkArraySink : public NetworkRecord {
 public:
  NetworkArraySink(const Network& net, bool nodes)
      : NetworkRecord(net), keep_nodes_(nodes), lines_(net.tree.lines.size()) {}
  void write(const NetworkSample& s) override {
    NetworkRecord::write(s);
    const std::vector<double> row = last_row();  // as written
    series.insert(series.end(), row.begin(), row.end());
    if (!keep_nodes_) return;
    for (std::size_t i = 0; i < s.lines.size(); ++i) {
      std::vector<double> row;
      for (std::size_t k = 0; k < s.lines[i].node_pos.size(); ++k) network_node_values(network(), s.lines[i], k, row);
      lines_[i].joints = std::max(lines_[i].joints, s.lines[i].node_pos.size());
      lines_[i].rows.push_back(std::move(row));
    }
  }
  /// Line i's nodes as one time x joint x component block (NaN where a sample has fewer joints).
  py::array_t<double> node_block(std::size_t i) const {
    const std::size_t c = network_node_columns(network()).size(), j = lines_[i].joints;
    const auto& rows = lines_[i].rows;
    std::vector<double> out(rows.size() * j * c, kNaN);
    for (std::size_t t = 0; t < rows.size(); ++t) std::copy(rows[t].begin(), rows[t].end(), out.begin() + t * j * c);
    return to_array(std::move(out),
                    {static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(j), static_cast<py::ssize_t>(c)});
  }

  std::vector<double> series;

 private:
  struct Line {
    std::vector<std::vector<double>> rows;  // per sample: its joints' columns, one after the other
    std::size_t joints = 0;
  };
  bool keep_nodes_;
  std::vector<Line> lines_;
};

/// Polls Python's signal handlers from the main thread while the GIL is
/// released, at most every 50 ms: Ctrl-C sets the run's stop flag.
class SignalPoll {
 public:
  explicit SignalPoll(volatile int& stop) : stop_(stop) {
    const auto main = py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
    on_main_ = PyThread_get_thread_ident() == main;
  }
  void operator()() {
    if (!on_main_) return;  // Python runs signal handlers only in the main thread
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(50)) return;
    last_ = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();  // re-raised by the package as towsim.Interrupted (a KeyboardInterrupt)
      interrupted = true;
      stop_ = 1;
    }
  }
  bool interrupted = false;

 private:
  volatile int& stop_;
  bool on_main_ = false;
  std::chrono::steady_clock::time_point last_{};
};

/// Now on the steady clock (CLOCK_MONOTONIC on Linux, as Python's time.monotonic()) [s].
double monotonic_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The summary as JSON text (the package parses it into a dict).
std::string json_text(const nlohmann::ordered_json& j) {
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

/// Text for Python: UTF-8, with invalid bytes (a scenario in another
/// encoding, quoted in a message) as U+FFFD, as in summary.json.
py::str text(const std::string& s) {
  return py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(s.data(), static_cast<py::ssize_t>(s.size()), "replace"));
}

/// A run's integration with the GIL released: simulate(progress, stop)
/// (an exception: a failed run), its wall-clock interval into (t0, t1)
/// [s, CLOCK_MONOTONIC = Python's time.monotonic()], then estimate(stats, stop)
/// (the discretisation estimate, after the interval).
template <class Simulate, class Estimate>
RunStats integrate(SignalPoll& poll, volatile int& stop, double& t0, double& t1, const Simulate& simulate_run,
                   const Estimate& estimate) {
  RunStats stats;
  py::gil_scoped_release release;
  t0 = monotonic_seconds();
  try {
    stats = simulate_run([&poll](double) { poll(); }, &stop);
  } catch (const std::exception& e) {
    stats.status = "failed";
    stats.message = std::string("internal error: ") + e.what();
  }
  t1 = monotonic_seconds();
  estimate(stats, &stop);
  return stats;
}

/// The keys every towsim.run result has after its arrays: the summary,
/// status, message, Ctrl-C and the integration's interval.
void put_run_end(py::dict& out, const nlohmann::ordered_json& summary, const RunStats& stats, const SignalPoll& poll,
                 double t0, double t1) {
  out["summary"] = json_text(summary);
  out["status"] = stats.status;
  out["message"] = text(stats.message);
  out["keyboard_interrupt"] = poll.interrupted;
  out["integration_interval"] = py::make_tuple(t0, t1);
}

/// towsim.run on a network: as a chain's, the nodes a dict of line name ->
/// time x joint x component.
py::dict run_network_arrays(const LoadedScenario& sc, py::dict out) {
  const Network& net = *sc.network;
  const bool keep_nodes = net.settings().sim.write_nodes;
  NetworkArraySink sink(net, keep_nodes);
  volatile int stop = 0;
  SignalPoll poll(stop);
  if (net.settings().initial.kind == Initial::Kind::Steady)
    if (const std::string why = network_steady_refusal(net); !why.empty()) {
      out["errors"] = text("initial: steady: " + why + "\n");
      return out;
    }
  double t0 = 0, t1 = 0;
  const RunStats stats = integrate(
      poll, stop, t0, t1,
      [&](const ProgressFn& progress, const volatile int* flag) { return simulate_network(net, sink, progress, flag); },
      [&](RunStats& st, const volatile int* flag) { record_network_discretisation_estimate(net, st, flag); });
  const auto summary = make_network_summary(to_json(sc.tree), stats, sink, keep_nodes);
  const auto columns = network_timeseries_columns(net);
  const auto rows = static_cast<py::ssize_t>(sink.samples());
  out["columns"] = columns;
  out["series"] = to_array(std::move(sink.series), {rows, static_cast<py::ssize_t>(columns.size())});
  out["node_columns"] = network_node_columns(net);
  if (keep_nodes) {
    py::dict nodes;
    for (std::size_t i = 0; i < net.line_names.size(); ++i) nodes[py::str(net.line_names[i])] = sink.node_block(i);
    out["nodes"] = nodes;
  } else {
    out["nodes"] = py::none();
  }
  put_run_end(out, summary, stats, poll, t0, t1);
  return out;
}

/// towsim.run: simulate; series and nodes in memory; GIL released while integrating.
py::dict run(const std::string& kind, const std::string& source, const std::string& label,
             const std::vector<std::string>& sets) {
  py::dict out;
  const LoadedScenario sc = load(kind, source, label, sets);
  if (!sc.ok()) {
    out["errors"] = text(sc.diags.str());
    return out;
  }
  if (sc.is_network()) return run_network_arrays(sc, out);
  const Model& model = *sc.model;
  ArraySink sink(model, model.sim.write_nodes);
  volatile int stop = 0;
  SignalPoll poll(stop);
  double t0 = 0, t1 = 0;
  const RunStats stats = integrate(
      poll, stop, t0, t1,
      [&](const ProgressFn& progress, const volatile int* flag) { return simulate(model, sink, progress, flag); },
      [&](RunStats& st, const volatile int* flag) { record_discretisation_estimate(model, st, flag); });
  const auto summary = make_summary(to_json(sc.tree), model.name, stats, sink, model.sim.write_nodes);
  const auto columns = timeseries_columns(model);
  const auto rows = static_cast<py::ssize_t>(sink.samples());
  out["columns"] = columns;
  out["series"] = to_array(std::move(sink.series), {rows, static_cast<py::ssize_t>(columns.size())});
  out["node_columns"] = node_columns(model);
  if (model.sim.write_nodes)
    out["nodes"] = to_array(sink.node_block(), {rows, static_cast<py::ssize_t>(sink.joints),
                                                static_cast<py::ssize_t>(node_columns(model).size())});
  else
    out["nodes"] = py::none();
  put_run_end(out, summary, stats, poll, t0, t1);
  return out;
}

/// towsim.statics on a network: its steady tow (network_statics, or
/// network_length_for_depth with target_depth > 0); the nodes a dict of line
/// name -> joint x component; iterations: the relaxation's steps, residual:
/// the joints' speed left [m/s]. Values NaN when it fails.
py::dict statics_network_arrays(const LoadedScenario& sc, double target_depth, const std::string& line_name,
                                py::dict out) {
  const Network& net = *sc.network;
  const bool with_target = !std::isnan(target_depth);
  // The line from the vessel that target_depth varies (-1: the network's one).
  int line = -1;
  if (!line_name.empty()) {
    line = net.line_index(line_name);
    if (line >= 0 && net.tree.tops[static_cast<std::size_t>(line)].line >= 0) line = -1;  // not from the vessel
    if (line < 0 || !with_target) {
      out["errors"] = text("line: " + line_name +
                           (with_target ? ": no line of that name from the vessel\n" : ": goes with target_depth\n"));
      return out;
    }
  }
  NetworkSteady st;
  std::optional<NetworkTargetDepth> target;
  std::string invalid, message;
  bool converged = true;
  volatile int stop = 0;
  SignalPoll poll(stop);
  {
    // The relaxation in a worker thread; this (main) thread polls Ctrl-C meanwhile.
    py::gil_scoped_release release;
    auto solve = std::async(std::launch::async, [&] {
      try {
        if (with_target) {
          target = network_length_for_depth(net, target_depth, &stop, line);
          if (!target->found) throw std::runtime_error(target->message);
          st = target->steady;
        } else {
          st = network_statics(net, &stop);
        }
      } catch (const std::invalid_argument& e) {
        invalid = e.what();
      } catch (const std::exception& e) {
        converged = false;
        message = stop ? "interrupted" : e.what();
      }
    });
    while (solve.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) poll();
    solve.get();
  }
  if (!invalid.empty()) {
    out["errors"] = text("statics: " + invalid + "\n");
    return out;
  }
  const Network& used = target && target->found ? target->network : net;
  const auto columns = network_timeseries_columns(used);
  const auto node_cols = network_node_columns(used);
  std::vector<double> row(columns.size(), kNaN);
  py::dict nodes;
  if (converged) {
    NetworkMemorySink mem;
    write_network_steady(used, st, mem);
    const NetworkSample& smp = mem.samples.front();
    NetworkRecord record(used);
    record.write(smp);
    row = record.last_row();  // as written
    for (std::size_t i = 0; i < smp.lines.size(); ++i) {
      std::vector<double> v;
      for (std::size_t k = 0; k < smp.lines[i].node_pos.size(); ++k) network_node_values(used, smp.lines[i], k, v);
      nodes[py::str(used.line_names[i])] = to_array(std::move(v),
                                                    {static_cast<py::ssize_t>(smp.lines[i].node_pos.size()),
                                                     static_cast<py::ssize_t>(node_cols.size())});
    }
  }
  if (with_target) out["deployed_length"] = target && target->found ? target->length : kNaN;
  out["columns"] = columns;
  out["values"] = to_array(std::move(row), {static_cast<py::ssize_t>(columns.size())});
  out["node_columns"] = node_cols;
  out["nodes"] = nodes;
  out["converged"] = converged;
  out["iterations"] = static_cast<long>(st.steps);
  out["residual"] = converged ? st.residual_speed : kNaN;
  out["message"] = text(message);
  out["tow_velocity"] = std::vector<double>{st.velocity.x(), st.velocity.y(), st.velocity.z()};
  out["keyboard_interrupt"] = poll.interrupted;
  return out;
}

/// towsim.statics: the steady-tow equilibrium at the tow law's final speed.
/// With target_depth > 0 (NaN: none), first the deployed length for that depth
/// (`towsim statics --target-depth`).
py::dict statics(const std::string& kind, const std::string& source, const std::string& label,
                 const std::vector<std::string>& sets, double target_depth, const std::string& line) {
  py::dict out;
  const LoadedScenario sc = load(kind, source, label, sets);
  if (!sc.ok()) {
    out["errors"] = text(sc.diags.str());
    return out;
  }
  if (sc.is_network()) return statics_network_arrays(sc, target_depth, line, out);
  if (!line.empty()) {
    out["errors"] = "line: chooses a network's line (lines:); a single cable has one\n";
    return out;
  }
  const Model& given = *sc.model;
  if (given.tow.mode != Tow::Mode::Motion) {
    out["errors"] = "tow.mode: statics needs mode: motion (the steady speed comes from the tow law)\n";
    return out;
  }
  std::optional<TouchdownStatics> td;  // without a target depth: the touchdown joint over a flat seabed
  StaticsResult r;
  Sample s;
  TargetDepthResult target;
  const bool with_target = !std::isnan(target_depth);
  volatile int stop = 0;
  SignalPoll poll(stop);
  {
    // The solve in a worker thread; this (main) thread polls Ctrl-C meanwhile.
    py::gil_scoped_release release;
    auto solve = std::async(std::launch::async, [&] {
      if (with_target) {
        target = length_for_depth(given, final_tow_velocity(given.tow), target_depth, &stop);
        r = target.statics;
        if (!target.found) r.converged = false, r.message = target.message;
      } else {
        td = touchdown_statics(given, final_tow_velocity(given.tow), &stop);
        r = td->statics;
      }
    });
    while (solve.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) poll();
    solve.get();
    s = r.sample;
  }
  const Model& model = td ? td->model : given;
  if (with_target) out["deployed_length"] = target.length;
  std::vector<double> row;
  timeseries_values(model, s, row);
  std::vector<double> nodes;
  for (std::size_t k = 0; k < s.node_pos.size(); ++k) node_values(model, s, k, nodes);
  const auto columns = timeseries_columns(model);
  out["columns"] = columns;
  out["values"] = to_array(std::move(row), {static_cast<py::ssize_t>(columns.size())});
  out["node_columns"] = node_columns(model);
  out["nodes"] = to_array(std::move(nodes), {static_cast<py::ssize_t>(s.node_pos.size()),
                                             static_cast<py::ssize_t>(node_columns(model).size())});
  out["converged"] = r.converged;
  out["iterations"] = r.iterations;
  out["residual"] = r.residual;
  out["message"] = text(r.message);
  out["tow_velocity"] = std::vector<double>{r.tow_velocity.x(), r.tow_velocity.y(), r.tow_velocity.z()};
  out["keyboard_interrupt"] = poll.interrupted;
  return out;
}

/// One sweep case, exactly as `towsim sweep` runs it (with `statics`, as a
/// `statics: true` sweep does): (status, message, [(figure, value)]). Ctrl-C
/// in a worker process's main thread ends the case `interrupted` (the
/// KeyboardInterrupt is cleared: the row says it).
py::tuple run_case_py(const std::string& kind, const std::string& source, const std::string& label,
                      const std::vector<std::string>& sets, const std::string& out_dir, bool statics) {
  CaseResult r;
  volatile int stop = 0;
  SignalPoll poll(stop);
  if (statics) {
    // The solve in a worker thread; this (main) thread polls Ctrl-C meanwhile.
    py::gil_scoped_release release;
    auto solve = std::async(std::launch::async, [&] {
      const LoadedScenario sc = load(kind, source, label, sets);
      r = statics_case(sc, out_dir, &stop);
    });
    while (solve.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) poll();
    solve.get();
  } else {
    py::gil_scoped_release release;
    const LoadedScenario sc = load(kind, source, label, sets);
    r = run_case(sc, out_dir, &stop, [&poll](double) { poll(); });
  }
  return py::make_tuple(r.status, text(r.message), r.figures);
}

/// The figures of a summary.json text, as the sweep tables name them.
std::vector<Figure> figures_of(const std::string& summary) {
  return summary_figures(nlohmann::ordered_json::parse(summary));
}

}  // namespace

PYBIND11_MODULE(_towsim, m) {
  m.doc() = "towsim C++ core (use the `towsim` package)";
  m.def("run", &run, py::arg("kind"), py::arg("source"), py::arg("label"), py::arg("sets"));
  m.def("statics", &statics, py::arg("kind"), py::arg("source"), py::arg("label"), py::arg("sets"),
        py::arg("target_depth") = std::numeric_limits<double>::quiet_NaN(), py::arg("line") = "");
  m.def("run_case", &run_case_py, py::arg("kind"), py::arg("source"), py::arg("label"), py::arg("sets"),
        py::arg("out_dir") = "", py::arg("statics") = false);
  m.def("towing_table_columns", &towing_table_columns);
  m.def("towing_row", &towing_row, py::arg("figures"));
  m.def("summary_figures", &figures_of, py::arg("summary_json"));
  m.def("examples", [] {
    std::vector<std::string> names;
    for (const auto& e : examples()) names.push_back(e.name);
    return names;
  });
  m.def("example_yaml", [](const std::string& name) -> py::object {
    const Example* e = find_example(name);
    if (e == nullptr) return py::none();
    return py::str(e->yaml);
  });
}
