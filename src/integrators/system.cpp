// The default and paper formulations as flat-state systems for the integrators.
#include "towsim/integrators/system.hpp"

#include <bit>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <thread>
#include <utility>

#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/paper.hpp"
#include "towsim/integrators/state_layout.hpp"
#include "towsim/integrators/worker.hpp"

#include "chain_rows.hpp"

namespace towsim {

namespace {

using Map3 = Eigen::Map<Vec3>;
using CMap3 = Eigen::Map<const Vec3>;

/// Write a 3-vector into a flat state at offset i.
void set3(StateVector& y, std::size_t i, const Vec3& v) { y[i] = v.x(), y[i + 1] = v.y(), y[i + 2] = v.z(); }

/// In Motion mode, put the imposed tow position and velocity at t into (r0, v0).
void impose_tow(const Model& m, double t, Vec3& r0, Vec3& v0, CourseCursor& course) {
  if (m.tow.mode != Tow::Mode::Motion) return;
  const TowKinematics k = tow_kinematics(m.tow, t, course);
  r0 = k.pos;
  v0 = k.vel;
}

/// The default system's workspace: the storage its evaluations write and
/// the cache of the stage solves (the Jacobian point). What derivative()
/// returns never depends on it: each evaluation rewrites what it reads, and
/// the cache is read only where it provably holds the same bits.
struct DefaultWorkspace {
  DefaultWorkspace(const Model& m, const PhysicalState& shape) : ws(m), s(shape), jws(m), js(shape), iw(m) {
    rhs.dw.assign(shape.e.size(), Vec3::Zero());
    rhs.rot.assign(shape.e.size(), Vec3::Zero());
    rhs.dwb.assign(shape.bodies.size(), Vec3::Zero());
    rhs.rotb.assign(shape.bodies.size(), Vec3::Zero());
    rhs.dl.assign(shape.e.size(), 0.0);
    rhs.dlr.assign(shape.e.size(), 0.0);
  }
  Workspace ws;             // the last derivative()'s evaluation (last_accelerations)
  PhysicalState s;          // its state
  Workspace jws;            // the evaluation at the step's start (the Jacobian point)
  PhysicalState js;         // its state
  ImplicitWorkspace iw;     // local Jacobian and stage-solve work arrays
  StageRhs rhs;             // one stage's right-hand side, per part
  bool ws_from_s = false;   // ws holds derivative()'s evaluation at s
  bool jac_from_s = false;  // jws holds it at js (swapped with ws_from_s)
};

/// Default formulation: unit vectors e_k, angular velocities, body
/// quaternions; its flat state's blocks: StateLayout::default_of.
class DefaultSystem final : public System {
 public:
  explicit DefaultSystem(const Model& m)
      : model_(m), rows_(m), layout_(rows_.layout()), work_(m, rows_.shape()), threads_(evaluation_threads(m)) {
    n_ = m.cable.n();
    winch_ = rows_.winch();
    elastic_top_ = rows_.elastic_top();
    fixed_length_ = rows_.fixed_length();
  }

  StateVector initial(const PhysicalState& s, double) override {
    StateVector y(layout_.size);
    rows_.pack(s, y.data());
    return y;
  }

  PhysicalState physical(const StateVector& y) const override {
    PhysicalState s = rows_.shape();
    rows_.unpack(y.data(), s);
    return s;
  }

  void physical_into(const StateVector& y, PhysicalState& out) const override {
    out = rows_.shape();  // as physical(y), into storage of the same sizes
    rows_.unpack(y.data(), out);
  }

  void derivative(const StateVector& y, StateVector& dy, double t, const StepWindow& window) override {
    ++rhs_evaluations;
    main_rates(y, dy, t, window, false);
  }

  void derivative_time_shift(const StateVector& y, StateVector& dy, double t, const StepWindow& window) override {
    ++rhs_evaluations;
    main_rates(y, dy, t, window, true);
  }

