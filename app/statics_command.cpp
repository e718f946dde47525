// `towsim statics`: the steady-tow configuration of a scenario (docs/theory.md §7).
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/output.hpp"
#include "towsim/sim/statics.hpp"
#include "towsim/sim/touchdown.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;

namespace {

constexpr double kDeg = 180.0 / M_PI;

/// "body depressor" (an in-line body), "the body" (the end body).
std::string body_label(const Model& model, std::size_t b) {
  return model.bodies[b].inline_body ? "body " + model.bodies[b].name : std::string("the body");
}

/// A pitch as the warnings give it: "+24.3".
std::string signed_deg(double v) {
  std::ostringstream os;
  os << std::showpos << std::fixed << std::setprecision(1) << v;
  return os.str();
}

/// "two", "three", ... for the warnings' counts.
std::string count_word(std::size_t n) {
  static const char* const words[] = {"no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine"};
  return n < 10 ? words[n] : std::to_string(n);
}

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
    if (b < r.equilibria.size() && r.equilibria[b].analysed) {
      const BodyEquilibria& eq = r.equilibria[b];
      out << "  equilibria of " << body_label(model, b) << " (its balances from " << kBodyStarts
          << " starts, stiffness about its x, y, z axes):\n";
      for (std::size_t i = 0; i < eq.balances.size(); ++i) {
        const BodyEquilibrium& e = eq.balances[i];
        out << "    roll/pitch/yaw (" << e.rpy_deg.transpose() << ") deg: " << (e.stable ? "stable" : "unstable")
            << ", stiffness (" << e.stiffness.transpose() << ") N m/rad"
            << (static_cast<int>(i) == eq.chosen ? ", reported" : "") << "\n";
      }
    }
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
  if (sc.is_network() || sc.model->tow.mode == Tow::Mode::Motion) return std::nullopt;
  const Where& w = sc.spec.tow.mode.where;
  return Diagnostic{w.loc, w.path, "statics needs mode: motion (the steady speed comes from the tow law; got force)"};
}

std::vector<std::string> equilibria_warnings(const Model& model, const StaticsResult& r) {
  std::vector<std::string> out;
  for (std::size_t b = 0; b < r.equilibria.size() && b < model.bodies.size(); ++b) {
    const BodyEquilibria& eq = r.equilibria[b];
    if (!eq.analysed || eq.chosen < 0) continue;
    const BodyEquilibrium& chosen = eq.balances[static_cast<std::size_t>(eq.chosen)];
    std::vector<std::string> stable;
    for (const BodyEquilibrium& e : eq.balances)
      if (e.stable) stable.push_back(signed_deg(e.rpy_deg.y()));
    std::string list;
    for (std::size_t i = 0; i < stable.size(); ++i)
      list += (i == 0 ? "" : i + 1 == stable.size() ? " and " : ", ") + stable[i];
    const std::string who = "trim of " + body_label(model, b) + ": ";
    if (!chosen.stable)
      out.push_back(
          who + "the equilibrium reported, " + signed_deg(chosen.rpy_deg.y()) + " deg pitch, is statically unstable" +
          (stable.empty() ? std::string(" (no stable one found)")
                          : "; stable: " + list + " deg pitch (an initial_attitude_deg near one selects it)"));
    else if (stable.size() > 1)
      out.push_back(who + count_word(stable.size()) + " stable equilibria, " + list + " deg pitch; reported " +
                    signed_deg(chosen.rpy_deg.y()) +
                    ", the one reached from its initial attitude (an initial_attitude_deg near another selects it)");
  }
  return out;
}

nlohmann::ordered_json bodies_json(const Model& model, const StaticsResult& r) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    nlohmann::ordered_json j;
    j["name"] = model.bodies[b].inline_body ? model.bodies[b].name : std::string("body");
    const bool analysed = b < r.equilibria.size() && r.equilibria[b].analysed;
    if (!analysed) {
      j["equilibria"] = nullptr;
      j["chosen"] = nullptr;
    } else {
      const BodyEquilibria& eq = r.equilibria[b];
      j["equilibria"] = nlohmann::ordered_json::array();
      for (const BodyEquilibrium& e : eq.balances)
        j["equilibria"].push_back({{"roll_deg", e.rpy_deg.x()},
                                   {"pitch_deg", e.rpy_deg.y()},
                                   {"yaw_deg", e.rpy_deg.z()},
                                   {"stable", e.stable},
                                   {"roll_stiffness", e.stiffness.x()},
                                   {"pitch_stiffness", e.stiffness.y()},
                                   {"yaw_stiffness", e.stiffness.z()},
                                   {"min_stiffness", e.min_stiffness}});
      j["chosen"] = eq.chosen;
    }
    list.push_back(j);
  }
  return list;
}

