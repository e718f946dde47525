// The run loop: integrate, land on output times, check the state, write samples.
#include "towsim/sim/simulate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/sim/statics.hpp"
#include "towsim/sim/winch_events.hpp"
#include "towsim/waves/vessel.hpp"

#include "run_loop.hpp"

namespace towsim {


namespace {

constexpr double kRad2Deg = 180.0 / M_PI;
constexpr double kMaxRate = 1e4;  // an angular velocity beyond this [rad/s] means divergence
// A slack elastic element shorter than this fraction of its length [-]: the
// straight-rod model of a folded cable has broken down (l -> 0 is singular).
constexpr double kMinLength = 0.05;

/// After an accepted step at t: slack episodes and peak tensions of an elastic cable.
void track_elastic(const Model& model, const System& sys, const StateVector& y, double t, RunStats& stats) {
  if (!lengths_in_state(model)) return;
  PhysicalState s = sys.physical(y);
  double top_unstretched = 0;  // L_1 when the winch sets it [m]
  if (elastic_winch(model)) {
    top_unstretched = s.top_unstretched;
    // The winch's top element at the strain l_1/L_1 of the model's L:
    // equivalent length and rate (its pay-out's damping term left out).
    const double scale = model.cable.elements[0].length / s.top_unstretched;
    s.length[0] *= scale;
    s.length_rate[0] *= scale;
  }
  stats.slack.update(model, s.length, s.length_rate, t, top_unstretched);
}

/// RK4 only: compare the step with the stability limit at this sample. Beyond
/// 0.9 times it (the estimate is within 10 % of the measured limits): a
/// warning (once); beyond 1.5 times it: an error text (the run stops).
std::string check_rk4_step(const Model& model, const Workspace& ws, double t, RunStats& stats) {
  if (model.sim.integrator != Integrator::RK4) return {};
  int k = 0;
  double T = 0;
  const double lim = rk4_step_limit(model, ws, t, &k, &T);
  if (!(lim > 0) || std::isinf(lim)) return {};
  if (stats.rk4_step_limit < 0 || lim < stats.rk4_step_limit) stats.rk4_step_limit = lim;
  const double h = model.sim.time_step;
  if (h <= 0.9 * lim) return {};
  // The estimate is within 10 % of the measured limit (tests): 1.5 times
  // it is clearly unstable.
  const bool refuse = h > 1.5 * lim;
  std::ostringstream os;
  os << (refuse ? "refused: " : "") << "rk4 time_step " << h << " s is above " << (refuse ? "1.5" : "0.9")
     << " times the estimated stability limit " << lim << " s at t = " << t << " s (element " << k << ", tension " << T
     << " N): " << (refuse ? "the run would diverge or be wrong" : "forces may be wrong")
     << "; use simulation.time_step <= " << 0.9 * lim << " or simulation.integrator: rosenbrock";
  if (refuse) return os.str();
  if (stats.warnings.empty() || stats.warnings.back().rfind("rk4 time_step", 0) != 0)
    stats.warnings.push_back(os.str());
  return {};
}

/// The first time each lifting surface is seen stalled (|angle of attack|
/// beyond its stall angle) at an output sample: a warning with the time.
void check_stall(const Model& model, const Workspace& ws, double t, RunStats& stats) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const Body& body = model.bodies[b];
    for (std::size_t j = 0; j < body.surfaces.size(); ++j) {
      const LiftingSurface& ls = body.surfaces[j];
      const SurfaceFlow f = surface_flow(model.fluid, ls, current_deflection(body, j, ws.body[b], t), t, ws.body[b]);
      if (f.speed < 1e-6 || std::abs(f.alpha) <= ls.stall_angle) continue;
      const std::string who = (body.inline_body ? "body " + body.name + "'s" : std::string("the body's")) +
                              " surface " + std::to_string(j);
      if (std::any_of(stats.warnings.begin(), stats.warnings.end(),
                      [&](const std::string& w) { return w.rfind(who + " stalled", 0) == 0; }))
        continue;
      std::ostringstream os;
      os << who << " stalled at t = " << t << " s: angle of attack " << f.alpha * kRad2Deg
         << " deg beyond its stall angle " << ls.stall_angle * kRad2Deg
         << " deg (its lift falls off; check the body's trim, link point and deflections)";
      stats.warnings.push_back(os.str());
    }
  }
}

