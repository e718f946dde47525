// The run loop for a network (towsim/sim/simulate_network.hpp).
#include "towsim/sim/simulate_network.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "run_checks.hpp"
#include "run_loop.hpp"
#include "towsim/integrators/network_system.hpp"
#include "towsim/sim/statics.hpp"
#include "towsim/sim/winch_events.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim {

namespace {

/// The network's rig for the run loop (src/sim/run_loop.hpp): its system,
/// checks, each line's winch events and samples with stable node identities.
struct NetworkRig {
  NetworkRig(const Network& n, NetworkSink& sink)
      : net(n), sink(sink), system_(std::make_unique<NetworkSystem>(n)), node_id(n.tree.lines.size()) {
    out.lines.resize(n.tree.lines.size());
    next_id.assign(n.tree.lines.size(), 0);
  }
  const Network& net;  // the run's settings and names (a line's model changes at its winch's events)
  NetworkSink& sink;
  std::unique_ptr<Network> owned;          // the network derived by winch events, when there is one
  std::unique_ptr<NetworkSystem> system_;  // the current network's system
  std::string refusal;                     // a refusal from the rk4 stability check
  TreeState checked;                       // the state of the last step checked (storage reused)
  NetworkSample out;                       // the sample being written (its storage reused)
  std::vector<std::vector<long>> node_id;  // per line, per output node row: stable across events [-]
  std::vector<long> next_id;               // per line: the next new node's identity [-]

