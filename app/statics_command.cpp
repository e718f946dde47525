// `towsim statics`: the steady-tow configuration of a scenario (docs/theory.md §7).
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "towsim/dynamics/dynamics.hpp"
#include "commands.hpp"
#include "towsim/output/output.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim::io {

namespace {

constexpr double kDeg = 180.0 / M_PI;

/// The statics result as one output sample (every point moving at V).
Sample statics_sample(const Model& model, const StaticsResult& r) {
  Workspace ws(model);
  compute_kinematics(model, r.state, ws);
  Sample s;
  s.t = 0;
  s.tow_pos = ws.P.front();
  s.tow_vel = r.tow_velocity;
  s.tow_force = r.tow_force;
  s.node_pos = ws.P;
  s.node_vel = ws.vP;
  for (const Vec3& f : r.joint_force) s.tension.push_back(f.norm());
  s.has_body = model.has_body;
  if (model.has_body) {
    s.body_pos = ws.O;
    s.body_vel = ws.vO;
    s.body_rpy_deg = roll_pitch_yaw(r.state.q) * kDeg;
    s.body_omega = Vec3::Zero();
    s.link_force = r.link_force;
  }
  return s;
}

/// Print the engineer's summary of a steady tow.
void print_statics(const Model& model, const StaticsResult& r, const Sample& s, std::ostream& out) {
  out << std::setprecision(6);
  const Vec3 F = r.tow_force;
  out << "steady tow at V = (" << r.tow_velocity.transpose() << ") m/s, |V| = " << r.tow_velocity.norm() << " m/s\n";
  out << "  converged: " << (r.converged ? "yes" : "NO") << " (" << r.iterations
      << " iterations, largest angular acceleration left " << r.residual << " rad/s^2)\n";
  out << "  tow force F_R = (" << F.transpose() << ") N, tension " << F.norm() << " N, "
      << std::atan2(F.z(), std::hypot(F.x(), F.y())) * kDeg << " deg above horizontal\n";
  const Vec3 end = s.node_pos.back() - s.tow_pos;
  out << "  cable end: depth " << -s.node_pos.back().z() << " m, " << std::hypot(end.x(), end.y())
      << " m horizontally from the tow point\n";
  if (model.has_body) {
    out << "  body: depth " << -s.body_pos.z() << " m, roll/pitch/yaw (" << s.body_rpy_deg.transpose()
        << ") deg\n";
    out << "  link force F_L = (" << r.link_force.transpose() << ") N, |F_L| = " << r.link_force.norm() << " N\n";
  }
  out << "  element  angle below horizontal [deg]  heading [deg]  tension at top [N]\n";
  for (int k = 0; k < model.cable.n(); ++k) {
    const Vec3& e = r.state.e[k];
    out << "  " << std::setw(7) << k + 1 << "  " << std::setw(28) << std::asin(-e.z()) * kDeg << "  "
        << std::setw(13) << std::atan2(e.y(), e.x()) * kDeg << "  " << std::setw(18) << s.tension[k] << "\n";
  }
}

}  // namespace

int statics_command(const StaticsOptions& opts, std::ostream& out, std::ostream& err) {
  const LoadedScenario sc = load_input(opts.input);
  if (!sc.ok()) {
    err << sc.diags.str();
    return kExitInvalid;
  }
  const Model& model = *sc.model;
  if (model.tow.mode != Tow::Mode::Motion) {
    err << "towsim: statics: tow.mode: statics needs mode: motion (the steady speed comes from the tow law)\n";
    return kExitInvalid;
  }
  const StaticsResult r = solve_statics(model, final_tow_velocity(model.tow));
  const Sample s = statics_sample(model, r);
  print_statics(model, r, s, out);
  if (!opts.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opts.out_dir, ec);
    if (ec) {
      err << "towsim: statics: " << opts.out_dir << ": cannot create the directory: " << ec.message() << "\n";
      return kExitError;
    }
    RunWriter writer(opts.out_dir, model.has_body, true);
    writer.write(s);
    writer.flush();
    out << "  written: " << opts.out_dir << "/timeseries.csv, " << opts.out_dir << "/nodes.csv\n";
  }
  if (!r.converged) {
    err << "towsim: statics: " << r.message << "\n";
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace towsim::io
