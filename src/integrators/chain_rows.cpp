// One chain's rows of a flat state in the default formulation.
#include "chain_rows.hpp"

#include <algorithm>

#include "towsim/dynamics/dynamics.hpp"
#include "towsim/model/depth_control.hpp"
#include "towsim/model/winch.hpp"

namespace towsim {

namespace {

using Map3 = Eigen::Map<Vec3>;
using CMap3 = Eigen::Map<const Vec3>;

/// Write a 3-vector into rows i..i+2.
void set3(double* y, std::size_t i, const Vec3& v) { y[i] = v.x(), y[i + 1] = v.y(), y[i + 2] = v.z(); }

}  // namespace

Vec3 tow_jump(const Model& m, double t) {
  if (m.tow.mode != Tow::Mode::Motion) return Vec3::Zero();
  const double d = 1e-9 * std::max(1.0, std::abs(t));
  return tow_kinematics(m.tow, t + d).vel - tow_kinematics(m.tow, t - d).vel;
}

void add_jump(const Model& m, const Accelerations& jump, double t, bool tow_law, PhysicalState& s) {
  for (std::size_t k = 0; k < s.w.size(); ++k) s.w[k] += jump.alpha[k];
  for (std::size_t k = 0; k < s.length_rate.size(); ++k) s.length_rate[k] += jump.length_acc[k];
  for (std::size_t b = 0; b < s.bodies.size(); ++b) s.bodies[b].w += jump.alpha_b[b];
  if (!tow_law || m.tow.mode != Tow::Mode::Motion) return;
  const double d = 1e-9 * std::max(1.0, std::abs(t));
  s.r0 = tow_kinematics(m.tow, t).pos;
  s.v0 = tow_kinematics(m.tow, t + d).vel;
}

PhysicalState jumped(const Model& m, PhysicalState s, const Vec3& dv, double t, Workspace& ws) {
  tow_velocity_jump(m, s, dv, ws);
  add_jump(m, ws.acc, t, true, s);
  return s;
}

double winch_jump(const Model& m, const PhysicalState& s, double t) {
  if (m.winch.mode != Winch::Mode::Imposed) return 0;
  return winch_kinematics(m.winch, t).rate - payout_rate(m, s);
}

Vec3 sheave_jump(const Model& m, const PhysicalState& s, double dL) {
  if (!elastic_winch(m)) return dL * s.e[0];
  return s.length_of(m, 0) / s.top_unstretched * dL * s.e[0];
}

void winch_rates_after_jump(const Model& m, double t, const Vec3& dsheave, PhysicalState& s) {
  if (!m.winch.active() || m.winch.mode != Winch::Mode::Imposed) return;
  if (elastic_winch(m)) {
    // l_1' = (d_1' relative to the sheave's material) + the sheave's pay-out.
    s.length_rate[0] += dsheave.dot(s.e[0]);
    s.top_unstretched_rate = winch_kinematics(m.winch, t).rate;
  } else {
    s.length_rate[0] = winch_kinematics(m.winch, t).rate;
  }
}

void winch_rates_after_stop(const Model& m, const Vec3& dv, PhysicalState& s) {
  if (elastic_winch(m)) {
    s.length_rate[0] += dv.dot(s.e[0]);
    s.top_unstretched_rate = 0;
  } else {
    s.length_rate[0] = 0;
  }
}

PhysicalState stopped(const Model& m, PhysicalState s, double rate, Workspace& ws) {
  const Vec3 dv = -sheave_jump(m, s, rate);
  tow_velocity_jump(m, s, dv, ws);
  for (std::size_t k = 0; k < s.w.size(); ++k) s.w[k] += ws.acc.alpha[k];
  for (std::size_t b = 0; b < s.bodies.size(); ++b) s.bodies[b].w += ws.acc.alpha_b[b];
  // The elements' stretch rates jump too (over an elastic top element).
  if (elastic_winch(m))
    for (std::size_t k = 0; k < s.length_rate.size(); ++k) s.length_rate[k] += ws.acc.length_acc[k];
  winch_rates_after_stop(m, dv, s);
  return s;
}

ChainRows::ChainRows(const Model& m)
    : model_(m), layout_(StateLayout::default_of(m)), shape_(PhysicalState::hanging(m)) {
  n_ = m.cable.n();
  winch_ = layout_.winch.size > 0;
  elastic_top_ = elastic_winch(m);
  lengths_ = layout_.lengths.size > 0;
  // Length control: l_1 = L(t) - (the fixed elements below + cable drawn in by removals).
  fixed_length_ = m.winch.length_offset;
  for (int k = 1; k < n_; ++k) fixed_length_ += m.cable.elements[static_cast<std::size_t>(k)].length;
}

void ChainRows::pack(const PhysicalState& s, double* y) const {
  set3(y, 0, s.r0);
  set3(y, 3, s.v0);
  for (int k = 0; k < n_; ++k) {
    set3(y, layout_.direction(k), s.e[k]);
    set3(y, layout_.rate(k), s.w[k]);
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const std::size_t o = layout_.body(b);
    const Quat& q = s.bodies[b].q;
    y[o] = q.w(), y[o + 1] = q.x(), y[o + 2] = q.y(), y[o + 3] = q.z();
    set3(y, o + 4, s.bodies[b].w);
  }
  if (elastic_top_)
    y[layout_.winch.offset] = s.top_unstretched, y[layout_.winch.offset + 1] = s.top_unstretched_rate;
  else if (winch_)
    y[layout_.winch.offset] = element_length(model_, s, 0), y[layout_.winch.offset + 1] = element_length_rate(s, 0);
  if (lengths_) {
    for (int k = 0; k < n_; ++k) {
      y[layout_.length(k)] = s.length_of(model_, k);
      y[layout_.length_rate(k)] = s.length_rate_of(k);
    }
  }
  // Depth controllers: [I, delta] each, bodies in order, surfaces in order.
  std::size_t i = 0;
  for (const BodyState& bs : s.bodies)
    for (const ControlState& c : bs.controls)
      y[layout_.control(i)] = c.integral, y[layout_.control(i++) + 1] = c.deflection;
}

void ChainRows::unpack(const double* y, PhysicalState& s) const {
  s.r0 = CMap3(y);
  s.v0 = CMap3(&y[3]);
  for (int k = 0; k < n_; ++k) {
    s.e[k] = CMap3(&y[layout_.direction(k)]);
    s.w[k] = CMap3(&y[layout_.rate(k)]);
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const std::size_t o = layout_.body(b);
    s.bodies[b].q = Quat(y[o], y[o + 1], y[o + 2], y[o + 3]).normalized();
    s.bodies[b].w = CMap3(&y[o + 4]);
  }
  if (elastic_top_)
    s.top_unstretched = y[layout_.winch.offset], s.top_unstretched_rate = y[layout_.winch.offset + 1];
  else if (winch_)
    s.length[0] = y[layout_.winch.offset], s.length_rate[0] = y[layout_.winch.offset + 1];
  if (lengths_) {
    for (int k = 0; k < n_; ++k) {
      s.length[k] = y[layout_.length(k)];
      s.length_rate[k] = y[layout_.length_rate(k)];
    }
  }
  std::size_t i = 0;
  for (BodyState& bs : s.bodies)
    for (ControlState& c : bs.controls) c.integral = y[layout_.control(i)], c.deflection = y[layout_.control(i++) + 1];
}

void ChainRows::impose_winch(double t, PhysicalState& s) const {
  // Over an elastic top element L_1 stays the state's (integrated exactly
  // from the schedule's L_1'', reset to it after every step): the
  // Rosenbrock-W stage solve sees the spring's dependence on it.
  if (!winch_ || model_.winch.mode != Winch::Mode::Imposed || elastic_top_) return;
  const WinchKinematics k = winch_kinematics(model_.winch, t);
  s.length[0] = k.length - fixed_length_;
  s.length_rate[0] = k.rate;
}

double ChainRows::project_winch(double t, double* y) const {
  if (!winch_) return 0;
  if (model_.winch.mode == Winch::Mode::Imposed) {
    const WinchKinematics k = winch_kinematics_before(model_.winch, t);
    y[layout_.winch.offset] = k.length - fixed_length_;
    y[layout_.winch.offset + 1] = k.rate;
    return 0;
  }
  // Tension control: the speed limit, then the stops at min_length and max_length.
  double& l = y[layout_.winch.offset];
  double& rate = y[layout_.winch.offset + 1];
  rate = std::clamp(rate, -model_.winch.max_speed, model_.winch.max_speed);
  const double L = l + fixed_length_;
  const bool at_max = L >= model_.winch.max_length && rate > 0;
  const bool at_min = L <= model_.winch.min_length && rate < 0;
  if (!at_max && !at_min) return 0;
  l = (at_max ? model_.winch.max_length : model_.winch.min_length) - fixed_length_;
  return rate;
}

void ChainRows::rates(const PhysicalState& s, const Workspace& ws, double* dy) const {
  if (elastic_top_)
    dy[layout_.winch.offset] = s.top_unstretched_rate, dy[layout_.winch.offset + 1] = ws.acc.top_length_acc;
  else if (winch_)
    dy[layout_.winch.offset] = s.length_rate[0], dy[layout_.winch.offset + 1] = ws.acc.top_length_acc;
  // de/dt = w x e, dw/dt = alpha; dq/dt = 1/2 (0, w_body) q.
  set3(dy, 0, s.v0);
  set3(dy, 3, ws.acc.a0);
  for (int k = 0; k < n_; ++k) {
    set3(dy, layout_.direction(k), s.w[k].cross(s.e[k]));
    set3(dy, layout_.rate(k), ws.acc.alpha[k]);
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const std::size_t o = layout_.body(b);
    const BodyState& bs = s.bodies[b];
    const Quat dq = Quat(0, bs.w.x(), bs.w.y(), bs.w.z()) * bs.q;
    dy[o] = 0.5 * dq.w(), dy[o + 1] = 0.5 * dq.x(), dy[o + 2] = 0.5 * dq.y(), dy[o + 3] = 0.5 * dq.z();
    set3(dy, o + 4, ws.acc.alpha_b[b]);
  }
  // dl/dt = l', dl'/dt = l''.
  if (lengths_) {
    for (int k = 0; k < n_; ++k) {
      dy[layout_.length(k)] = s.length_rate[k];
      dy[layout_.length_rate(k)] = ws.acc.length_acc[k];
    }
  }
  // Depth controllers: dI/dt and d delta/dt from the depth of each controlled body.
  std::size_t i = 0;
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const BodyWork& bw = ws.body[b];
    std::size_t c = 0;
    for (const LiftingSurface& ls : model_.bodies[b].surfaces) {
      if (!ls.depth_control) continue;
      const ControlRates r = depth_control_rates(*ls.depth_control, s.bodies[b].controls[c++], -bw.O.z(), -bw.vO.z());
      dy[layout_.control(i)] = r.dintegral, dy[layout_.control(i++) + 1] = r.ddeflection;
    }
  }
}

