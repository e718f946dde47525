// A network of lines as one flat-state system (towsim/integrators/network_system.hpp).
#include "towsim/integrators/network_system.hpp"

#include <algorithm>
#include <stdexcept>

#include "chain_rows.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/integrators/state_layout.hpp"

namespace towsim {

namespace {

using CMap3 = Eigen::Map<const Vec3>;

void set3(double* y, const Vec3& v) { y[0] = v.x(), y[1] = v.y(), y[2] = v.z(); }

/// The state sizes of every line (their shapes).
TreeState shapes(const std::vector<std::unique_ptr<ChainRows>>& rows) {
  TreeState s;
  for (const auto& r : rows) s.push_back(r->shape());
  return s;
}

/// A line below a node: its top joint's rows (r0, v0) are not part of the
/// state (its node's motion is): their rates and stage increments are
/// zero, so they neither move nor enter the step's error estimate.
void hold_top_rows(double* rows) { std::fill(rows, rows + 6, 0.0); }

/// A loop's initial gap left by its assembly at most this [m].
constexpr double kLoopAssembly = 1e-9;

}  // namespace

NetworkSystem::NetworkSystem(const Network& net)
    : net_(net), tree_(net.tree), ws_(net.tree), jws_(net.tree), iw_(net.tree, ws_) {
  for (const Model& m : tree_.lines) {
    offset_.push_back(size_);
    rows_.push_back(std::make_unique<ChainRows>(m));
    size_ += rows_.back()->size();
  }
  s_ = shapes(rows_);
  js_ = s_;
  rhs_.resize(tree_.lines.size());
  for (std::size_t i = 0; i < rhs_.size(); ++i) {
    const std::size_t n = s_[i].e.size(), nb = s_[i].bodies.size();
    rhs_[i].dw.assign(n, Vec3::Zero()), rhs_[i].rot.assign(n, Vec3::Zero());
    rhs_[i].dwb.assign(nb, Vec3::Zero()), rhs_[i].rotb.assign(nb, Vec3::Zero());
    rhs_[i].dl.assign(n, 0.0), rhs_[i].dlr.assign(n, 0.0);
  }
  course_.resize(tree_.lines.size());
  stop_rate_.assign(tree_.lines.size(), 0.0);
}

NetworkSystem::~NetworkSystem() = default;

StateVector NetworkSystem::initial(const PhysicalState&, double) {
  throw std::logic_error("towsim: network: the initial state is a tree's (initial_tree)");
}

StateVector NetworkSystem::initial_tree(const TreeState& s) const {
  if (s.size() != rows_.size()) throw std::logic_error("towsim: network: one state per line");
  StateVector y(size_);
  for (std::size_t i = 0; i < rows_.size(); ++i) rows_[i]->pack(s[i], y.data() + offset_[i]);
  return y;
}

void NetworkSystem::tree_state_into(const StateVector& y, TreeState& out) const {
  // Storage of another shape (another network's, before a winch event): resized.
  const auto fits = [&] {
    for (std::size_t i = 0; i < rows_.size(); ++i)
      if (out[i].e.size() != rows_[i]->shape().e.size() || out[i].length.size() != rows_[i]->shape().length.size())
        return false;
    return true;
  };
  if (out.size() != rows_.size() || !fits()) out = shapes(rows_);
  for (std::size_t i = 0; i < rows_.size(); ++i) rows_[i]->unpack(y.data() + offset_[i], out[i]);
}

void NetworkSystem::rates(const StateVector& y, StateVector& dy, double t, const StepWindow& window) {
  // Each line's state; the roots' tops at their imposed motion.
  tree_state_into(y, s_);
  const double tl = window.law_time(t);
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const Model& m = tree_.lines[i];
    if (tree_.tops[i].line >= 0) continue;
    rows_[i]->impose_winch(tl, s_[i]);
    if (m.tow.mode != Tow::Mode::Motion) continue;
    const TowKinematics k = tow_kinematics(m.tow, tl, ws_.lines[i].course);
    s_[i].r0 = k.pos, s_[i].v0 = k.vel;
  }
  // The tree's one sweep; a line below a node has its node's top joint.
  tree_forward_dynamics(tree_, s_, tl, ws_);
  dy.resize(size_);
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    if (tree_.tops[i].line >= 0) s_[i].r0 = ws_.top[i], s_[i].v0 = ws_.top_velocity[i];
    rows_[i]->rates(s_[i], ws_.lines[i], dy.data() + offset_[i]);
    if (tree_.tops[i].line >= 0) hold_top_rows(dy.data() + offset_[i]);
  }
  gather_forces();
}

