// The run loop for a network (towsim/sim/simulate_network.hpp).
#include "towsim/sim/simulate_network.hpp"

#include <chrono>
#include <stdexcept>

#include "run_checks.hpp"
#include "run_loop.hpp"
#include "towsim/integrators/network_system.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim {

namespace {

/// The network's rig for the run loop (src/sim/run_loop.hpp).
struct NetworkRig {
  NetworkRig(const Network& n, NetworkSink& sink) : net(n), sink(sink), system(n) {
    out.lines.resize(n.tree.lines.size());
  }
  const Network& net;
  NetworkSink& sink;
  NetworkSystem system;
  std::string refusal;  // a refusal from the rk4 stability check
  TreeState checked;    // the state of the last step checked (storage reused)
  NetworkSample out;    // the sample being written (its storage reused)

  const Simulation& sim() const { return net.settings().sim; }
  bool winch() const { return false; }
  bool sea() const { return net.settings().fluid.waves != nullptr; }  // waves (a tow point alone gives a vessel)
  double force_scale() const {
    double w = 0;
    for (const Model& m : net.tree.lines) w += run::force_scale(m);
    return w;
  }
  std::vector<double> breakpoints() const { return tow_breakpoints(net.settings().tow); }
  System& sys() { return system; }
  /// Every row finite, every line sound (the line named).
  std::string check(const System& sys, const StateVector& y) {
    if (std::string err = run::check_finite(sys, y); !err.empty()) return err;
    system.tree_state_into(y, checked);
    for (std::size_t i = 0; i < checked.size(); ++i)
      if (std::string err = run::check_chain(net.tree.lines[i], checked[i]); !err.empty())
        return "line " + net.line_names[i] + ": " + err;
    return {};
  }
  bool event_due(const System&, const StateVector&) const { return false; }
  void track(const System&, const StateVector&, double, RunStats&) const {}
  void event(StateVector&, double, RunStats&) {}
  /// Each line's sample at (y, t), from one evaluation of the tree.
  void write(const StateVector& y, double t, RunStats& stats) {
    const TreeWorkspace& ws = system.evaluate_tree(y, t);
    const TreeState& s = system.evaluated_state();
    out.t = t;
    for (std::size_t i = 0; i < s.size(); ++i) {
      std::string err;
      run::sample_checks(net.tree.lines[i], s[i], ws.lines[i], t, stats, out.lines[i], &err);
      if (!err.empty() && refusal.empty()) refusal = "line " + net.line_names[i] + ": " + err;
    }
    sink.write(out);
  }
  void flush() { sink.flush(); }
};

}  // namespace

RunStats simulate_network(const Network& net, NetworkSink& sink, const ProgressFn& progress,
                          const volatile int* stop_flag) {
  RunStats stats;
  const Model& settings = net.settings();
  stats.integrator = integrator_key(settings.sim.integrator);
  stats.threads = 1;
  const auto wall0 = std::chrono::steady_clock::now();
  NetworkRig rig(net, sink);
  StateVector y;
  try {
    // The tree's impulsive response is not computed: a jump of the tow velocity is refused before the run.
    if (rig.system.has_nodes())
      for (double b : rig.breakpoints())
        if (b <= settings.sim.duration && rig.system.tow_jump(b) > NetworkSystem::kRoundOffJump)
          throw std::runtime_error("the tow velocity jumps at t = " + std::to_string(b) +
                                   " s (the start of a heave or a track): a network with lines below a junction or "
                                   "body takes a tow law whose velocity is continuous");
    y = rig.system.initial_tree(network_initial_state(net));
    rig.system.apply_tow_jump(y, 0.0);  // at rest, tow at speed
  } catch (const std::exception& e) {
    stats.status = "failed";
    stats.message = e.what();
    sink.flush();
    return stats;
  }
  rig.system.project(y, 0.0);
  rig.write(y, 0.0, stats);
  return run::run_loop(rig, y, std::move(stats), wall0, progress, stop_flag);
}

}  // namespace towsim
