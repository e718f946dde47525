// Default formulation: O(n) articulated recursion along the chain of parts
// (docs/theory.md §5.2 "Linear-cost recursion", §5.3 "Bodies in the chain",
// §5.6 "Parts and the sweep").
//
// For the part of the system below joint k (everything hanging from it:
// elements, attachments, bodies), the force f_k it receives through the
// joint is affine in the joint's acceleration: f_k = K_k a_{P_k} + b_k. The
// pass up the chain (sweep::up) builds (K_k, b_k) from the bottom up, each
// part eliminating its own coordinates; the pass down (sweep::down) then
// gives each part's accelerations from the acceleration of the joint above.
#include <algorithm>
#include <stdexcept>

#include "articulated.hpp"
#include "parts/body_node.hpp"
#include "parts/paid_out_element.hpp"
#include "parts/rigid_element.hpp"
#include "sweep.hpp"
#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim {

namespace {

using parts::BodyNode;
using parts::ElementArrays;
using parts::PaidOutElement;
using parts::RigidElement;

/// Forward dynamics' pass up the chain: at each joint, the part below is the
/// element under it plus any attachment there, or a body (which carries the
/// cable hanging from its lower link, if any). With inertias_known, the
/// rigid elements' inertia part (K, T, G T, Phi, H) is the workspace's
/// already, from an evaluation at the same directions and lengths: only their
/// bias part runs (elastic and paid-out elements and bodies: all).
struct ArticulatePass {
  const Model& model;
  const PhysicalState& s;
  Workspace& ws;
  bool inertias_known;
  // Point loads and inertias at the joints exist only with attachments or a
  // seabed; else Ma and Fa are +0 (attachment_loads) and adding them changes
  // no bit: skipped.
  const bool joints = !model.cable.attachments.empty() || model.seabed.has_value();
  const ElementArrays arrays{ws};
  const Element* els = model.cable.elements.data();
  const Vec3 *e = s.e.data(), *w = s.w.data();
  bool symmetric = true;     // K below exactly symmetric (Ma[n]; a rigid element's K, mirrored)
  const Mat3* Kb = nullptr;  // the body's (KQ, bQ) when one hangs below the current element
  const Vec3* bb = nullptr;