void ChainRows::normalise(double* y) const {
  for (int k = 0; k < n_; ++k) {
    Map3 e(&y[layout_.direction(k)]), w(&y[layout_.rate(k)]);
    e.normalize();
    w -= w.dot(e) * e;
  }
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    Eigen::Map<Eigen::Vector4d> q(&y[layout_.body(b)]);
    q.normalize();
  }
}

void ChainRows::stage_rhs(const double* r, const PhysicalState& js, StageRhs& rhs) const {
  // Velocity rows: (M + hg C + hg^2 K) z = -(hg C + hg^2 K) r_v - hg K rot(r_x), k_v = r_v + z.
  rhs.dv0 = CMap3(&r[3]);
  rhs.dx0 = CMap3(r);
  for (int i = 0; i < n_; ++i) {
    rhs.dw[i] = CMap3(&r[layout_.rate(i)]);
    rhs.rot[i] = js.e[i].cross(CMap3(&r[layout_.direction(i)]));
  }
  for (std::size_t b = 0; b < js.bodies.size(); ++b) {
    const std::size_t o = layout_.body(b);
    rhs.dwb[b] = CMap3(&r[o + 4]);
    // dq = 1/2 (0, rot) q  =>  rot = 2 vec(dq q^-1).
    rhs.rotb[b] = 2 * (Quat(r[o], r[o + 1], r[o + 2], r[o + 3]) * js.bodies[b].q.conjugate()).vec();
  }
  // Lengths' rows (elastic elements; a winch's top length: below).
  if (lengths_) {
    for (int i = 0; i < n_; ++i) {
      const bool el = is_elastic(model_.cable.elements[static_cast<std::size_t>(i)]);
      rhs.dl[i] = el ? r[layout_.length(i)] : 0.0;
      rhs.dlr[i] = el ? r[layout_.length_rate(i)] : 0.0;
    }
  }
  // A tension-controlled winch's rows (l_1, l_1'): the drum in the stage solve.
  // (Over an elastic top element the winch sets its unstretched L_1, which
  // moves no joint: W = I on those rows.)
  const bool drum = winch_ && model_.winch.mode == Winch::Mode::Tension && !elastic_top_;
  rhs.winch_dl = drum ? r[layout_.winch.offset] : 0.0;
  rhs.winch_dlr = drum ? r[layout_.winch.offset + 1] : 0.0;
  if (elastic_top_) {
    // The top element's spring and damper see L_1, L_1' (their rows stay explicit: W = I there).
    const double lam = js.length[0] / js.top_unstretched;
    rhs.top_dL = lam * r[layout_.winch.offset];
    rhs.top_dLr = lam * r[layout_.winch.offset + 1];
  }
}