void NetworkSystem::gather_forces() {
  forces_.tow_force = ws_.lines.front().acc.tow_force;
  forces_.link_force.clear();
  for (std::size_t i = 1; i < ws_.lines.size(); ++i) forces_.link_force.push_back(ws_.lines[i].acc.tow_force);
  for (const Workspace& w : ws_.lines)
    forces_.link_force.insert(forces_.link_force.end(), w.acc.link_force.begin(), w.acc.link_force.end());
}

void NetworkSystem::derivative(const StateVector& y, StateVector& dy, double t, const StepWindow& window) {
  ++rhs_evaluations;
  rates(y, dy, t, window);
}

void NetworkSystem::project(StateVector& y, double t) {
  bool stops = false;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    double* yi = y.data() + offset_[i];
    const Model& m = tree_.lines[i];
    if (tree_.tops[i].line < 0 && m.tow.mode == Tow::Mode::Motion) {
      const TowKinematics k = tow_kinematics(m.tow, t, course_[i]);
      set3(yi, k.pos);
      set3(yi + 3, k.vel);
    }
    rows_[i]->normalise(yi);
    // The winch on its law; stop_rate_: a tension winch's speed at its stop.
    stop_rate_[i] = rows_[i]->project_winch(t, yi);
    stops = stops || stop_rate_[i] != 0;
  }
  if (stops) stop_winches(y);
  // Loops: the state put back onto their position and velocity constraints.
  if (tree_.loops.empty()) return;
  tree_state_into(y, js_close_);
  tree_close_loops(tree_, js_close_);
  for (std::size_t i = 0; i < rows_.size(); ++i) rows_[i]->pack(js_close_[i], y.data() + offset_[i]);
}

void NetworkSystem::stop_winches(StateVector& y) {
  tree_state_into(y, js_close_);
  TreeState& s = js_close_;
  if (!has_nodes()) {
    // Lines joined only through the vessel: each line's own impulse.
    for (std::size_t i = 0; i < rows_.size(); ++i)
      if (stop_rate_[i] != 0) s[i] = stopped(tree_.lines[i], s[i], stop_rate_[i], ws_.lines[i]);
  } else {
    std::vector<Vec3> dv(rows_.size(), Vec3::Zero());
    for (std::size_t i = 0; i < rows_.size(); ++i)
      if (stop_rate_[i] != 0) dv[i] = -sheave_jump(tree_.lines[i], s[i], stop_rate_[i]);
    sheave_jumps(s, dv);
    for (std::size_t i = 0; i < rows_.size(); ++i)
      if (stop_rate_[i] != 0) winch_rates_after_stop(tree_.lines[i], dv[i], s[i]);
  }
  for (std::size_t i = 0; i < rows_.size(); ++i) rows_[i]->pack(s[i], y.data() + offset_[i]);
}

void NetworkSystem::sheave_jumps(TreeState& s, const std::vector<Vec3>& dv) {
  tree_tow_velocity_jump(tree_, s, dv, ws_);
  for (std::size_t i = 0; i < rows_.size(); ++i) add_jump(tree_.lines[i], ws_.lines[i].acc, 0.0, false, s[i]);
}

double NetworkSystem::tow_jump(double t) const {
  double size = 0;
  for (std::size_t i = 0; i < rows_.size(); ++i)
    if (tree_.tops[i].line < 0) size = std::max(size, towsim::tow_jump(tree_.lines[i], t).norm());
  return size;
}

bool NetworkSystem::has_nodes() const {
  return std::any_of(tree_.tops.begin(), tree_.tops.end(), [](const LineTop& top) { return top.line >= 0; });
}