  /// dy = f(y, t) on the main workspace, uncounted; time_shift: the rigid
  /// elements' inertias from work_.jws when it provably holds them for this state
  /// (work_.jac_from_s and work_.js's directions and body attitudes bitwise those of
  /// work_.s: the inertias read nothing else without a winch or elastic
  /// elements). Bit-identical either way.
  void main_rates(const StateVector& y, StateVector& dy, double t, const StepWindow& window, bool time_shift) {
    work_.ws_from_s = false;  // until the evaluation completes
    rates(y, dy, t, window, work_.s, work_.ws, time_shift, fork());
    work_.ws_from_s = true;
  }

  void start_side_forces(const StateVector& y_side, double t_side, const StepWindow& window,
                         EvaluationForces& side) override {
    if (!use_worker()) {
      System::start_side_forces(y_side, t_side, window, side);
      return;
    }
    SideEvaluation& sv = side_evaluation();
    sv.y = &y_side, sv.t = t_side, sv.window = window, sv.out = &side;
    sv.worker.start(&side_job, this);
    sv.running = true;
  }

  void finish_side_forces(const StateVector& y, StateVector& dy, double t, const StepWindow& window) override {
    if (!side_ || !side_->running) {  // started serially
      System::finish_side_forces(y, dy, t, window);
      return;
    }
    rhs_evaluations += 2;
    // f(y, t) here while the side runs; the side's failure first (serially it comes first).
    std::exception_ptr error;
    try {
      work_.ws_from_s = false;  // until the evaluation completes
      rates(y, dy, t, window, work_.s, work_.ws);
      work_.ws_from_s = true;
    } catch (...) {
      error = std::current_exception();
    }
    side_->running = false;
    side_->worker.wait();
    if (error) std::rethrow_exception(error);
  }

  void cancel_side_forces() noexcept override {
    if (!side_ || !side_->running) return;
    side_->running = false;
    try {
      side_->worker.wait();
    } catch (...) {  // dropped: serially this evaluation never ran
    }
  }

  void expect_side_evaluation() override {
    if (use_worker()) side_evaluation().worker.expect();
  }

  int threads() const override { return threads_; }

  /// The worker as a Fork for the main thread's evaluations (threads 2),
  /// else none: it takes half of the elements' loads when it has no side
  /// evaluation pending (Worker::run_pair).
  Fork* fork() { return use_worker() ? &side_evaluation().worker : nullptr; }

  void project(StateVector& y, double t) override {
    if (model_.tow.mode == Tow::Mode::Motion) {
      const TowKinematics k = tow_kinematics(model_.tow, t, work_.ws.course);
      set3(y, 0, k.pos);
      set3(y, 3, k.vel);
    }
    rows_.normalise(y.data());
    // The winch on its law; a tension winch at its stop: the pay-out speed
    // drops to zero (an impulse).
    const double rate = rows_.project_winch(t, y.data());
    if (rate == 0) return;
    work_.ws_from_s = false;
    y = initial(stopped(model_, physical(y), rate, work_.ws), t);
  }

  const Workspace& evaluate(const StateVector& y, double t) override {
    StateVector dy;
    main_rates(y, dy, t, StepWindow::after(t), false);
    return work_.ws;
  }

  double apply_tow_jump(StateVector& y, double t) override {
    // The tow point's jump, plus the winch's: a jump dl' of the pay-out
    // speed is a jump dl' e_1 of the top material's velocity.
    PhysicalState s = physical(y);
    const double dl = winch_ ? winch_jump(model_, s, t) : 0.0;
    const Vec3 dsheave = winch_ ? Vec3(sheave_jump(model_, s, dl)) : Vec3::Zero();
    const Vec3 dv = tow_jump(model_, t) + dsheave;
    if (dv.norm() == 0) return 0;
    work_.ws_from_s = false;
    s = jumped(model_, s, dv, t, work_.ws);
    winch_rates_after_jump(model_, t, dsheave, s);
    y = initial(s, t);
    return dv.norm();
  }