nlohmann::ordered_json statics_summary(const LoadedScenario& sc, const StaticsResult& r, RunRecord& rec) {
  rec.write(r.sample);
  rec.flush();
  RunStats stats;  // a statics "run": one sample at t = 0
  stats.status = r.converged ? "ok" : r.interrupted ? "interrupted" : "failed";
  stats.message = r.converged ? "" : r.message;
  stats.steps = r.iterations;
  stats.warnings = equilibria_warnings(*sc.model, r);
  auto summary = make_summary(to_json(sc.tree), sc.model->name, stats, rec, true);
  if (!sc.model->bodies.empty()) summary["bodies"] = bodies_json(*sc.model, r);
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
  if (const auto refusal = statics_refusal(sc)) {
    // A rule between the command and the scenario, in the scenario's error format.
    err << refusal->str() << "\n";
    return kExitInvalid;
  }
  if (sc.is_network()) return statics_network(sc, *sc.network, opts, out, err, stop_flag);
  if (!opts.line.empty()) {
    err << "towsim: statics: --line chooses a network's line (lines:); a single cable has one\n";
    return kExitInvalid;
  }
  const Model& model = *sc.model;
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
  // --trim: the link point x for the body's pitch, and the statics there.
  std::optional<TrimResult> trim;
  if (!opts.trim_body.empty()) {
    std::size_t b = model.bodies.size();
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      if ((model.bodies[i].inline_body ? model.bodies[i].name : std::string("body")) == opts.trim_body) b = i;
    if (b == model.bodies.size() || opts.target_depth) {
      std::string names;
      for (const Body& body : model.bodies)
        names += (names.empty() ? "" : ", ") + (body.inline_body ? body.name : std::string("body"));
      err << "towsim: statics: --trim " << opts.trim_body << ": "
          << (opts.target_depth
                  ? std::string("not with --target-depth")
                  : "no such body (the scenario's: " + (names.empty() ? std::string("none") : names) + ")")
          << "\n";
      return kExitInvalid;
    }
    trim = link_point_for_pitch(model, final_tow_velocity(model.tow), b, opts.trim_pitch, stop_flag);
    if (trim->statics.interrupted) {
      err << "towsim: statics: --trim " << opts.trim_body << ": interrupted\n";
      return kExitInterrupted;
    }
    if (!trim->found) {
      err << "towsim: statics: --trim " << opts.trim_body << ": " << trim->message << "\n";
      return kExitFailed;
    }
    deployed = model;
    deployed->bodies[b].link_point.x() = trim->link_x;
    std::string key = "body.link_point";
    for (const BodySpec& spec : sc.spec.cable.inline_bodies)
      if (model.bodies[b].inline_body && spec.name.value == model.bodies[b].name) key = spec.where.path + ".link_point";
    const Vec3 lp = deployed->bodies[b].link_point;
    std::ostringstream set;
    set << std::setprecision(17) << key << "=[" << lp.x() << ", " << lp.y() << ", " << lp.z() << "]";
    out << std::setprecision(7) << "link point for a pitch of " << fmt_num(opts.trim_pitch) << " deg of "
        << body_label(model, b) << ": x = " << trim->link_x << " m (pitch " << trim->pitch_deg << " deg; --set '"
        << set.str() << "')\n";
  }
  // Over a flat seabed: the steady tow with a joint at its touchdown.
  std::optional<TouchdownStatics> td;
  if (!target && !trim) td = touchdown_statics(model, final_tow_velocity(model.tow), stop_flag);
  const Model& used = deployed ? *deployed : td ? td->model : model;
  const StaticsResult r = target ? target->statics : trim ? trim->statics : td->statics;
  const Sample& s = r.sample;
  print_statics(used, r, s, out);
  if (td && td->split_element >= 0)
    out << std::setprecision(7) << "  touchdown joint: element " << td->split_element + 1 << " split " << td->split_arc
        << " m from its top, where the cable meets the bottom (" << used.cable.n() << " elements)\n";
  for (const std::string& w : equilibria_warnings(used, r)) err << "towsim: statics: warning: " << w << "\n";
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
      if (trim) summary["trim"] = {{"body", opts.trim_body}, {"pitch_deg", opts.trim_pitch}, {"link_x", trim->link_x}};
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

}  // namespace towsim::cli
