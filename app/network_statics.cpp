// `towsim statics` on a network of lines (docs/scenario.md "Statics of a
// network"): the steady tow at the tow law's final velocity, printed per
// line, body and junction, and written as a one-sample run with --out.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "commands.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/network_output.hpp"
#include "towsim/sim/network_target_depth.hpp"
#include "towsim/sim/simulate_network.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;

namespace {

constexpr double kDeg = 180.0 / M_PI;

/// The steady tow as text: the relaxation, then every line, body and junction.
void print_network_statics(const Network& net, const NetworkSteady& st, const NetworkSample& smp, std::ostream& out) {
  out << std::setprecision(7) << "steady tow of " << net.name << " at V = (" << st.velocity.transpose()
      << ") m/s, |V| = " << st.velocity.norm() << " m/s\n";
  out << "  relaxed by the network's dynamics: " << st.relaxed_time << " s of simulated time in " << st.steps
      << " steps; joints left moving at " << std::setprecision(2) << st.residual_speed << " m/s relative to the tow\n"
      << std::setprecision(7);
  out << "  line: top tension [N], top force (x y z) [N], angle below horizontal at the top [deg], end depth [m]\n";
  for (std::size_t i = 0; i < smp.lines.size(); ++i) {
    const Sample& l = smp.lines[i];
    const Vec3 e = (l.node_pos.size() > 1 ? (l.node_pos[1] - l.node_pos[0]) : Vec3(0, 0, -1)).normalized();
    out << "    " << net.line_names[i] << ": " << l.tow_force.norm() << ", (" << l.tow_force.transpose() << "), "
        << std::asin(-e.z()) * kDeg << ", " << -l.node_pos.back().z() << "\n";
  }
  for (const NetworkBody& b : net.bodies) {
    const BodySample& bs = smp.lines[static_cast<std::size_t>(b.line)].bodies[static_cast<std::size_t>(b.body)];
    out << "  body " << b.name << ": depth " << -bs.pos.z() << " m, at (" << bs.pos.transpose()
        << ") m, roll/pitch/yaw (" << bs.rpy_deg.transpose() << ") deg, link tension " << bs.link_force.norm()
        << " N\n";
  }
  for (const NetworkJunction& j : net.junctions)
    out << "  junction " << j.name << ": depth " << -smp.lines[static_cast<std::size_t>(j.line)].node_pos.back().z()
        << " m\n";
}

/// --out: the steady tow as a network run's files, its one sample (at t = 0)
/// and that sample's statistics.
int write_network_statics(const LoadedScenario& sc, const Network& net, const NetworkSample& sample, RunStats stats,
                          const StaticsOptions& opts, std::ostream& err) {
  if (!create_output_dir(opts.out_dir, err)) return kExitError;
  try {
    const DirLock lock(opts.out_dir);
    remove_run_outputs(opts.out_dir);
    NetworkWriter writer(opts.out_dir, net, true);
    writer.write(sample);
    writer.flush();
    auto summary = make_network_summary(to_json(sc.tree), stats, writer, true);
    std::string why;
    if (!write_summary(opts.out_dir, summary, &why)) throw std::runtime_error(why);
    if (const std::string e = writer.error(); !e.empty()) throw std::runtime_error(e);
  } catch (const std::exception& e) {
    err << "towsim: " << e.what() << "\n";
    return kExitError;
  }
  return kExitOk;
}

}  // namespace

int statics_network(const LoadedScenario& sc, const Network& net, const StaticsOptions& opts, std::ostream& out,
                    std::ostream& err, const volatile int* stop_flag) {
  // What a network's statics does not do yet: refused before anything is written.
  if (!opts.trim_body.empty()) {
    err << "towsim: statics: --trim takes a single line (cable:), not a network yet\n";
    return kExitInvalid;
  }
  if (opts.target_depth && !(*opts.target_depth > 0)) {
    err << "towsim: statics: --target-depth must be > 0 (got " << fmt_num(*opts.target_depth) << ")\n";
    return kExitInvalid;
  }
  int line = -1;
  if (!opts.line.empty()) {
    if (!opts.target_depth) {
      err << "towsim: statics: --line goes with --target-depth (the line whose length it varies)\n";
      return kExitInvalid;
    }
    line = net.line_index(opts.line);
    if (line < 0 || net.tree.tops[static_cast<std::size_t>(line)].line >= 0) {
      std::string roots;
      for (std::size_t i = 0; i < net.line_names.size(); ++i)
        if (net.tree.tops[i].line < 0) roots += (roots.empty() ? "" : ", ") + net.line_names[i];
      err << "towsim: statics: --line " << opts.line << ": "
          << (line < 0 ? "no such line"
                       : "hangs from " + net.line_from[static_cast<std::size_t>(line)] + ", not from the vessel")
          << " (lines from the vessel: " << roots << ")\n";
      return kExitInvalid;
    }
  }
  NetworkSteady st;
  std::optional<NetworkTargetDepth> target;
  try {
    if (opts.target_depth) {
      target = network_length_for_depth(net, *opts.target_depth, stop_flag, line);
      if (!target->found)
        throw std::runtime_error("--target-depth " + fmt_num(*opts.target_depth) + ": " + target->message);
      st = target->steady;
      out << std::setprecision(7) << "deployed length of line "
          << net.line_names[static_cast<std::size_t>(target->line)] << " for a depth of " << fmt_num(*opts.target_depth)
          << " m: " << target->length << " m (deepest " << (net.bodies.empty() ? "line end" : "body")
          << (line >= 0 ? " below it" : "") << " at " << target->depth << " m; " << target->evaluations
          << " steady tows)\n";
    } else {
      st = network_statics(net, stop_flag);
    }
  } catch (const std::invalid_argument& e) {
    err << "towsim: statics: " << e.what() << "\n";
    return kExitInvalid;
  } catch (const std::exception& e) {
    if (stop_flag && *stop_flag) {
      err << "towsim: statics: interrupted\n";
      return kExitInterrupted;
    }
    err << "towsim: statics: " << e.what() << "\n";
    return kExitFailed;
  }
  const Network& used = target ? target->network : net;
  NetworkMemorySink mem;
  RunStats stats = write_network_steady(used, st, mem);
  stats.steps = st.steps;
  print_network_statics(used, st, mem.samples.front(), out);
  return opts.out_dir.empty() ? kExitOk : write_network_statics(sc, used, mem.samples.front(), stats, opts, err);
}

}  // namespace towsim::cli