  bool has_stage_solve() const override { return true; }
  // w_k after the e_k block; a body's w after its quaternion.
  std::size_t element_rate_row(std::size_t k) const override { return layout_.rate(k); }
  std::size_t body_rate_row(std::size_t b) const override { return layout_.body(b) + 4; }

  void prepare_stage_solve(double t, const StepWindow& window) override {
    // Keep the evaluation at the step's start: its kinematics, inertias and
    // forces define the local Jacobian for all stages of the step. Swapped,
    // not copied (~4 % of a km-cable-1000 run): the next derivative()
    // rewrites what it reads of work_.ws and work_.s, the rest is the model's and the
    // same in both (outputs bit-identical, docs/performance.md).
    std::swap(work_.jws, work_.ws);
    std::swap(work_.js, work_.s);
    std::swap(work_.jac_from_s, work_.ws_from_s);
    local_jacobian(model_, work_.js, work_.jws, window.law_time(t), work_.iw.jac);
    work_.iw.hg = -1;  // a new Jacobian: factorise again at the next stage solve
  }

  void stage_solve(double hg, const StateVector& r, StateVector& k) override {
    rows_.stage_rhs(r.data(), work_.js, work_.rhs);
    implicit_stage_solve(model_, work_.js, work_.jws, hg, work_.rhs, work_.iw);
    k.resize(r.size());
    rows_.stage_result(r.data(), work_.js, work_.rhs, work_.iw, hg, k.data());
  }

  const Accelerations* last_accelerations() const override { return &work_.ws.acc; }

  std::string describe(std::size_t i) const override { return layout_.describe(i, model_); }

 private:
  /// work_.jws holds the rigid elements' inertias of s's state (after unpack).
  bool inertias_in_jws(const PhysicalState& s) const {
    if (!work_.jac_from_s || winch_ || rows_.lengths()) return false;
    // Bitwise (-0 and NaN included): the inertias were computed from these bits.
    const auto same = [](const auto& a, const auto& b) {
      for (Eigen::Index i = 0; i < a.size(); ++i)
        if (std::bit_cast<std::uint64_t>(a.data()[i]) != std::bit_cast<std::uint64_t>(b.data()[i])) return false;
      return true;
    };
    for (std::size_t k = 0; k < s.e.size(); ++k)
      if (!same(s.e[k], work_.js.e[k])) return false;
    for (std::size_t b = 0; b < s.bodies.size(); ++b)
      if (!same(s.bodies[b].q.coeffs(), work_.js.bodies[b].q.coeffs())) return false;
    return true;
  }
  /// dy = f(y, t) evaluated on (s, ws): derivative()'s work, on the main
  /// workspace or the worker's. Reads the model and the step's window only.
  void rates(const StateVector& y, StateVector& dy, double t, const StepWindow& window, PhysicalState& s, Workspace& ws,
             bool time_shift = false, Fork* fork = nullptr) const {
    rows_.unpack(y.data(), s);
    const double tl = window.law_time(t);
    impose_tow(model_, tl, s.r0, s.v0, ws.course);
    rows_.impose_winch(tl, s);
    if (time_shift && inertias_in_jws(s))
      forward_dynamics_time_shift(model_, s, tl, work_.jws, ws, fork);
    else
      forward_dynamics(model_, s, tl, ws, fork);
    dy.resize(layout_.size);
    rows_.rates(s, ws, dy.data());
  }
  /// The worker's job: the side evaluation on its own state and workspace.
  static void side_job(void* self) {
    auto& sys = *static_cast<DefaultSystem*>(self);
    SideEvaluation& side = *sys.side_;
    sys.rates(*side.y, side.dy, side.t, side.window, side.s, side.ws);
    side.out->tow_force = side.ws.acc.tow_force;
    side.out->link_force = side.ws.acc.link_force;
  }
  const Model& model_;
  ChainRows rows_;             // the chain's rows: packing, rates, stage right-hand side and result
  const StateLayout& layout_;  // the flat state's blocks (rows_')
  DefaultWorkspace work_;      // storage and caches: derivative()'s results do not depend on it
  int n_ = 0;
  bool winch_ = false;        // the state carries the winch's l_1, l_1'
  bool elastic_top_ = false;  // ... as L_1, L_1' of an elastic top element (l_1, l_1' among the lengths)
  double fixed_length_ = 0;   // deployed length but l_1 [m]

