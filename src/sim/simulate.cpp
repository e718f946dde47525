// The run loop: integrate, land on output times, check the state, write samples.
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/touchdown.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/sim/statics.hpp"
#include "towsim/sim/winch_events.hpp"
#include "towsim/waves/vessel.hpp"

#include "run_checks.hpp"
#include "run_loop.hpp"

namespace towsim {

namespace {

constexpr double kRad2Deg = 180.0 / M_PI;

/// The touchdown point of a sample (the first point of the cable below the
/// bottom from the top, along the elements' segments, element_seabed_contact),
/// its arc length along the elements, and the cable length beyond it.
void touchdown_sample(const Model& model, const Workspace& ws, Sample& out) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.touchdown_arc_length = nan;
  out.touchdown = Vec3::Constant(nan);
  out.lying_length = 0;
  if (!model.seabed) return;
  double arc = 0;  // [m]
  for (std::size_t k = 0; k < model.cable.elements.size(); ++k) {
    if (std::isnan(out.touchdown_arc_length)) {
      const SegmentContact c = element_seabed_contact(model, ws, k);
      if (!std::isnan(c.first)) {
        const int b = ws.body_at[k + 1];
        const bool inl = b >= 0 && model.bodies[static_cast<std::size_t>(b)].inline_body;
        const Vec3& bottom = inl ? ws.body[static_cast<std::size_t>(b)].Q : ws.P[k + 1];
        out.touchdown_arc_length = arc + c.first * ws.L[k];
        out.touchdown = ws.P[k] + c.first * (bottom - ws.P[k]);
      }
    }
    arc += ws.L[k];
  }
  if (!std::isnan(out.touchdown_arc_length)) out.lying_length = arc - out.touchdown_arc_length;
}

}  // namespace

Sample make_sample(const Model& model, const PhysicalState& s, const Workspace& ws, double t) {
  Sample out;
  make_sample(model, s, ws, t, out);
  return out;
}

void make_sample(const Model& model, const PhysicalState& s, const Workspace& ws, double t, Sample& out) {
  // Every field set again; the vectors keep their storage.
  out.t = t;
  out.tow_pos = ws.P.front();
  out.tow_vel = ws.vP.front();
  out.tow_force = ws.acc.tow_force;
  out.deployed_length = 0;
  for (double L : ws.L) out.deployed_length += L;
  out.payout_speed = ws.winch ? payout_rate(model, s) : 0.0;
  // A node: position, velocity, force through it onto the part below, that
  // force along the adjacent element el's axis e (tension pulls the part
  // below back along -e), el's strain and, with breaking loads, the node's
  // utilisation from el's section; fs: the seabed's force there; M: the
  // bending spring's moment there.
  const auto& els = model.cable.elements;
  const bool strength = std::any_of(model.cable.sections.begin(), model.cable.sections.end(),
                                    [](const Section& sec) { return sec.breaking_load > 0; });
  const bool bending = ws.bending;
  auto node = [&](const Vec3& p, const Vec3& v, const Vec3& f, std::size_t el, const Vec3& fs, const Vec3& M) {
    out.node_pos.push_back(p);
    out.node_vel.push_back(v);
    out.tension.push_back(f.norm());
    out.axial.push_back(-f.dot(s.e[el]));
    out.strain.push_back(is_elastic(model.cable.elements[el])
                             ? element_strain(current_element(model, ws, el), s.length_of(model, el))
                             : 0.0);
    if (strength) {
      const auto sec = static_cast<std::size_t>(els[el].section);
      const double limit = sec < model.cable.sections.size() ? model.cable.sections[sec].breaking_load : 0.0;
      out.utilisation.push_back(limit > 0 ? f.norm() / limit : 0.0);
    }
    if (model.seabed) out.node_seabed.push_back(fs);
    if (bending) out.bending.push_back(M.norm());
  };
  for (auto* v : {&out.node_pos, &out.node_vel, &out.node_seabed}) v->clear();
  for (auto* v : {&out.tension, &out.axial, &out.strain, &out.utilisation, &out.bending}) v->clear();
  out.contact_length = 0;
  const std::size_t n = els.size();
  for (std::size_t k = 0; k <= n; ++k) {
    const int b = k == 0 ? -1 : ws.body_at[k];
    const std::size_t above = k == 0 ? 0 : k - 1;
    if (b >= 0 && model.bodies[static_cast<std::size_t>(b)].inline_body) {
      const BodyWork& bw = ws.body[static_cast<std::size_t>(b)];
      node(bw.Q, bw.vQ, ws.acc.link_force[static_cast<std::size_t>(b)], above, bw.Fs_q, Vec3::Zero());
      node(ws.P[k], ws.vP[k], ws.acc.joint_force[k], k, ws.Fs[k], Vec3::Zero());
      out.contact_length += bw.ls_q;
    } else {
      node(ws.P[k], ws.vP[k], ws.acc.joint_force[k], above, ws.Fs[k], ws.bend[k]);
    }
    out.contact_length += ws.ls[k];
  }
  touchdown_sample(model, ws, out);
  out.seabed_normal = ws.seabed_normal;
  out.seabed_friction = ws.seabed_friction;
  out.bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyWork& bw = ws.body[b];
    BodySample& o = out.bodies[b];
    o.pos = bw.O;
    o.vel = bw.vO;
    o.rpy_deg = roll_pitch_yaw(s.bodies[b].q) * kRad2Deg;
    o.omega = bw.w;
    o.link_force = ws.acc.link_force[b];
    o.lower_link_force = ws.acc.lower_link_force[b];
    o.controls.clear();
    // Depth controllers: deflection, its rate and the depth error.
    std::size_t c = 0;
    for (const LiftingSurface& ls : model.bodies[b].surfaces) {
      if (!ls.depth_control) continue;
      const ControlState& cs = s.bodies[b].controls[c];
      const ControlRates r = depth_control_rates(*ls.depth_control, cs, -bw.O.z(), -bw.vO.z());
      o.controls.push_back({bw.deflection[c++] * kRad2Deg, r.ddeflection * kRad2Deg, r.error});
    }
  }
  out.has_waves = false;
  out.wave_elevation = 0;
  out.tow_wave = Vec3::Zero();
  if (has_sea(model)) sea_sample(model, t, out);
  out.node_id.resize(out.node_pos.size());
  for (std::size_t k = 0; k < out.node_id.size(); ++k) out.node_id[k] = static_cast<long>(k);
}