/// The first output time the cable (a joint below the tow point: a vessel's
/// tow point may stand above the water) or a body is above the mean water
/// surface z = 0: a warning, once per part. The water's loads act there as
/// under water; such results are not physical (docs/theory.md §3).
void check_surface(const Model& model, const Sample& s, RunStats& stats) {
  const auto warn = [&stats, &s](const std::string& who, const std::string& where, double z) {
    if (std::any_of(stats.warnings.begin(), stats.warnings.end(),
                    [&](const std::string& w) { return w.rfind(who + " rose above", 0) == 0; }))
      return;
    std::ostringstream os;
    os << who << " rose above the water surface at t = " << s.t << " s (" << where << "z = " << z
       << " m): the water's loads (buoyancy, drag, added mass) still act there, so results above z = 0 are not "
          "physical";
    stats.warnings.push_back(os.str());
  };
  for (std::size_t k = 1; k < s.node_pos.size(); ++k)
    if (s.node_pos[k].z() > 0) {
      warn("the cable", "joint " + std::to_string(k) + " at ", s.node_pos[k].z());
      break;
    }
  for (std::size_t b = 0; b < model.bodies.size() && b < s.bodies.size(); ++b)
    if (s.bodies[b].pos.z() > 0)
      warn(model.bodies[b].inline_body ? "body " + model.bodies[b].name : std::string("the body"), "",
           s.bodies[b].pos.z());
}

/// Output sample of state y at time t into `out` (its storage reused; `s`:
/// storage for y's physical state); tracks the element length drift.
void sample_of(const Model& model, System& sys, const StateVector& y, double t, RunStats& stats, Sample& out,
               PhysicalState& s, std::string* err = nullptr) {
  const Workspace& ws = sys.evaluate(y, t);
  if (err) *err = check_rk4_step(model, ws, t, stats);
  check_stall(model, ws, t, stats);
  sys.physical_into(y, s);
  make_sample(model, s, ws, t, out);
  check_surface(model, out, stats);
  for (std::size_t k = 0; k < model.cable.elements.size(); ++k) {
    const int b = ws.body_at[k + 1];
    const Vec3& bottom = b >= 0 ? ws.body[static_cast<std::size_t>(b)].Q : ws.P[k + 1];
    const double L = ws.L[k];  // the state's length (winch, elastic)
    stats.max_element_drift = std::max(stats.max_element_drift, std::abs((bottom - ws.P[k]).norm() / L - 1));
  }
}

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