  const Mat3& K_below(std::size_t k, bool body) const { return body ? *Kb : arrays.K[k + 1]; }
  const Vec3& b_below(std::size_t k, bool body) const { return body ? *bb : arrays.b[k + 1]; }
  void end(std::size_t n) {
    // Below the cable's end hang its attachments and, at a junction of a
    // tree of lines, the lines below it.
    ws.K[n] = ws.Ma[n];
    ws.b[n] = -ws.Fa[n];
    if (ws.end_children) ws.K[n] += ws.end_K, ws.b[n] += ws.end_b;
  }
  void body(std::size_t b, std::size_t j) {
    BodyWork& bw = ws.body[b];
    BodyNode::articulate(model.bodies[b], bw, arrays.K[j], arrays.b[j]);
    Kb = &bw.KQ;
    bb = &bw.bQ;
    symmetric = false;
  }
  void elastic(std::size_t k, bool body) {
    elastic_backward(s.e[k], s.length_of(model, k), ws.Mt[k], ws.F[k], ws.Mom[k], K_below(k, body), b_below(k, body),
                     ws.elastic[k], ws.K[k], ws.b[k]);
    ws.K[k] += ws.Ma[k];
    symmetric = false;
  }
  void paid_out_elastic(std::size_t k, bool body) { elastic(k, body); }
  void rigid_element(const Element& el, std::size_t k, bool body, bool inertia) {
    const Mat3& Kk = K_below(k, body);
    if (inertia) {
      if (symmetric)
        RigidElement::inertia<true>(el, e[k], Kk, k, arrays);
      else
        RigidElement::inertia<false>(el, e[k], Kk, k, arrays);
      if (joints) ws.K[k] += ws.Ma[k];
    }
    RigidElement::bias(el, e[k], w[k], Kk, b_below(k, body), k, arrays);
    symmetric = true;
  }
  void rigid(std::size_t k, bool body) { rigid_element(els[k], k, body, !inertias_known); }
  // The winch's top: its length moves with time, its inertia part always runs.
  void paid_out(std::size_t k, bool body) { rigid_element(ws.top, k, body, true); }
  // An attachment at joint k moves with it: its inertia (above) and loads add on.
  void joint(std::size_t k) {
    if (joints) ws.b[k] -= ws.Fa[k];
  }
};

/// Forward dynamics' pass down the chain: the tow-point acceleration or tow
/// force, then each element's angular acceleration and joint force, and each
/// body's. imposed_a0: an impulse's tow-point velocity jump (no pay-out).
struct AcceleratePass {
  const Model& model;
  const PhysicalState& s;
  double t;
  Workspace& ws;
  const Vec3* imposed_a0;
  Accelerations& acc = ws.acc;
  // The arrays' data through local pointers: the compiler cannot tell that
  // the stores into them leave the vectors alone, and would reload each
  // one's start per element.
  const Eigen::Matrix<double, 3, 2>*T = ws.T.data(), *GT = ws.GT.data();
  const Eigen::Matrix2d* Phi = ws.Phi.data();
  const Eigen::Vector2d* Tr0 = ws.Tr0.data();
  const Vec3 *c = ws.c.data(), *e = s.e.data(), *bs = ws.b.data();
  const double* Ls = ws.L.data();
  const Mat3* Ks = ws.K.data();
  Vec3 *alpha = acc.alpha.data(), *joint_force = acc.joint_force.data();
  Vec3 a = Vec3::Zero();  // acceleration of the current joint [m/s^2, R_g]

  void top() {
    // Winch: the top element's material at the sheave accelerates at a_0 +
    // l'' e_1 plus the Coriolis terms (PaidOutElement::top); the recursion
    // runs from there unchanged.
    acc.top_length_acc = 0;
    const bool winch = ws.winch && !imposed_a0;  // an impulse (imposed_a0) has no pay-out acceleration
    const bool elastic_top = winch && is_elastic(model.cable.elements[0]);
    const Vec3 e1 = s.e.empty() ? Vec3::UnitZ().eval() : s.e[0];  // [-, R_g]
    const PaidOutElement::Top pay = winch ? PaidOutElement::top(model, s, ws, elastic_top) : PaidOutElement::Top{};
    const Vec3& a_extra = pay.a_extra;                                   // a_top - a_0 without the l'' term
    const Mat3 K_pay = elastic_top ? Mat3(pay.lam * ws.K[0]) : ws.K[0];  // d(f_0)/d(L_1'') along e_1 [kg]
    if (winch && model.winch.mode == Winch::Mode::Imposed) acc.top_length_acc = winch_kinematics(model.winch, t).acc;
    if (imposed_a0 || model.tow.mode == Tow::Mode::Motion) {
      acc.a0 = imposed_a0 ? *imposed_a0 : tow_kinematics(model.tow, t, ws.course).acc;
      if (winch && model.winch.mode == Winch::Mode::Tension)
        acc.top_length_acc = PaidOutElement::drum_acceleration(model.winch, e1, pay.pay_rate,
                                                               PaidOutElement::deployed_length(model, s), K_pay,
                                                               ws.K[0] * (acc.a0 + a_extra) + ws.b[0]);
    }
    const Vec3 a_pay = elastic_top ? Vec3(pay.lam * acc.top_length_acc * e1) : Vec3(acc.top_length_acc * e1);
    if (imposed_a0 || model.tow.mode == Tow::Mode::Motion) {
      acc.tow_force = ws.K[0] * (acc.a0 + a_extra + a_pay) + ws.b[0];
    } else {
      acc.tow_force = tow_force(model.tow, t);
      acc.a0 = ws.K[0].ldlt().solve(acc.tow_force - ws.b[0]) - a_extra - a_pay;
    }
    acc.joint_force[0] = acc.tow_force;
    a = acc.a0 + a_extra + a_pay;
  }
  void rigid(std::size_t k) { RigidElement::accelerate(T[k], Phi[k], Tr0[k], GT[k], c[k], e[k], Ls[k], a, alpha[k]); }
  void paid_out(std::size_t k) { rigid(k); }
  // Elastic element: d'' from the top joint's acceleration (§5.4).
  void elastic(std::size_t k) {
    a += elastic_forward(ws.elastic[k], s.e[k], s.w[k], s.length_of(model, k), s.length_rate_of(k), a, acc.alpha[k],
                         acc.length_acc[k]);
  }
  // The winch's elastic element: its top is the material at the sheave
  // (an impulse has no pay-out: the plain elastic step).
  void paid_out_elastic(std::size_t k) {
    if (imposed_a0) return elastic(k);
    a += elastic_forward(ws.elastic[0], s.e[0], s.w[0], s.length_of(model, 0), s.length_rate_of(0), a, Vec3(a - acc.a0),
                         acc.alpha[0], acc.length_acc[0]);
  }
  void body(std::size_t b, std::size_t j) {
    const Body& body = model.bodies[b];
    BodyNode::accelerate(body, ws.body[b], ws.K[j], ws.b[j], b, a, acc);
    acc.joint_force[j] = body.inline_body ? acc.lower_link_force[b] : acc.link_force[b];
  }
  void joint(std::size_t j) const { joint_force[j] = Ks[j] * a + bs[j]; }
};

}  // namespace