  /// The network now: the given one, or the one winch events made of it.
  const Network& current() const { return owned ? *owned : net; }
  NetworkSystem& system() const { return *system_; }
  const Simulation& sim() const { return net.settings().sim; }
  bool winch() const { return net.has_winch(); }
  bool sea() const { return net.settings().fluid.waves != nullptr; }  // waves (a tow point alone gives a vessel)
  double force_scale() const {
    double w = 0;
    for (const Model& m : current().tree.lines) w += run::force_scale(m);
    return w;
  }
  std::vector<double> breakpoints() const {
    std::vector<double> breaks = tow_breakpoints(net.settings().tow);
    for (const Model& m : net.tree.lines)
      for (double b : winch_breakpoints(m.winch)) breaks.push_back(b);
    return breaks;
  }
  System& sys() const { return *system_; }
  /// Every row finite, every line sound (the line named).
  std::string check(const System& sys, const StateVector& y) {
    if (std::string err = run::check_finite(sys, y); !err.empty()) return err;
    system_->tree_state_into(y, checked);
    for (std::size_t i = 0; i < checked.size(); ++i)
      if (std::string err = run::check_chain(current().tree.lines[i], checked[i]); !err.empty())
        return "line " + net.line_names[i] + ": " + err;
    return {};
  }
  /// A line's winch is due to split or remove its top element.
  bool event_due(const System&, const StateVector& y) {
    if (!winch()) return false;
    system_->tree_state_into(y, checked);
    const TreeModel& tree = current().tree;
    for (std::size_t i = 0; i < checked.size(); ++i)
      if (tree.lines[i].winch.active() && winch_event(tree.lines[i], checked[i]) != WinchEvent::None) return true;
    return false;
  }
  void track(const System&, const StateVector&, double, RunStats&) const {}
  void event(StateVector& y, double t, RunStats& stats);
  /// Each line's sample at (y, t), from one evaluation of the tree, its nodes with their identities.
  void write(const StateVector& y, double t, RunStats& stats) {
    const TreeWorkspace& ws = system_->evaluate_tree(y, t);
    const TreeState& s = system_->evaluated_state();
    out.t = t;
    for (std::size_t i = 0; i < s.size(); ++i) {
      std::string err;
      Sample& l = out.lines[i];
      run::sample_checks(current().tree.lines[i], s[i], ws.lines[i], t, stats, l, &err);
      if (!err.empty() && refusal.empty()) refusal = "line " + net.line_names[i] + ": " + err;
      if (node_id[i].empty()) node_id[i] = l.node_id, next_id[i] = static_cast<long>(l.node_id.size());
      l.node_id = node_id[i];
    }
    sink.write(out);
  }
  void flush() { sink.flush(); }
};

/// True when line i carries more of the tree: a line hangs from it or a loop closes on it.
bool carries(const TreeModel& tree, std::size_t i) {
  const auto li = static_cast<int>(i);
  return std::any_of(tree.tops.begin(), tree.tops.end(), [li](const LineTop& t) { return t.line == li; }) ||
         std::any_of(tree.loops.begin(), tree.loops.end(),
                     [li](const LoopJoint& j) { return j.line == li || j.node_line == li; });
}

/// The network's kinetic energy at (y, t): every line's, each line below a
/// node moving with it (its added mass and the bodies' included) [J].
double tree_energy(NetworkSystem& sys, const StateVector& y, double t) {
  const TreeWorkspace& ws = sys.evaluate_tree(y, t);
  const TreeState& s = sys.evaluated_state();
  double E = 0;
  for (std::size_t i = 0; i < s.size(); ++i) E += kinetic_energy(sys.network().tree.lines[i], s[i], ws.lines[i]);
  return E;
}

/// Split or remove the top element of every line whose winch is due at t;
/// y becomes the state of the network derived. A removal's impulse (the
/// pay-out speed brought back to the winch's) is the line's own, or the
/// tree's when the line carries more of it; the energy it takes is then
/// the whole tree's change.
void NetworkRig::event(StateVector& y, double t, RunStats& stats) {
  TreeState s;
  system_->tree_state_into(y, s);
  double energy_before = 0, chains_lost = 0;  // [J]
  auto next = std::make_unique<Network>(current());
  std::vector<Vec3> jump(s.size(), Vec3::Zero());
  std::vector<double> rate(s.size(), 0.0);
  bool changed = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Model& m = current().tree.lines[i];
    if (!m.winch.active()) continue;
    const WinchEvent e = winch_event(m, s[i]);
    if (e == WinchEvent::None) continue;
    changed = true;
    if (e == WinchEvent::Split) {
      next->tree.lines[i] = split_model(m);
      s[i] = split_state(m, s[i]);
      node_id[i].insert(node_id[i].begin() + 1, next_id[i]++);
      ++stats.winch_splits;
      continue;
    }
    rate[i] = m.winch.mode == Winch::Mode::Imposed ? winch_kinematics(m.winch, t).rate : payout_rate(m, s[i]);
    Removal r = remove_top(m, s[i], t, rate[i]);
    const bool tree_impulse = carries(current().tree, i) && r.jump != Vec3::Zero();
    if (tree_impulse && std::all_of(jump.begin(), jump.end(), [](const Vec3& j) { return j == Vec3::Zero(); }))
      energy_before = tree_energy(*system_, y, t);
    next->tree.lines[i] = std::move(r.model);
    s[i] = tree_impulse ? std::move(r.before_impulse) : std::move(r.state);
    if (tree_impulse) jump[i] = r.jump;
    node_id[i].erase(node_id[i].begin() + 1);
    ++stats.winch_removals;
    chains_lost += r.energy_lost;
  }
  if (!changed) return;
  const bool tree_impulses = std::any_of(jump.begin(), jump.end(), [](const Vec3& j) { return j != Vec3::Zero(); });
  stats.rhs_evaluations += system_->rhs_evaluations;
  auto sys = std::make_unique<NetworkSystem>(*next);  // before the old network goes: the old system refers to it
  system_ = std::move(sys);
  owned = std::move(next);
  // The removals' impulses through the tree; each such line's pay-out speed then its winch's.
  if (tree_impulses) {
    system_->sheave_jumps(s, jump);
    for (std::size_t i = 0; i < s.size(); ++i)
      if (jump[i] != Vec3::Zero()) s[i].length_rate[0] = rate[i];
  }
  y = system_->initial_tree(s);
  stats.winch_energy_lost += tree_impulses ? energy_before - tree_energy(*system_, y, t) : chains_lost;
}