double rk4_step_limit(const Model& model, const Workspace& ws, double t, int* element, double* tension) {
  double best = std::numeric_limits<double>::infinity();
  const auto& els = model.cable.elements;
  const bool bending = ws.bending;
  for (std::size_t k = 0; k < els.size(); ++k) {
    const Element& el = current_element(model, ws, k);
    const int b = ws.body_at[k + 1];
    const Vec3& fb = b >= 0 ? ws.acc.link_force[static_cast<std::size_t>(b)] : ws.acc.joint_force[k + 1];
    const double T = std::max(ws.acc.joint_force[k].norm(), fb.norm());
    const double mn = el.mass + el.added_mass;
    // Rocking: omega^2 = 12 T / ((m + m_a) L). Drag damping at rate sigma
    // (normal: C / (m + m_a), along e: C / m) shifts the fast modes to
    // -sigma/2 +- i omega; RK4 is stable to |h lambda| ~ 2 sqrt(2) there.
    const Vec3 e = (ws.G[k] - ws.P[k]) * (2 / el.length);  // G = P_{k-1} + (L/2) e
    Mat3 C;
    double K = 0;
    element_local_jacobian(model, el, e, ws.vG[k], ws.G[k], t, ws.F[k], fb, C, K);
    const Mat3 P = Mat3::Identity() - e * e.transpose();
    // The largest eigenvalue of the projected damping, in closed form (3x3:
    // the trigonometric solution of the characteristic cubic, no iterations).
    Eigen::SelfAdjointEigenSolver<Mat3> eig;
    eig.computeDirect(P * C * P, Eigen::EigenvaluesOnly);
    const double sn = eig.eigenvalues().maxCoeff() / mn;
    const double sigma = std::max(sn, e.dot(C * e) / el.mass);
    double w2 = 12 * T / (mn * el.length) + 0.25 * sigma * sigma;
    // Bending springs: the zig-zag mode turns each element about G against
    // twice its self-stiffness (each joint's angle is twice the turn).
    if (bending) w2 += 2 * element_bending_stiffness(model, ws, k) / element_rot_inertia(el);
    if (!(w2 > 0)) continue;
    const double h = 2 * std::sqrt(2.0) / std::sqrt(w2);
    if (h < best) {
      best = h;
      if (element) *element = static_cast<int>(k) + 1;
      if (tension) *tension = T;
    }
  }
  return best;
}