// Each pass in its own function: small enough for the compiler to inline
// its parts' 3x3 algebra (one function with both passes was not).

[[gnu::noinline, gnu::flatten]] void chain::articulate(const Model& model, const PhysicalState& s, Workspace& ws,
                                                       bool inertias_known) {
  ArticulatePass up{model, s, ws, inertias_known};
  sweep::up(model, ws, up);
}

[[gnu::noinline, gnu::flatten]] void chain::accelerate(const Model& model, const PhysicalState& s, double t,
                                                       Workspace& ws, const Vec3* imposed_a0) {
  AcceleratePass down{model, s, t, ws, imposed_a0};
  sweep::down(model, ws, down);
  ws.acc.end_acc = down.a;  // the last joint's (an end body's link point)
}

namespace {

/// Both passes of the forward dynamics at the loads and kinematics ws holds.
void articulated_sweep(const Model& model, const PhysicalState& s, double t, Workspace& ws, bool inertias_known,
                       const Vec3* imposed_a0 = nullptr) {
  chain::articulate(model, s, ws, inertias_known);
  chain::accelerate(model, s, t, ws, imposed_a0);
}

/// The dynamics' entry check (Pinocchio's model.check(data)).
void check_fits(const Model& model, const PhysicalState& s, const Workspace& ws) {
  if (!ws.fits(model) || s.e.size() != model.cable.elements.size() || s.w.size() != s.e.size() ||
      s.bodies.size() != model.bodies.size() ||
      !std::all_of(model.bodies.begin(), model.bodies.end(), [&](const Body& b) {
        const auto i = static_cast<std::size_t>(&b - model.bodies.data());
        return s.bodies[i].controls.size() == static_cast<std::size_t>(control_count(b)) &&
               ws.body[i].deflection.size() == s.bodies[i].controls.size();
      }))
    throw std::logic_error("towsim: workspace or state does not fit the model");
}

}  // namespace