/// Watches a relaxation's samples: stops it (through `stop`) at the first
/// whose joints and bodies all move by less than kNetworkSettledSpeed (a
/// body's rotation counted at 1 m from its origin), or when the motion has
/// stopped decaying: the largest speed over the last kStallWindow seconds
/// at least kStallRatio of the window's before (a limit cycle: a body
/// hunting, a line strumming), which no longer relaxation would settle.
class SettleSink final : public NetworkSink {
 public:
  static constexpr double kStallWindow = 2000;  // [s]
  static constexpr double kStallRatio = 0.9;    // [-]
  volatile int stop = 0;
  bool settled = false;
  double speed = 0;  // the last sample's largest speed [m/s]
  double time = 0;   // its time [s]
  void write(const NetworkSample& s) override {
    speed = 0;
    for (const Sample& l : s.lines) {
      for (const Vec3& v : l.node_vel) speed = std::max(speed, v.norm());
      for (const BodySample& b : l.bodies) speed = std::max({speed, b.vel.norm(), b.omega.norm() * 1.0});
    }
    time = s.t;
    if (s.t > 0 && speed < kNetworkSettledSpeed) {
      settled = true;
      stop = 1;
    }
    // The windows' largest speeds: the current one and the one before.
    window_max_ = std::max(window_max_, speed);
    if (s.t >= window_end_) {
      if (previous_max_ > 0 && window_max_ >= kStallRatio * previous_max_) stop = 1;
      previous_max_ = window_max_;
      window_max_ = 0;
      window_end_ += kStallWindow;
    }
  }
  void flush() override {}

 private:
  double window_end_ = kStallWindow, window_max_ = 0, previous_max_ = 0;
};

/// A number as text in %g's shortest form.
std::string fmt_g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

/// A flat bottom seen from the tow moving at V: it moves at -V. At rest
/// (V = 0) the friction vanishes at the equilibrium and its viscous slope
/// would only make the lying cable creep: left out. Slipping near the
/// smoothing speed v_s the same slope makes the lying length creep: a
/// sharper law, v_s' = |V| / 10, scaled to the same friction at the slip
/// |V| (the same equilibrium). As the chain's relaxation (docs/theory.md §7).
void seabed_in_tow_frame(Seabed& sb, const Vec3& V) {
  constexpr double kSharpSlip = 0.1;  // v_s' / |V| at most [-]
  const double U = V.norm();
  sb.velocity = -V;
  if (!(U > 0)) sb.friction = 0;
  if (U > 0 && sb.slip_speed > kSharpSlip * U) {
    const double sharp = kSharpSlip * U;
    sb.friction *= std::hypot(U, sharp) / std::hypot(U, sb.slip_speed);
    sb.slip_speed = sharp;
  }
}

/// A start that does not cut into a flat bottom: down the tree, each
/// line's elements hang straight down to the bottom's level, the one that
/// would pass it slants onto it, and the rest lie on it behind the tow
/// (along -V, or +x at rest). A line below a body starts from its node's
/// cable end (the body's size is left to the contact). Nothing changes
/// without a seabed.
void lay_on_bottom(const Network& net, const Vec3& V, TreeState& s) {
  const TreeModel& tree = net.tree;
  Vec3 back = -Vec3(V.x(), V.y(), 0);
  back = back.norm() > 0 ? Vec3(back.normalized()) : Vec3::UnitX();
  std::vector<double> end_z(tree.lines.size(), 0.0);  // each line's cable end [m]
  for (std::size_t i = 0; i < tree.lines.size(); ++i) {
    const Model& m = tree.lines[i];
    const int parent = tree.tops[i].line;
    double z = parent < 0 ? s[i].r0.z() : end_z[static_cast<std::size_t>(parent)];
    if (!m.seabed) {
      for (std::size_t k = 0; k < s[i].e.size(); ++k) z += m.cable.elements[k].length * s[i].e[k].z();
      end_z[i] = z;
      continue;
    }
    const double bottom = m.seabed->bottom_z(s[i].r0.x());
    for (std::size_t k = 0; k < s[i].e.size(); ++k) {
      const double L = m.cable.elements[k].length, drop = std::max(0.0, std::min(L, z - bottom));
      s[i].e[k] = drop >= L ? Vec3(-Vec3::UnitZ())
                            : Vec3(std::sqrt(L * L - drop * drop) / L * back - drop / L * Vec3::UnitZ());
      z -= drop;
    }
    end_z[i] = z;
  }
}