  /// The side evaluation (start_side_forces) on the worker: its
  /// own state and workspace (sized as work_.s and work_.ws; every evaluation rewrites
  /// what it reads of them, the rest is the model's), its inputs and output.
  struct SideEvaluation {
    SideEvaluation(const Model& m, const PhysicalState& s0) : ws(m), s(s0) {}
    Workspace ws;
    PhysicalState s;
    StateVector dy;  // discarded rates
    const StateVector* y = nullptr;
    double t = 0;
    StepWindow window;
    EvaluationForces* out = nullptr;
    bool running = false;  // started, not finished or cancelled yet
    Worker worker;         // last: its thread ends before the rest goes
  };
  /// The worker (threads 2) unless it has stalled kMaxWorkerStalls times,
  /// in at least 1 of 32 waits: another process holds the second core, and
  /// each wait for a job the helper cannot run costs a scheduler slice
  /// (threads 2 ran 3x slower than threads 1 next to one busy process). The
  /// run then goes on without it: the same results, every path being
  /// bit-identical.
  bool use_worker() const {
    if (threads_ < 2) return false;
    if (!side_) return true;
    const int stalls = side_->worker.stalls();
    return stalls < kMaxWorkerStalls || 32L * stalls < side_->worker.waits();
  }
  /// The side evaluation's storage and worker, made at first use.
  SideEvaluation& side_evaluation() {
    if (!side_) side_ = std::make_unique<SideEvaluation>(model_, rows_.shape());
    return *side_;
  }
  int threads_ = 1;                       // evaluation_threads(model_) [-]
  std::unique_ptr<SideEvaluation> side_;  // made at the first side evaluation with threads_ >= 2
};

/// Paper formulation: the angles q in their charts, the charts in the state
/// (they give the angles their meaning); its blocks: StateLayout::paper_of.
class PaperSystem final : public System {
 public:
  explicit PaperSystem(const Model& m) : model_(m), layout_(StateLayout::paper_of(m)), pw_(m), eval_ws_(m) {
    na_ = paper_angle_count(m);
  }

  StateVector initial(const PhysicalState& s, double) override {
    p_ = to_paper(model_, s);
    StateVector y(layout_.size);
    pack(p_, y);
    return y;
  }

  PhysicalState physical(const StateVector& y) const override {
    PaperState p = p_;
    unpack(y, p);
    return from_paper(model_, p);
  }

  void derivative(const StateVector& y, StateVector& dy, double t, const StepWindow& window) override {
    ++rhs_evaluations;
    rates(y, dy, t, window);
  }

  void project(StateVector& y, double t) override {
    unpack(y, p_);
    impose_tow(model_, t, p_.r0, p_.v0, eval_ws_.course);
    rechart(model_, p_);
    pack(p_, y);
  }

  const Workspace& evaluate(const StateVector& y, double t) override {
    // Forces from the paper's own solve; joint tensions from the recursion
    // on the same physical state (they agree to round-off: tests).
    StateVector dy;
    rates(y, dy, t, StepWindow::after(t));
    PhysicalState s = from_paper(model_, p_);
    forward_dynamics(model_, s, t, eval_ws_);
    eval_ws_.acc.tow_force = pw_.acc.tow_force;
    eval_ws_.acc.link_force = pw_.acc.link_force;
    eval_ws_.acc.joint_force.front() = pw_.acc.tow_force;
    if (!model_.bodies.empty()) eval_ws_.acc.joint_force.back() = pw_.acc.link_force[0];
    return eval_ws_;
  }