void compute_loads(const Model& model, const PhysicalState& s, double t, Workspace& ws, Fork* fork) {
  const auto& els = model.cable.elements;
  // Each element's loads, mass matrix and axial force (+ stop) from its own
  // kinematics: the elements in [begin, end).
  auto elements = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Element& el = current_element(model, ws, k);
      element_loads(model, el, s.e[k], ws.edot[k], ws.vG[k], ws.G[k], t, ws.F[k], ws.Mom[k], &ws.Uw[k]);
      ws.Mt[k] = element_mass(el, s.e[k]);
      ws.elastic[k].T = element_axial_force(els[k], s.length_of(model, k), s.length_rate_of(k));
    }
  };
  const std::size_t n = els.size();
  if (fork != nullptr && n >= kSplitLoadsElements) {
    // The upper half on the fork's other thread, the lower one here.
    const std::size_t m = n / 2;
    auto upper = [&] { elements(0, m); };
    auto lower = [&] { elements(m, n); };
    fork_pair(fork, upper, lower);
  } else {
    elements(0, n);
  }
  // The winch's elastic top element: strain of l_1 over the paid-out L_1.
  if (ws.winch && is_elastic(els[0]))
    ws.elastic[0].T = paid_out_tension(ws.top, s.length_of(model, 0), s.length_rate_of(0), s.top_unstretched_rate);
  bending_loads(model, s, ws);  // couples of the bending springs at the joints
  attachment_loads(model, t, ws);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    body_inertia(model.fluid, model.bodies[b], ws.body[b], t);
    body_loads(model.fluid, model.bodies[b], t, ws.body[b]);
  }
  seabed_loads(model, ws);  // point loads at joints (ws.Fa) and on bodies, like attachments
}

void tow_velocity_jump(const Model& model, const PhysicalState& s, const Vec3& dv, Workspace& ws) {
  check_fits(model, s, ws);
  // Same recursion at zero velocity with zero finite loads: only inertia and
  // the joint impulses remain; "accelerations" are then velocity jumps.
  PhysicalState s0 = s;
  s0.v0.setZero();
  for (auto& w : s0.w) w.setZero();
  for (auto& r : s0.length_rate) r = 0;
  for (auto& bs : s0.bodies) bs.w.setZero();
  compute_kinematics(model, s0, ws);
  compute_loads(model, s0, 0.0, ws);
  for (std::size_t k = 0; k < ws.F.size(); ++k) ws.F[k].setZero(), ws.Mom[k].setZero();
  for (auto& f : ws.Fa) f.setZero();
  for (auto& ew : ws.elastic) ew.T = 0;  // a finite tension gives no impulse
  for (auto& bw : ws.body) bw.Fb.setZero(), bw.Mb.setZero(), bw.hw.setZero();
  articulated_sweep(model, s0, 0.0, ws, false, &dv);
}

void forward_dynamics(const Model& model, const PhysicalState& s, double t, Workspace& ws, Fork* fork) {
  check_fits(model, s, ws);
  compute_kinematics(model, s, ws);
  compute_loads(model, s, t, ws, fork);
  articulated_sweep(model, s, t, ws, false);
}

void forward_dynamics_time_shift(const Model& model, const PhysicalState& s, double t, const Workspace& inertias,
                                 Workspace& ws, Fork* fork) {
  check_fits(model, s, ws);
  if (!inertias.fits(model)) throw std::logic_error("towsim: workspace does not fit the model");
  // The rigid elements' inertia part, as the evaluation at s's directions
  // and lengths left it (same sizes: copied in place, no allocation).
  if (&inertias != &ws) {
    std::copy(inertias.K.begin(), inertias.K.end(), ws.K.begin());
    std::copy(inertias.T.begin(), inertias.T.end(), ws.T.begin());
    std::copy(inertias.GT.begin(), inertias.GT.end(), ws.GT.begin());
    std::copy(inertias.Phi.begin(), inertias.Phi.end(), ws.Phi.begin());
    std::copy(inertias.H.begin(), inertias.H.end(), ws.H.begin());
  }
  // Everything that moves with time (the imposed tow motion through r0, v0;
  // current, waves, schedules through the loads): as forward_dynamics.
  compute_kinematics(model, s, ws);
  compute_loads(model, s, t, ws, fork);
  articulated_sweep(model, s, t, ws, true);
}

}  // namespace towsim