void ChainRows::stage_result(const double* r, const PhysicalState& js, const StageRhs& rhs, const ImplicitWorkspace& iw,
                             double hg, double* k) const {
  // Rows without local terms keep k = r (W = I there: still a W-method);
  // the tow point's and the elements' rows (the first layout_.bodies.offset) are
  // all written below, so only the rest is copied.
  std::copy(r + layout_.bodies.offset, r + layout_.size, k + layout_.bodies.offset);
  // Position rows: k_x = r_x + hg B k_v (B: velocities -> position rates at the step's start).
  const Vec3 kv0 = CMap3(&r[3]) + iw.a0;
  set3(k, 3, kv0);
  set3(k, 0, CMap3(r) + hg * kv0);
  for (int i = 0; i < n_; ++i) {
    const Vec3 kw = rhs.dw[i] + iw.alpha[i];
    set3(k, layout_.rate(i), kw);
    set3(k, layout_.direction(i), CMap3(&r[layout_.direction(i)]) + hg * kw.cross(js.e[i]));
  }
  if (lengths_) {
    // k_l' = r_l' + z_l, k_l = r_l + hg k_l' (elastic elements; z_l = 0 else).
    for (int i = 0; i < n_; ++i) {
      if (!is_elastic(model_.cable.elements[static_cast<std::size_t>(i)])) continue;
      const std::size_t l = layout_.length(i), lr = layout_.length_rate(i);
      const double klr = r[lr] + iw.zl[i];
      k[lr] = klr;
      k[l] = r[l] + hg * klr;
    }
  }
  const bool drum = winch_ && model_.winch.mode == Winch::Mode::Tension && !elastic_top_;
  if (drum && model_.tow.mode == Tow::Mode::Motion) {
    // k_l' = r_l' + z_l, k_l = r_l + hg k_l' (Force mode: W = I there).
    k[layout_.winch.offset + 1] = r[layout_.winch.offset + 1] + iw.z_winch;
    k[layout_.winch.offset] = r[layout_.winch.offset] + hg * k[layout_.winch.offset + 1];
  }
  for (std::size_t b = 0; b < js.bodies.size(); ++b) {
    const std::size_t o = layout_.body(b);
    const Vec3 kw = rhs.dwb[b] + iw.alpha_b[b];
    set3(k, o + 4, kw);
    const Quat dq = Quat(0, kw.x(), kw.y(), kw.z()) * js.bodies[b].q;
    k[o] = r[o] + 0.5 * hg * dq.w(), k[o + 1] = r[o + 1] + 0.5 * hg * dq.x();
    k[o + 2] = r[o + 2] + 0.5 * hg * dq.y(), k[o + 3] = r[o + 3] + 0.5 * hg * dq.z();
  }
}

}  // namespace towsim
