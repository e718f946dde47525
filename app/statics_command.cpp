// `towsim statics`: the steady-tow configuration of a scenario (docs/theory.md §7).
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <new>
#include <optional>
#include <stdexcept>

#include "commands.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/output.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim::io {

namespace {

constexpr double kDeg = 180.0 / M_PI;

/// Print the engineer's summary of a steady tow.
void print_statics(const Model& model, const StaticsResult& r, const Sample& s, std::ostream& out) {
  out << std::setprecision(6);
  const Vec3 F = r.tow_force;
  out << "steady tow at V = (" << r.tow_velocity.transpose() << ") m/s, |V| = " << r.tow_velocity.norm() << " m/s\n";
  out << "  converged: "
      << (r.converged     ? "yes"
          : r.interrupted ? "NO, interrupted"
                          : "NO")
      << " (" << r.iterations << " iterations, largest angular acceleration left " << r.residual << " rad/s^2)\n";
  out << "  tow force F_R = (" << F.transpose() << ") N, tension " << F.norm() << " N, "
      << std::atan2(F.z(), std::hypot(F.x(), F.y())) * kDeg << " deg above horizontal\n";
  const Vec3 end = s.node_pos.back() - s.tow_pos;
  out << "  cable end: depth " << -s.node_pos.back().z() << " m, " << std::hypot(end.x(), end.y())
      << " m horizontally from the tow point\n";
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodySample& bs = s.bodies[b];
    out << "  " << (model.bodies[b].inline_body ? "body " + model.bodies[b].name : std::string("body")) << ": depth "
        << -bs.pos.z() << " m, roll/pitch/yaw (" << bs.rpy_deg.transpose() << ") deg\n";
    out << "  link force F_L = (" << bs.link_force.transpose() << ") N, |F_L| = " << bs.link_force.norm() << " N\n";
    if (model.bodies[b].inline_body)
      out << "  lower link force = (" << bs.lower_link_force.transpose() << ") N, |F| = " << bs.lower_link_force.norm()
          << " N\n";
  }
  out << "  element  angle below horizontal [deg]  heading [deg]  tension at top [N]\n";
  for (std::size_t k = 0; k < model.cable.elements.size(); ++k) {
    const Vec3& e = r.state.e[k];
    out << "  " << std::setw(7) << k + 1 << "  " << std::setw(28) << std::asin(-e.z()) * kDeg << "  " << std::setw(13)
        << std::atan2(e.y(), e.x()) * kDeg << "  " << std::setw(18) << r.joint_force[k].norm() << "\n";
  }
}

}  // namespace

std::optional<Diagnostic> statics_refusal(const LoadedScenario& sc) {
  if (sc.model->tow.mode == Tow::Mode::Motion) return std::nullopt;
  const Where& w = sc.spec.tow.mode.where;
  return Diagnostic{w.loc, w.path, "statics needs mode: motion (the steady speed comes from the tow law; got force)"};
}

nlohmann::ordered_json statics_summary(const LoadedScenario& sc, const StaticsResult& r, RunRecord& rec) {
  rec.write(r.sample);
  rec.flush();
  RunStats stats;  // a statics "run": one sample at t = 0
  stats.status = r.converged ? "ok" : r.interrupted ? "interrupted" : "failed";
  stats.message = r.converged ? "" : r.message;
  stats.steps = r.iterations;
  auto summary = make_summary(to_json(sc.tree), sc.model->name, stats, rec, true);
  summary.erase("phases");  // a steady configuration: no manoeuvre phases
  return summary;
}

namespace {

/// The command; statics_command adds the out-of-memory message.
int statics_command_impl(const StaticsOptions& opts, std::ostream& out, std::ostream& err,
                         const volatile int* stop_flag) {
  const LoadedScenario sc = load_input(opts.input);
  if (!sc.ok()) {
    err << sc.diags.str();
    return kExitInvalid;
  }
  const Model& model = *sc.model;
  if (const auto refusal = statics_refusal(sc)) {
    // A rule between the command and the scenario, in the scenario's error format.
    err << refusal->str() << "\n";
    return kExitInvalid;
  }
  // --target-depth: the deployed length for that depth, and the statics there.
  std::optional<Model> deployed;
  std::optional<TargetDepthResult> target;
  if (opts.target_depth) {
    const double D = *opts.target_depth;
    if (!(D > 0)) {
      err << "towsim: statics: --target-depth must be > 0 (got " << fmt_num(D) << ")\n";
      return kExitInvalid;
    }
    target = length_for_depth(model, final_tow_velocity(model.tow), D, stop_flag);
    if (target->statics.interrupted) {
      err << "towsim: statics: --target-depth " << fmt_num(D) << ": interrupted\n";
      return kExitInterrupted;
    }
    if (!target->found) {
      err << "towsim: statics: --target-depth " << fmt_num(D) << ": " << target->message << "\n";
      return kExitFailed;
    }
    deployed = with_deployed_length(model, target->length);
    out << std::setprecision(7) << "deployed length for a depth of " << fmt_num(D) << " m: " << target->length << " m ("
        << (end_body(model) != nullptr ? "body" : "cable end") << " at " << target->depth << " m)\n";
  }
  const Model& used = deployed ? *deployed : model;
  const StaticsResult r = target ? target->statics : solve_statics(model, final_tow_velocity(model.tow), stop_flag);
  const Sample& s = r.sample;
  print_statics(used, r, s, out);
  if (!opts.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opts.out_dir, ec);
    if (ec) {
      err << "towsim: statics: " << opts.out_dir << ": cannot create the directory: " << ec.message() << "\n";
      return kExitError;
    }
    try {                                // an I/O failure (as `run`): exit 1 with the reason
      const DirLock lock(opts.out_dir);  // one towsim at a time in a directory
      remove_run_outputs(opts.out_dir);  // no stale file of a previous run
      RunWriter writer(opts.out_dir, used, true);
      auto summary = statics_summary(sc, r, writer);
      if (target)
        summary["target_depth"] = {{"depth", *opts.target_depth},
                                   {"deployed_length", target->length},
                                   {"reached_depth", target->depth}};
      std::string why;
      if (!writer.error().empty()) throw std::runtime_error(writer.error());
      if (!write_summary(opts.out_dir, summary, &why)) throw std::runtime_error(why);
    } catch (const std::runtime_error& e) {
      err << "towsim: statics: " << e.what() << "\n";
      return kExitError;
    }
    out << "  written: " << opts.out_dir << "/timeseries.csv, " << opts.out_dir << "/nodes.csv, " << opts.out_dir
        << "/summary.json\n";
  }
  if (r.interrupted) {
    err << "towsim: statics: " << r.message << " (the last iterate is printed"
        << (opts.out_dir.empty() ? "" : " and written") << ")\n";
    return kExitInterrupted;
  }
  if (!r.converged) {
    err << "towsim: statics: " << r.message << "\n";
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace

int statics_command(const StaticsOptions& opts, std::ostream& out, std::ostream& err, const volatile int* stop_flag) {
  try {
    return statics_command_impl(opts, out, err, stop_flag);
  } catch (const std::bad_alloc&) {
    err << "towsim: statics: out of memory (the model is too large for this machine)\n";
    return kExitError;
  }
}

}  // namespace towsim::io