/// The network seen from its tow points at velocity V: each root line's
/// tow held at its position at t = 0 turned by `yaw` about the vertical
/// through the first tow point, the current less V, calm water, the
/// hanging start, the relaxation's settings, every winch held, a flat
/// bottom moving at -V.
Network tow_frame(const Network& net, const Vec3& V, double yaw) {
  Network r = net;
  const Eigen::AngleAxisd turn(yaw, Vec3::UnitZ());
  std::optional<Vec3> first;
  for (std::size_t i = 0; i < r.tree.lines.size(); ++i) {
    Model& m = r.tree.lines[i];
    if (r.tree.tops[i].line < 0) {
      const Vec3 p = tow_kinematics(m.tow, 0.0).pos;
      if (!first) first = p;
      m.tow.pieces.clear();
      m.tow.vessel.reset();
      m.tow.start = *first + turn * (p - *first);
      finalize_tow(m.tow);
    }
    Fluid& f = m.fluid;
    f.waves.reset();
    if (f.current_velocity.empty()) f.current_depth = {0.0}, f.current_velocity = {Vec3::Zero()};
    for (Vec3& u : f.current_velocity) u -= V;
    if (m.initial.kind == Initial::Kind::Steady) m.initial.kind = Initial::Kind::Hanging;
    m.winch = Winch{};  // held at its initial deployed length
    if (m.seabed) seabed_in_tow_frame(*m.seabed, V);
    m.sim.integrator = Integrator::Rosenbrock;
    m.sim.tolerance = 1e-6;
    m.sim.time_step = 0.01;
    m.sim.duration = kNetworkRelaxTime;
    m.sim.output_interval = 1;
  }
  return r;
}

/// What a steady tow of the network needs: every root line in motion mode,
/// a flat bottom if any (network_steady_refusal).
void check_steady(const Network& net) {
  if (std::string why = network_steady_refusal(net); !why.empty()) throw std::invalid_argument(why);
}

}  // namespace

std::string network_steady_refusal(const Network& net) {
  for (std::size_t i = 0; i < net.tree.lines.size(); ++i) {
    const Model& m = net.tree.lines[i];
    if (m.seabed && std::any_of(m.seabed->depth.begin(), m.seabed->depth.end(),
                                [&](double d) { return d != m.seabed->depth.front(); }))
      return "a network's steady tow over a seabed needs a flat bottom (depth: D; a table of depths moves under "
             "the tow; use hanging or {direction: [x, y, z]})";
    if (net.tree.tops[i].line < 0 && m.tow.mode != Tow::Mode::Motion)
      return "a steady tow needs tow.mode: motion (the steady velocity comes from the tow law)";
  }
  return {};
}

NetworkSteady network_steady_state(const Network& net, const Vec3& V, double yaw, const volatile int* stop_flag,
                                   const TreeState* start) {
  check_steady(net);
  NetworkSteady out;
  out.velocity = V;
  out.yaw = yaw;
  // Relax in the tow's frame until every joint is at rest.
  const Network frame = tow_frame(net, V, yaw);
  SettleSink watch;
  NetworkRig rig(frame, watch);
  TreeState s0 = network_initial_state(frame);
  if (start == nullptr) lay_on_bottom(frame, V, s0);
  if (start != nullptr) {
    // From the given shape, at rest in the frame; each line's top where the frame puts it.
    for (std::size_t i = 0; i < s0.size(); ++i) {
      const Vec3 r0 = s0[i].r0;
      s0[i] = (*start)[i];
      s0[i].r0 = r0;
      s0[i].v0.setZero();
    }
  }
  StateVector y = rig.system().initial_tree(s0);
  rig.system().project(y, 0.0);
  RunStats stats;
  rig.write(y, 0.0, stats);
  stats = run::run_loop(rig, y, std::move(stats), std::chrono::steady_clock::now(), {}, &watch.stop);
  if (stop_flag && *stop_flag) throw std::runtime_error("the steady tow's relaxation was interrupted");
  if (stats.status == "failed") throw std::runtime_error("the steady tow's relaxation failed: " + stats.message);
  if (!watch.settled)
    throw std::runtime_error("the network has no steady tow: after " + std::to_string(std::lround(watch.time)) +
                             " s of relaxation its joints still move at " + fmt_g(watch.speed) +
                             " m/s and no longer settle (a body hunting, a line strumming, or a mode slower than " +
                             std::to_string(std::lround(kNetworkRelaxTime)) + " s)");
  out.relaxed_time = watch.time;
  out.residual_speed = watch.speed;
  out.steps = stats.steps;
  // At rest relative to the tow, every point moving at V.
  rig.system().tree_state_into(y, out.state);
  for (std::size_t i = 0; i < out.state.size(); ++i) {
    PhysicalState& s = out.state[i];
    const Model& m = net.tree.lines[i];
    if (elastic_winch(m)) s.top_unstretched = m.cable.elements.front().length;  // the winch's paid-out L_1
    s.v0 = V;
    for (Vec3& w : s.w) w.setZero();
    for (double& r : s.length_rate) r = 0;
    s.top_unstretched_rate = 0;
    for (BodyState& b : s.bodies) b.w.setZero();
  }
  return out;
}