double NetworkSystem::apply_tow_jump(StateVector& y, double t) {
  // Each root line's jump: its tow point's plus its sheave's (a jump dl' of
  // the pay-out speed is a jump dl' e_1 of the top material's velocity);
  // none: nothing to do.
  std::vector<Vec3> dv(rows_.size(), Vec3::Zero()), dsheave(rows_.size(), Vec3::Zero());
  const bool winches = net_.has_winch();
  if (winches) tree_state_into(y, js_close_);
  double size = 0;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    if (tree_.tops[i].line >= 0) continue;
    const Model& m = tree_.lines[i];
    if (rows_[i]->winch()) dsheave[i] = sheave_jump(m, js_close_[i], winch_jump(m, js_close_[i], t));
    dv[i] = towsim::tow_jump(m, t) + dsheave[i];
    size = std::max(size, dv[i].norm());
  }
  if (size == 0) return 0;
  // Below kRoundOffJump on a tree with nodes the jump is the difference
  // quotient's round-off at a change of acceleration (a ramp's end): left out.
  if (has_nodes() && size <= NetworkSystem::kRoundOffJump) return 0;
  tree_state_into(y, s_);
  if (!has_nodes()) {
    // Lines joined only through the vessel: each line's own impulsive
    // response (none where its top does not jump: a winch's breakpoint on another line).
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      if (dv[i] == Vec3::Zero()) continue;
      s_[i] = jumped(tree_.lines[i], s_[i], dv[i], t, ws_.lines[i]);
      winch_rates_after_jump(tree_.lines[i], t, dsheave[i], s_[i]);
      rows_[i]->pack(s_[i], y.data() + offset_[i]);
    }
    return size;
  }
  // The tree's impulsive response (loops closed by impulses), then every
  // root's tow rows on its law's right limit (the lines below nodes keep
  // rows for their tops that follow their nodes: not read by the dynamics).
  tree_tow_velocity_jump(tree_, s_, dv, ws_);
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    add_jump(tree_.lines[i], ws_.lines[i].acc, t, tree_.tops[i].line < 0, s_[i]);
    winch_rates_after_jump(tree_.lines[i], t, dsheave[i], s_[i]);
    rows_[i]->pack(s_[i], y.data() + offset_[i]);
  }
  return size;
}

PhysicalState NetworkSystem::physical(const StateVector& y) const {
  PhysicalState s = rows_.front()->shape();
  rows_.front()->unpack(y.data(), s);
  return s;
}

const TreeWorkspace& NetworkSystem::evaluate_tree(const StateVector& y, double t) {
  StateVector dy;
  rates(y, dy, t, StepWindow::after(t));
  return ws_;
}

const Workspace& NetworkSystem::evaluate(const StateVector& y, double t) { return evaluate_tree(y, t).lines.front(); }

std::string NetworkSystem::describe(std::size_t i) const {
  std::size_t line = 0;
  while (line + 1 < offset_.size() && offset_[line + 1] <= i) ++line;
  return "line " + net_.line_names[line] + ": " + rows_[line]->layout().describe(i - offset_[line], tree_.lines[line]);
}

void NetworkSystem::prepare_stage_solve(double t, const StepWindow& window) {
  // The evaluation at the step's start is the Jacobian point (swapped, not copied).
  std::swap(jws_, ws_);
  std::swap(js_, s_);
  tree_local_jacobian(tree_, js_, jws_, window.law_time(t), iw_);
  for (ImplicitWorkspace& w : iw_.lines) w.hg = -1;  // a new Jacobian: factorise again
}

void NetworkSystem::stage_solve(double hg, const StateVector& r, StateVector& k) {
  for (std::size_t i = 0; i < rows_.size(); ++i) rows_[i]->stage_rhs(r.data() + offset_[i], js_[i], rhs_[i]);
  tree_stage_solve(tree_, js_, jws_, hg, rhs_, iw_);
  k.resize(r.size());
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    rows_[i]->stage_result(r.data() + offset_[i], js_[i], rhs_[i], iw_.lines[i], hg, k.data() + offset_[i]);
    if (tree_.tops[i].line >= 0) hold_top_rows(k.data() + offset_[i]);
  }
}

TreeState network_initial_state(const Network& net) {
  const TreeModel& tree = net.tree;
  TreeState s;
  for (const Model& m : tree.lines) {
    if (m.initial.kind == Initial::Kind::Steady)
      throw std::invalid_argument("towsim: network: initial: steady is network_steady_state's (simulate_network)");
    s.push_back(initial_state(m));
    lean_upright(m, s.back());
  }
  // A loop starts closed: assembled from the hanging lines.
  if (!tree.loops.empty() && !(tree_close_loops(tree, s) <= kLoopAssembly))
    throw std::invalid_argument(
        "towsim: network: a loop could not be closed from the initial state (give initial: {direction: ...} "
        "along which the loop's lines can meet)");
  // A line below a node starts at its node: the tree's kinematics give it.
  TreeWorkspace ws(tree);
  tree_forward_dynamics(tree, s, 0.0, ws);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (tree.tops[i].line >= 0) s[i].r0 = ws.top[i], s[i].v0.setZero();
  return s;
}

}  // namespace towsim