/// Empty if y is sound; else what went wrong and where (`s`: storage for
/// y's physical state).
std::string check_state(const Model& model, const System& sys, const StateVector& y, PhysicalState& s) {
  for (std::size_t i = 0; i < y.size(); ++i)
    if (!std::isfinite(y[i])) return sys.describe(i) + ": state is not finite (NaN or infinity)";
  sys.physical_into(y, s);
  for (int k = 0; k < model.cable.n(); ++k)
    if (s.w[k].norm() > kMaxRate)
      return "element " + std::to_string(k + 1) + ": angular velocity diverged (" + std::to_string(s.w[k].norm()) +
             " rad/s); reduce simulation.time_step or use an adaptive integrator";
  for (std::size_t k = 0; k < s.length.size(); ++k) {
    // Unstretched length: the model's, or the winch's paid-out L_1.
    const double L = k == 0 && elastic_winch(model) ? s.top_unstretched : model.cable.elements[k].length;
    if (is_elastic(model.cable.elements[k]) && !(s.length[k] > kMinLength * L))
      return "element " + std::to_string(k + 1) + ": a slack element shortened to " +
             std::to_string(s.length[k] / L * 100) +
             " % of its length (the cable folded on itself); reduce simulation.time_step or refine the cable";
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (s.bodies[b].w.norm() > kMaxRate)
      return "body " + model.bodies[b].name +
             ": angular velocity diverged; reduce simulation.time_step or use an adaptive integrator";
  return {};
}

/// Absolute force scale of the force error norm: the chain's apparent weight [N].
double force_scale(const Model& model) {
  double w = 0;
  for (const Element& el : model.cable.elements) w += std::abs(el.weight);
  for (const Body& b : model.bodies) w += std::abs(b.mass - model.fluid.rho * b.displaced_volume) * model.fluid.g;
  for (const Attachment& a : model.cable.attachments)
    w += std::abs(a.mass - model.fluid.rho * a.volume) * model.fluid.g;
  return std::max(w, 1.0);
}

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
  double force_scale() const { return towsim::force_scale(*chain.model); }
  std::vector<double> breakpoints() const {
    std::vector<double> breaks = tow_breakpoints(model.tow);
    for (double b : winch_breakpoints(model.winch)) breaks.push_back(b);
    return breaks;
  }
  System& sys() { return *chain.sys; }
  std::string check(const System& sys, const StateVector& y) { return check_state(*chain.model, sys, y, checked); }
  bool event_due(const System& sys, const StateVector& y) const {
    return chain.model->winch.active() && winch_event(*chain.model, sys.physical(y)) != WinchEvent::None;
  }
  void track(const System& sys, const StateVector& y, double t, RunStats& stats) const {
    track_elastic(*chain.model, sys, y, t, stats);
  }
  void event(StateVector& y, double t, RunStats& stats) { winch_event_at(chain, y, t, stats); }
  /// One sample of the current chain at (y, t), its nodes with their identities.
  void write(const StateVector& y, double t, RunStats& stats) {
    sample_of(*chain.model, *chain.sys, y, t, stats, out, sampled, &refusal);
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
  // A loose tolerance passes large errors as "ok" (dopri5 at 0.1: a peak tension 6.5 times the converged one).
  constexpr double kLooseTolerance = 1e-2;  // [-]
  if (model.sim.integrator != Integrator::RK4 && model.sim.tolerance > kLooseTolerance) {
    std::ostringstream os;
    os << "simulation.tolerance " << model.sim.tolerance << " is loose (above " << kLooseTolerance
       << "): the results may be far from converged; check them at a tolerance 10 times smaller";
    stats.warnings.push_back(os.str());
  }
  const auto wall0 = std::chrono::steady_clock::now();
  // A steady start can fail or be interrupted: the run then ends before t = 0.
  PhysicalState s0;
  if (model.initial.kind == Initial::Kind::Steady) {
    const StaticsResult st = steady_state(model, stop_flag);
    if (!st.converged) {
      stats.status = st.interrupted ? "interrupted" : "failed";
      stats.message = st.interrupted ? "interrupted by signal while solving the steady initial state"
                                     : "initial: steady: " + st.message;
      stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      sink.flush();
      return stats;
    }
    s0 = st.state;
  } else {
    s0 = initial_state(model);
  }
  ChainRig rig(model, sink);
  StateVector y = rig.chain.sys->initial(s0, 0.0);
  if (model.initial.kind != Initial::Kind::Steady) rig.chain.sys->apply_tow_jump(y, 0.0);  // at rest, tow at speed
  rig.chain.sys->project(y, 0.0);
  rig.write(y, 0.0, stats);
  rig.track(*rig.chain.sys, y, 0.0, stats);
  return run::run_loop(rig, y, std::move(stats), wall0, progress, stop_flag);
}

}  // namespace towsim