NetworkSteady network_steady_state(const Network& net, const volatile int* stop_flag) {
  check_steady(net);
  // The tow velocity at t = 0+: one for every root line.
  std::optional<Vec3> V;
  for (std::size_t i = 0; i < net.tree.lines.size(); ++i) {
    if (net.tree.tops[i].line >= 0) continue;
    const Vec3 v = tow_kinematics(net.tree.lines[i].tow, 1e-9).vel;
    if (V && (v - *V).norm() > 1e-9 * std::max(1.0, v.norm()))
      throw std::invalid_argument("initial: steady: the tow points start at different velocities (a turn at t = 0)");
    if (!V) V = v;
  }
  return network_steady_state(net, V.value_or(Vec3::Zero()), 0.0, stop_flag);
}

NetworkSteady network_statics(const Network& net, const volatile int* stop_flag, const TreeState* start) {
  check_steady(net);
  const Tow& tow = net.settings().tow;
  const Vec3 V = final_tow_velocity(tow);
  // The heading's change from the offsets' own (before any manoeuvre) to the final course's.
  Tow straight = tow;
  std::erase_if(straight.pieces, [](const TowLaw& p) { return is_manoeuvre(p); });
  const Vec3 v0 = final_tow_velocity(straight);
  const double yaw = V.head<2>().norm() > 0 && v0.head<2>().norm() > 0
                         ? std::atan2(V.y(), V.x()) - std::atan2(v0.y(), v0.x())
                         : 0.0;
  return network_steady_state(net, V, yaw, stop_flag, start);
}

RunStats write_network_steady(const Network& net, const NetworkSteady& st, NetworkSink& sink) {
  // Evaluated where it is steady: in the tow's frame (tow points held, the current less V).
  const Network frame = tow_frame(net, st.velocity, st.yaw);
  NetworkMemorySink mem;
  RunStats stats;
  NetworkRig rig(frame, mem);
  TreeState s = st.state;
  for (PhysicalState& p : s) p.v0.setZero();
  StateVector y = rig.system().initial_tree(s);
  rig.system().project(y, 0.0);
  rig.write(y, 0.0, stats);
  // Seen from the water: everything moves at V.
  NetworkSample out = mem.samples.front();
  for (Sample& l : out.lines) {
    l.tow_vel += st.velocity;
    for (Vec3& v : l.node_vel) v += st.velocity;
    for (BodySample& b : l.bodies) b.vel += st.velocity;
  }
  sink.write(out);
  sink.flush();
  return stats;
}

RunStats simulate_network(const Network& net, NetworkSink& sink, const ProgressFn& progress,
                          const volatile int* stop_flag) {
  RunStats stats;
  const Model& settings = net.settings();
  stats.integrator = integrator_key(settings.sim.integrator);
  stats.threads = 1;
  run::tolerance_warnings(settings.sim, stats);
  const auto wall0 = std::chrono::steady_clock::now();
  NetworkRig rig(net, sink);
  StateVector y;
  try {
    if (settings.initial.kind == Initial::Kind::Steady) {
      const NetworkSteady st = network_steady_state(net, stop_flag);
      y = rig.system().initial_tree(st.state);  // moving at the tow's velocity: no jump
    } else {
      y = rig.system().initial_tree(network_initial_state(net));
      rig.system().apply_tow_jump(y, 0.0);  // at rest, tow at speed
    }
  } catch (const std::exception& e) {
    stats.status = "failed";
    stats.message = e.what();
    sink.flush();
    return stats;
  }
  rig.system().project(y, 0.0);
  rig.write(y, 0.0, stats);
  return run::run_loop(rig, y, std::move(stats), wall0, progress, stop_flag);
}

}  // namespace towsim