namespace {

/// The run's current chain: the model given, or one derived from it by
/// winch events (one element more or less in the top section), with its
/// system and the material identities of its nodes.
struct Chain {
  const Model* model = nullptr;
  std::unique_ptr<Model> owned;  // the derived model, when there is one
  std::unique_ptr<System> sys;
  std::vector<long> node_id;  // per output node row, stable across events [-]
  long next_id = 0;           // the next new node's identity [-]
};

/// Split or remove the winch's top element of the state y at t; y becomes
/// the state of the new chain.
void winch_event_at(Chain& c, StateVector& y, double t, RunStats& stats) {
  const PhysicalState s = c.sys->physical(y);
  std::unique_ptr<Model> m;
  PhysicalState s2;
  switch (winch_event(*c.model, s)) {
    case WinchEvent::None:
      return;
    case WinchEvent::Split:
      m = std::make_unique<Model>(split_model(*c.model));
      s2 = split_state(*c.model, s);
      c.node_id.insert(c.node_id.begin() + 1, c.next_id++);
      ++stats.winch_splits;
      break;
    case WinchEvent::Remove: {
      const Winch& w = c.model->winch;
      const double rate = w.mode == Winch::Mode::Imposed ? winch_kinematics(w, t).rate : payout_rate(*c.model, s);
      Removal r = remove_top(*c.model, s, t, rate);
      m = std::make_unique<Model>(std::move(r.model));
      s2 = std::move(r.state);
      c.node_id.erase(c.node_id.begin() + 1);
      ++stats.winch_removals;
      stats.winch_energy_lost += r.energy_lost;
      break;
    }
  }
  stats.rhs_evaluations += c.sys->rhs_evaluations;
  c.sys = make_system(*m);  // before the old model goes: the old system refers to it
  c.owned = std::move(m);
  c.model = c.owned.get();
  y = c.sys->initial(s2, t);
}

/// The chain's rig for the run loop (src/sim/run_loop.hpp): its system,
/// checks, winch events and samples with stable node identities.
struct ChainRig {
  ChainRig(const Model& m, OutputSink& sink) : model(m), sink(sink) {
    chain.model = &m;
    chain.sys = make_system(m);
  }
  const Model& model;  // the run's settings (the chain's own model changes at winch events)
  OutputSink& sink;
  Chain chain;
  std::string refusal;    // a refusal from the rk4 stability check
  PhysicalState checked;  // the physical state of the last step checked (storage reused)
  Sample out;             // the sample being written (its storage reused)
  PhysicalState sampled;  // its physical state (storage reused)

  const Simulation& sim() const { return model.sim; }
  bool winch() const { return model.winch.active(); }
  bool sea() const { return has_sea(model); }
  double force_scale() const { return run::force_scale(*chain.model); }
  std::vector<double> breakpoints() const {
    std::vector<double> breaks = tow_breakpoints(model.tow);
    for (double b : winch_breakpoints(model.winch)) breaks.push_back(b);
    return breaks;
  }
  System& sys() const { return *chain.sys; }
  std::string check(const System& sys, const StateVector& y) {
    if (std::string err = run::check_finite(sys, y); !err.empty()) return err;
    sys.physical_into(y, checked);
    return run::check_chain(*chain.model, checked);
  }
  bool event_due(const System& sys, const StateVector& y) const {
    return chain.model->winch.active() && winch_event(*chain.model, sys.physical(y)) != WinchEvent::None;
  }
  void track(const System& sys, const StateVector& y, double t, RunStats& stats) const {
    run::track_elastic(*chain.model, sys, y, t, stats);
  }
  void event(StateVector& y, double t, RunStats& stats) { winch_event_at(chain, y, t, stats); }
  /// One sample of the current chain at (y, t), its nodes with their identities.
  void write(const StateVector& y, double t, RunStats& stats) {
    const Workspace& ws = chain.sys->evaluate(y, t);
    chain.sys->physical_into(y, sampled);
    run::sample_checks(*chain.model, sampled, ws, t, stats, out, &refusal);
    if (chain.node_id.empty()) {
      chain.node_id = out.node_id;
      chain.next_id = static_cast<long>(out.node_id.size());
    }
    out.node_id = chain.node_id;
    sink.write(out);
  }
  void flush() { sink.flush(); }
};

}  // namespace

RunStats simulate(const Model& model, OutputSink& sink, const ProgressFn& progress, const volatile int* stop_flag) {
  RunStats stats;
  stats.integrator = integrator_key(model.sim.integrator);
  stats.threads = evaluation_threads(model);
  run::tolerance_warnings(model.sim, stats);
  const auto wall0 = std::chrono::steady_clock::now();
  // A steady start can fail or be interrupted: the run then ends before t = 0.
  PhysicalState s0;
  std::optional<Model> split;  // a steady start over a flat seabed: the model with its touchdown joint
  if (model.initial.kind == Initial::Kind::Steady) {
    TouchdownStatics td = steady_touchdown_state(model, stop_flag);
    const StaticsResult& st = td.statics;
    if (!st.converged) {
      stats.status = st.interrupted ? "interrupted" : "failed";
      stats.message = st.interrupted ? "interrupted by signal while solving the steady initial state"
                                     : "initial: steady: " + st.message;
      stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      sink.flush();
      return stats;
    }
    s0 = st.state;
    if (td.split_element >= 0) split = std::move(td.model);
  } else {
    s0 = initial_state(model);
    lean_upright(model, s0);
  }
  const Model& run_model = split ? *split : model;
  ChainRig rig(run_model, sink);
  StateVector y = rig.chain.sys->initial(s0, 0.0);
  if (model.initial.kind != Initial::Kind::Steady) rig.chain.sys->apply_tow_jump(y, 0.0);  // at rest, tow at speed
  rig.chain.sys->project(y, 0.0);
  rig.write(y, 0.0, stats);
  rig.track(*rig.chain.sys, y, 0.0, stats);
  return run::run_loop(rig, y, std::move(stats), wall0, progress, stop_flag);
}

}  // namespace towsim