  double apply_tow_jump(StateVector& y, double t) override {
    const Vec3 dv = tow_jump(model_, t);
    if (dv.norm() == 0) return 0;
    unpack(y, p_);
    const PaperState charts = p_;
    const PhysicalState s = jumped(model_, from_paper(model_, p_), dv, t, eval_ws_);
    // Same charts: only the rates change.
    p_ = to_paper_in_charts(model_, s, charts);
    pack(p_, y);
    return dv.norm();
  }

  std::string describe(std::size_t i) const override { return layout_.describe(i, model_); }

 private:
  /// dy = f(y, t), uncounted, on the workspace (p_, pw_).
  void rates(const StateVector& y, StateVector& dy, double t, const StepWindow& window) {
    unpack(y, p_);
    const double tl = window.law_time(t);
    impose_tow(model_, tl, p_.r0, p_.v0, eval_ws_.course);
    paper_dynamics(model_, p_, tl, pw_);
    dy.resize(y.size());
    set3(dy, 0, p_.v0);
    set3(dy, 3, pw_.acc.a0);
    Eigen::Map<Eigen::VectorXd>(&dy[layout_.angles.offset], na_) = p_.qd;
    Eigen::Map<Eigen::VectorXd>(&dy[layout_.angle_rates.offset], na_) = pw_.qdd;
    // The charts change only by project() (rechart).
    std::fill(dy.begin() + static_cast<std::ptrdiff_t>(layout_.charts.offset), dy.end(), 0.0);
  }
  void pack(const PaperState& p, StateVector& y) const {
    set3(y, 0, p.r0);
    set3(y, 3, p.v0);
    Eigen::Map<Eigen::VectorXd>(&y[layout_.angles.offset], na_) = p.q;
    Eigen::Map<Eigen::VectorXd>(&y[layout_.angle_rates.offset], na_) = p.qd;
    for (std::size_t k = 0; k < p.chart.size(); ++k) Eigen::Map<Mat3>{&y[layout_.chart(k)]} = p.chart[k];
    if (!model_.bodies.empty()) Eigen::Map<Mat3>{&y[layout_.chart(p.chart.size())]} = p.body_chart;
  }
  void unpack(const StateVector& y, PaperState& p) const {
    p.r0 = CMap3(y.data());
    p.v0 = CMap3(&y[3]);
    p.q = Eigen::Map<const Eigen::VectorXd>(&y[layout_.angles.offset], na_);
    p.qd = Eigen::Map<const Eigen::VectorXd>(&y[layout_.angle_rates.offset], na_);
    p.chart.resize(layout_.elements);
    for (std::size_t k = 0; k < p.chart.size(); ++k) p.chart[k] = Eigen::Map<const Mat3>(&y[layout_.chart(k)]);
    if (!model_.bodies.empty()) p.body_chart = Eigen::Map<const Mat3>(&y[layout_.chart(p.chart.size())]);
  }

  const Model& model_;
  StateLayout layout_;  // the flat state's blocks
  int na_ = 0;          // angles [-]
  // The workspace, storage only (derivative()'s results do not depend on it):
  PaperWorkspace pw_;  // the paper's dense solve
  Workspace eval_ws_;  // the recursion's, for outputs and tow jumps
  PaperState p_;       // y's coordinates, unpacked
};

}  // namespace

int evaluation_threads(const Model& model) {
  if (model.sim.integrator != Integrator::Rosenbrock || model.sim.formulation != Formulation::Default) return 1;
  if (model.sim.threads >= 2) return 2;
  if (model.sim.threads == 1) return 1;
  // auto: where the second core pays (docs/performance.md).
  return model.cable.n() >= kAutoThreadsElements && std::thread::hardware_concurrency() >= 2 ? 2 : 1;
}

std::unique_ptr<System> make_system(const Model& model) {
  if (model.sim.formulation == Formulation::Paper && lengths_in_state(model))
    throw std::invalid_argument("towsim: the paper formulation has inextensible elements only (elastic cable given)");
  if (model.sim.formulation == Formulation::Paper) return std::make_unique<PaperSystem>(model);
  return std::make_unique<DefaultSystem>(model);
}

}  // namespace towsim
