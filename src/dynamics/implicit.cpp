// Linear stage solves of the Rosenbrock-W integrator (docs/theory.md §6.3):
// the articulated recursion of fast.cpp at zero velocity, with the inertia of
// each part increased by its local damping and stiffness, M + hg C + hg^2 K,
// and the right-hand side given as loads on the parts. Cost O(n).
#include "towsim/dynamics/implicit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../body/body_load_laws.hpp"
#include "../hydro/drag_laws.hpp"
#include "articulated.hpp"
#include "parts/body_node.hpp"
#include "parts/coupled_element.hpp"
#include "parts/elastic_element.hpp"
#include "parts/rigid_element.hpp"
#include "sweep.hpp"
#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/elastic.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/model/table.hpp"

namespace towsim {

namespace {

inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// psd_part for N = 3 or 6.
template <int N>
Eigen::Matrix<double, N, N> psd_part_n(const Eigen::Matrix<double, N, N>& A) {
  Eigen::Matrix<double, N, N> S = 0.5 * (A + A.transpose());
  // Positive semi-definite (a pivoted LDL^T with no negative pivot): nothing
  // to drop, no eigensolve (the common case: drag damping, hanging bodies).
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(S);
  if (ldlt.info() == Eigen::Success && ldlt.isPositive()) return S;
  // 3x3: the closed form (roots of the characteristic cubic; ~sqrt(eps) |S|
  // near a double eigenvalue, tests/unit/test_psd_part.cpp); 6x6: QR iteration.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> es;
  if constexpr (N == 3)
    es.computeDirect(S);
  else
    es.compute(S);
  const Eigen::Matrix<double, N, 1> l = es.eigenvalues().cwiseMax(0.0);
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}

/// Gradient of a field at O_t + c along the displacements of c as the body
/// turns about O_t, dc = -[c]x dtheta: central differences in theta (steps
/// 1e-6 rad, as the rotations of body_local_jacobian's stiffness).
template <class Field>
Mat3 turned_gradient(const Vec3& O, const Vec3& c, Field&& field) {
  const double da = 1e-6;
  Mat3 Gc;
  for (int j = 0; j < 3; ++j) {
    const Mat3 Rp = Eigen::AngleAxisd(da, Vec3::Unit(j)).toRotationMatrix();
    Gc.col(j) = (field(Vec3(O + Rp * c)) - field(Vec3(O + Rp.transpose() * c))) / (2 * da);
  }
  return Gc;
}

}  // namespace

Mat3 psd_part(const Mat3& A) { return psd_part_n<3>(A); }
Mat6 psd_part(const Mat6& A) { return psd_part_n<6>(A); }

namespace {

/// The derivatives of a body's load laws (body_laws::visit_body_loads):
/// D = -d(F; M)/d(v_O; omega) and dM/dtheta (M about O_t, R_g). A force F at
/// c = R c_b turning with the body moves its point by dc = -[c]x dtheta:
/// dM = dc x F + c x dF = ([F]x [c]x + [c]x dF/dtheta) dtheta.
struct LoadDerivatives {
  const Fluid& fluid;
  const BodyWork& bw;
  double t;
  Mat6 D = Mat6::Zero();
  Mat3 dM = Mat3::Zero();

  /// A force fixed in R_g: only its point turns.
  void world(const Vec3& c, const Vec3& F) { dM.noalias() += skew(F) * skew(c); }
  /// A force turning with the body: dF = dtheta x F as well.
  void turning(const Vec3& c, const Vec3& F) {
    world(c, F);
    dM.noalias() -= skew(c) * skew(F);
  }
  /// Froude-Krylov: dF = rho V grad(a_w) dc.
  void waves(const Vec3& c, const Vec3& F, double rV) {
    world(c, F);
    dM.noalias() += skew(c) * rV * turned_gradient(bw.O, c, [&](const Vec3& x) { return fluid.acceleration(x, t); });
  }
  /// A velocity-dependent load at c: dF/d(v_O, omega) = A [I, -[c]x]; as the
  /// body turns, u changes by w x dc - grad(U) dc and the load's axes turn
  /// with it, dF = dtheta x F - A (dtheta x u) (the laws are isotropic):
  /// dF/dtheta = A ([u]x - [w]x [c]x + grad(U) [c]x) - [F]x.
  void flow(const Vec3& c, const Vec3& u, const body_laws::PointLoad& p) {
    Eigen::Matrix<double, 3, 6> J;
    J << Mat3::Identity(), -skew(c);
    Eigen::Matrix<double, 6, 3> Jt;
    Jt << Mat3::Identity(), skew(c);
    D.noalias() -= Jt * p.A * J;
    Mat3 dFdt = p.A * (skew(u) - skew(bw.w) * skew(c)) - skew(p.F);
    if (!fluid.uniform())
      dFdt.noalias() -= p.A * turned_gradient(bw.O, c, [&](const Vec3& x) { return fluid.velocity(x, t); });
    world(c, p.F);
    dM.noalias() += skew(c) * dFdt;
  }
  /// Generic damping: dtau/dnu_r = -T, so -d(F; M)/d(v_O; omega) = B T B^T,
  /// B = diag(R, R). Turning: d(B tau) = dtheta x (B tau) + B dtau,
  /// dnu_r = B^T [x]x dtheta, x = (xr; omega).
  void damping(const Vec3& xr, const Vec6& /*nur*/, const Vec6& tau, const Mat6& T) {
    Mat6 B = Mat6::Zero();
    B.topLeftCorner<3, 3>() = bw.R;
    B.bottomRightCorner<3, 3>() = bw.R;
    const Mat6 BTB = B * T * B.transpose();
    D += BTB;
    Eigen::Matrix<double, 6, 3> X;
    X << skew(xr), skew(bw.w);
    dM.noalias() -= skew(Vec3(bw.R * tau.tail<3>())) + (BTB * X).bottomRows<3>();
  }
};

}  // namespace

void body_load_derivatives(const Fluid& fluid, const Body& body, const BodyWork& bw, double t, Mat6& D, Mat3& KO) {
  LoadDerivatives d{fluid, bw, t};
  body_laws::visit_body_loads<true>(fluid, body, t, bw, d);
  D = d.D;
  KO = -d.dM;  // KO = -dM/dtheta
}

Mat3 body_line_stiffness(const Body& body, const BodyWork& bw, const Vec3& lower_link_force) {
  Mat3 K = Mat3::Zero();
  // Each pull on the body f (minus the force on the cable below), arm r from Q.
  const auto pull = [&](const Vec3& f, const Vec3& r) { K += f.dot(r) * Mat3::Identity() - f * r.transpose(); };
  if (body.inline_body) pull(-lower_link_force, bw.rQ2 - bw.rQ);
  for (const BodyChild& ch : bw.children) pull(-(ch.K * ch.a + ch.b), ch.r - bw.rQ);  // f_0 = K a + b on the line
  return K;
}

void body_local_jacobian(const Fluid& fluid, const Body& body, const BodyWork& bw, double t, Mat6& C, Mat3& K,
                         const Mat3& lines) {
  // Analytic derivatives of the loads (body_load_derivatives).
  Mat6 D;
  Mat3 KO;
  body_load_derivatives(fluid, body, bw, t, D, KO);
  C = psd_part(D);
  // About Q: the loads' resultant F, carried by the arm O_t - Q, adds
  // -(F.rQ) I + F rQ^T (potential -F.x with x - Q = (x - O_t) - rQ).
  const Vec3& F = bw.Fb;
  K = psd_part(Mat3(KO - F.dot(bw.rQ) * Mat3::Identity() + F * bw.rQ.transpose() + lines));
}

void element_local_jacobian(const Model& model, const Element& el, const Vec3& e, const Vec3& vG, const Vec3& xG,
                            double t, const Vec3& F, const Vec3& f_bottom, Mat3& C, double& K, const Vec3* water) {
  // Rocking stiffness: with the joint forces held, turning e by dtheta moves
  // the bottom joint by L dtheta x e and G by half that; the loads there
  // (tension -f_bottom.e, own loads F.e along e) resist it.
  const double L = el.length;
  K = std::max(0.0, -L * f_bottom.dot(e) + 0.5 * L * F.dot(e));
  C.setZero();
  const Fluid& fluid = model.fluid;
  if (fluid.rho == 0) return;
  // Drag damping -dF/du (u: velocity relative to the water at G; in still
  // water the water's velocity is +0, u = vG, as element_loads; the water's
  // velocity as the loads took it when given: the same value, no second wave sum).
  const Vec3 u = !(fluid.has_current() || fluid.waves) ? vG
                 : water                               ? Vec3(vG - *water)
                                                       : Vec3(vG - fluid.velocity(xG, t));
  const double ue = u.dot(e);
  const Vec3 un = u - ue * e;
  C += drag_laws::normal_drag_damping(el.drag_factor, e, un);
  // Tangential friction: its e-e derivative (symmetric part along e).
  const double ct = drag_laws::tangential_friction_damping(model.cable.tangential_law, el.friction_factor, u, ue,
                                                           model.cable.sign_smoothing_speed);
  C += ct * e * e.transpose();
}

Mat3 attachment_local_damping(const Model& model, const Attachment& a, const Vec3& x, const Vec3& v, double t) {
  const Fluid& fluid = model.fluid;
  if (fluid.rho == 0) return Mat3::Zero();
  // Drag -1/2 rho CdA |u| u (attachment_loads).
  return drag_laws::point_drag_damping(0.5 * fluid.rho * a.drag_area, v - fluid.velocity(x, t));
}

// ---- A body's own seabed contact (its hull points) ------------------------
void body_contact_local_jacobian(const Seabed& sb, const Body& body, const BodyWork& bw, Mat6& C, Mat6& K) {
  C.setZero();
  K.setZero();
  hull_points(sb, body, bw, [&](const Vec3& p, double length) {
    const Vec3 r = p - bw.O;
    const Vec3 v = bw.vO + bw.w.cross(r);
    const SeabedForce f = sb.contact(p, v, length);
    if (f.length <= 0) return;
    Mat3 Cp = Mat3::Zero(), Kp = Mat3::Zero();
    sb.contact_slopes(p, v, f.length, f.total(), Cp, Kp);
    // The point moves with the body: dp = dx_O - [r]x dtheta.
    Eigen::Matrix<double, 3, 6> J;
    J << Mat3::Identity(), -skew(r);
    C.noalias() += J.transpose() * Cp * J;
    K.noalias() += J.transpose() * Kp * J;
  });
}
// ---- end of a body's own seabed contact -----------------------------------

void local_jacobian(const Model& model, const PhysicalState& s, const Workspace& ws, double t, LocalJacobian& jac) {
  const auto& els = model.cable.elements;
  for (std::size_t k = 0; k < els.size(); ++k) {
    const int bi = ws.body_at[k + 1];
    const Vec3& fb = bi >= 0 ? ws.acc.link_force[idx(bi)] : ws.acc.joint_force[k + 1];
    element_local_jacobian(model, current_element(model, ws, k), s.e[k], ws.vG[k], ws.G[k], t, ws.F[k], fb,
                           jac.element_damping[k], jac.element_stiffness[k], &ws.Uw[k]);
  }
  bending_local_stiffness(model, ws, jac.element_stiffness);  // the bending springs' own rotations
  for (auto& C : jac.joint_damping) C.setZero();
  for (const Attachment& a : model.cable.attachments) {
    const auto k = idx(a.joint);
    jac.joint_damping[k] += attachment_local_damping(model, a, ws.P[k], ws.vP[k], t);
  }
  // Seabed springs: at the joints, and at the bodies' link points Q (the end
  // body's contact at P_n, an in-line body's upper link).
  for (auto& K : jac.joint_stiffness) K.setZero();
  for (auto& C : jac.bodyq_damping) C.setZero();
  for (auto& K : jac.bodyq_stiffness) K.setZero();
  if (model.seabed) {
    const Seabed& sb = *model.seabed;
    const std::size_t n = els.size();
    for (std::size_t k = 0; k <= n; ++k) {
      const int bi = k > 0 ? ws.body_at[k] : -1;
      const bool end_body = bi >= 0 && !model.bodies[idx(bi)].inline_body;
      Mat3& C = end_body ? jac.bodyq_damping[idx(bi)] : jac.joint_damping[k];
      Mat3& K = end_body ? jac.bodyq_stiffness[idx(bi)] : jac.joint_stiffness[k];
      sb.contact_slopes(ws.P[k], ws.vP[k], ws.ls[k], ws.Fs[k], C, K);
      if (bi >= 0 && !end_body) {
        const BodyWork& bw = ws.body[idx(bi)];
        sb.contact_slopes(bw.Q, bw.vQ, bw.ls_q, bw.Fs_q, jac.bodyq_damping[idx(bi)], jac.bodyq_stiffness[idx(bi)]);
      }
    }
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    body_local_jacobian(model.fluid, model.bodies[b], ws.body[b], t, jac.body_damping[b], jac.body_stiffness[b],
                        model.sim.line_pull_stiffness
                            ? body_line_stiffness(model.bodies[b], ws.body[b], ws.acc.lower_link_force[b])
                            : Mat3::Zero());
  // The bodies' own seabed contact (hull points).
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.seabed) {
      body_contact_local_jacobian(*model.seabed, model.bodies[b], ws.body[b], jac.body_contact_damping[b],
                                  jac.body_contact_stiffness[b]);
    } else {
      jac.body_contact_damping[b].setZero();
      jac.body_contact_stiffness[b].setZero();
    }
  }
}

ImplicitWorkspace::ImplicitWorkspace(const Model& model) {
  const std::size_t n = model.cable.elements.size(), nb = model.bodies.size();
  body_children.assign(nb, {});  // a tree of lines sizes them (TreeImplicitWorkspace)
  jac.element_damping.assign(n, Mat3::Zero());
  jac.element_stiffness.assign(n, 0.0);
  jac.joint_damping.assign(n + 1, Mat3::Zero());
  jac.joint_stiffness.assign(n + 1, Mat3::Zero());
  jac.bodyq_damping.assign(nb, Mat3::Zero());
  jac.bodyq_stiffness.assign(nb, Mat3::Zero());
  jac.body_damping.assign(nb, Mat6::Zero());
  jac.body_stiffness.assign(nb, Mat3::Zero());
  jac.body_contact_damping.assign(nb, Mat6::Zero());
  jac.body_contact_stiffness.assign(nb, Mat6::Zero());
  F.assign(n, Vec3::Zero());
  Mom.assign(n, Vec3::Zero());
  Fa.assign(n + 1, Vec3::Zero());
  Fb.assign(nb, Vec3::Zero());
  Mb.assign(nb, Vec3::Zero());
  K.assign(n + 1, Mat3::Zero());
  b.assign(n + 1, Vec3::Zero());
  T.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  Phi.assign(n, Eigen::Matrix2d::Zero());
  H.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  TH.assign(n, Mat3::Zero());
  q.assign(n, Vec3::Zero());
  Tr0.assign(n, Eigen::Vector2d::Zero());
  bPhi.assign(nb, Mat3::Zero());
  bC.assign(nb, Mat3::Zero());
  bKQ.assign(nb, Mat3::Zero());
  brhs.assign(nb, Vec3::Zero());
  bbQ.assign(nb, Vec3::Zero());
  FQ.assign(nb, Vec3::Zero());
  Fd.assign(n, Vec3::Zero());
  EAinv.assign(n, Mat3::Zero());
  EG.assign(n, Mat3::Zero());
  Er.assign(n, Vec3::Zero());
  zl.assign(n, 0.0);
  dvP.assign(n + 1, Vec3::Zero());
  dxP.assign(n + 1, Vec3::Zero());
  alpha.assign(n, Vec3::Zero());
  alpha_b.assign(nb, Vec3::Zero());
  kappa.assign(n + 1, 0.0);
  for (auto* v : {&Qb, &Rb, &Sb}) v->assign(n + 1, Mat3::Zero());
  qb.assign(n + 1, Vec3::Zero());
  coupled.assign(n, 0);
  PG.assign(n, Eigen::Matrix<double, 2, 3>::Zero());
  PE.assign(n, Eigen::Matrix<double, 2, 3>::Zero());
  zr.assign(n, Eigen::Vector2d::Zero());
}

namespace {

using parts::BodyNode;
using parts::ElasticElement;
using parts::RigidElement;

/// implicit_factor's pass up the chain (sweep::up): the forward dynamics'
/// elimination at zero velocity with each part's modified inertia. kCoupled:
/// some bending spring couples two rigid elements (else that step is
/// compiled out of the rigid elements').
template <bool kCoupled>
struct FactorPass {
  const Model& model;
  const PhysicalState& s;
  const Workspace& ws;
  double hg;
  ImplicitWorkspace& iw;
  const LocalJacobian& jac = iw.jac;
  // Joint terms exist only with attachments or a seabed (else zero: skipped).
  const bool joints = !model.cable.attachments.empty() || model.seabed.has_value();
  const Mat3 zero = Mat3::Zero();
  // The arrays' data through local pointers (the stores into them leave the
  // vectors alone, which the compiler cannot tell).
  const Mat3 *Mts = ws.Mt.data(), *Cs = jac.element_damping.data();
  const double* Krs = jac.element_stiffness.data();
  const char* coupled = iw.coupled.data();  // per element (all 0 without bending springs)
  Mat3 *Ks = iw.K.data(), *THs = iw.TH.data();
  Eigen::Matrix<double, 3, 2>*Ts = iw.T.data(), *Hs = iw.H.data();
  Eigen::Matrix2d* Phis = iw.Phi.data();

  Mat3 joint_terms(std::size_t k) const {
    return joints ? Mat3(hg * jac.joint_damping[k] + hg * hg * jac.joint_stiffness[k]) : Mat3::Zero().eval();
  }
  /// The articulated inertia below element k: the body's at its bottom joint, or the joint's.
  const Mat3& below(std::size_t k, bool body) const {
    return body ? iw.bKQ[sweep::body_index(ws.body_at[k + 1])] : Ks[k + 1];
  }
  void end(std::size_t n) {
    iw.K[n] = ws.Ma[n] + joint_terms(n);
    if (ws.end_children) iw.K[n] += iw.end.K;  // the lines below a junction
  }
  void body(std::size_t b, std::size_t j) { BodyNode::factor(model.bodies[b], ws.body[b], jac, hg, Ks[j], b, iw); }
  void elastic(std::size_t k, bool body) {
    const Element& el = current_element(model, ws, k);
    ElasticElement::factor(el, s.e[k], s.length_of(model, k), ws.Mt[k], Mts[k] + hg * Cs[k], jac.element_damping[k],
                           jac.element_stiffness[k], hg, below(k, body), iw.EAinv[k], iw.EG[k], iw.K[k]);
    iw.K[k] += ws.Ma[k] + joint_terms(k);
  }
  void paid_out_elastic(std::size_t k, bool body) { elastic(k, body); }
  void rigid_element(const Element& el, std::size_t k, bool body) {
    const double L = el.length;
    const Mat3 Mt = Mts[k] + hg * Cs[k];
    const Mat3& Kk = below(k, body);
    if (kCoupled && coupled[k]) {
      // A bending spring couples its rotation to a neighbour's (a body's link
      // is a ball joint: no spring, no coupling below it).
      Ts[k] = ws.T[k];
      const parts::CoupledBelow cb{Kk, body ? zero : iw.Qb[k + 1], body ? zero : iw.Rb[k + 1],
                                   body ? zero : iw.Sb[k + 1]};
      parts::coupled_element_factor(ws.T[k], L, Mt, element_rot_inertia(el) + hg * hg * Krs[k], cb, iw.kappa[k + 1],
                                    iw.kappa[k], hg, k, iw);
    } else {
      const auto& T = Ts[k] = ws.T[k];  // tangent_basis(s.e[k]): the evaluation at s computed it
      RigidElement::factor(T, L, Mt, element_rot_inertia(el) + hg * hg * Krs[k], Kk, Phis[k], Hs[k], THs[k], Ks[k]);
    }
    // Ma (+0 without joint terms) and the joint terms only with attachments or a seabed.
    if (joints) Ks[k] += ws.Ma[k], Ks[k] += joint_terms(k);
  }
  void rigid(std::size_t k, bool body) { rigid_element(model.cable.elements[k], k, body); }
  void paid_out(std::size_t k, bool body) { rigid_element(ws.top, k, body); }  // the winch's top at its current length
  void joint(std::size_t) {}
};

}  // namespace

void implicit_factor(const Model& model, const PhysicalState& s, const Workspace& ws, double hg,
                     ImplicitWorkspace& iw) {
  // Bending springs between rigid elements: those elements' rotations are
  // eliminated together with their neighbours' (coupled_element_factor).
  if (ws.bending) parts::couple_bending_springs(model, ws, iw);
  if (iw.any_coupled) {
    FactorPass<true> pass{model, s, ws, hg, iw};
    sweep::up(model, ws, pass);
  } else {
    FactorPass<false> pass{model, s, ws, hg, iw};
    sweep::up(model, ws, pass);
  }
  iw.hg = hg;
}

namespace {

// The three passes of a stage solve, as separate functions: each small enough
// for the compiler to inline its 3x3 algebra (one large function was not).

/// The right-hand side as loads on the parts, down the chain (sweep::down):
/// -hg C dv at each damper (dv: the velocity increments r_v carried down the
/// chain), -hg K (hg dw + rot) on rotations, -hg K (hg dv + dx) on joint
/// springs (dx: the joints' displacements).
struct LoadPass {
  const Model& model;
  const PhysicalState& s;
  const Workspace& ws;
  double hg;
  const StageRhs& r;
  ImplicitWorkspace& iw;
  const LocalJacobian& jac = iw.jac;
  const bool free_top = model.tow.mode != Tow::Mode::Motion;
  // The joints' increments are read only by the joint terms.
  const bool joints = !model.cable.attachments.empty() || model.seabed.has_value();
  // The arrays' data through local pointers (as FactorPass).
  const Vec3 *es = s.e.data(), *rdw = r.dw.data(), *rrot = r.rot.data();
  const Mat3* Cs = jac.element_damping.data();
  const double* Kr = jac.element_stiffness.data();
  Vec3 *Fs = iw.F.data(), *Moms = iw.Mom.data();
  Vec3 dv = Vec3::Zero(), dx = Vec3::Zero();  // increments of the current joint [m/s], [m]

  void top() {
    const std::size_t n = model.cable.elements.size();
    // Tension-controlled winch, tow point held: the pay-out is a prismatic
    // joint at the top (its increments move the top material along e_1).
    const bool drum = model.winch.mode == Winch::Mode::Tension && !free_top && n > 0 && !elastic_winch(model);
    dv = free_top ? r.dv0 : Vec3::Zero();
    dx = free_top ? r.dx0 : Vec3::Zero();
    if (iw.top_given) dv = iw.top_dv, dx = iw.top_dx;  // a line hanging from a node
    if (drum) dv += r.winch_dlr * s.e[0], dx += r.winch_dl * s.e[0];
    iw.drum = drum;
    iw.drum_rhs = drum ? -hg * model.winch.damping * r.winch_dlr : 0.0;
    iw.dvP[0] = dv;
    iw.dxP[0] = dx;
  }
  void rigid_element(std::size_t k, double L) {
    RigidElement::load(es[k], L, rdw[k], rrot[k], Cs[k], Kr[k], hg, dv, dx, Fs[k], Moms[k]);
  }
  void rigid(std::size_t k) { rigid_element(k, model.cable.elements[k].length); }
  void paid_out(std::size_t k) { rigid_element(k, ws.top.length); }  // the winch's top at its current length
  void elastic(std::size_t k) {
    const double dl = k < r.dl.size() ? r.dl[k] : 0.0, dlr = k < r.dlr.size() ? r.dlr[k] : 0.0;
    const double pL = k == 0 ? r.top_dL : 0.0, pLr = k == 0 ? r.top_dLr : 0.0;  // the winch's paid-out part
    ElasticElement::load(current_element(model, ws, k), es[k], s.length_of(model, k), rdw[k], rrot[k], dl, dlr, pL, pLr,
                         jac.element_damping[k], jac.element_stiffness[k], hg, dv, dx, iw.F[k], iw.Mom[k], iw.Fd[k]);
  }
  void paid_out_elastic(std::size_t k) { elastic(k); }
  void body(std::size_t b, std::size_t j) {
    BodyNode::load(model.bodies[b], ws.body[b], jac, hg, r.dwb[b], r.rotb[b], b, dv, dx, iw);
    joint(j);
  }
  void joint(std::size_t j) {
    if (joints) iw.dvP[j] = dv, iw.dxP[j] = dx;
  }
  /// After the pass: the coupled bending springs' off-diagonal terms, and the
  /// joint terms (only with attachments or a seabed; else Fa stays +0, as
  /// constructed, and the bias pass skips it).
  void finish() {
    if (iw.any_coupled) parts::coupled_spring_loads(s, hg, r, iw);
    if (joints)
      for (std::size_t k = 0; k < iw.Fa.size(); ++k)
        iw.Fa[k] = -hg * (jac.joint_damping[k] * iw.dvP[k]) -
                   hg * (jac.joint_stiffness[k] * (hg * iw.dvP[k] + iw.dxP[k]));
  }
};

/// Bias pass up the chain (sweep::up; the inertias are factorised). Without
/// joint terms Fa is +0 and x - 0 = x: not subtracted.
template <bool kCoupled>
struct BiasPass {
  const Model& model;
  const PhysicalState& s;
  const Workspace& ws;
  ImplicitWorkspace& iw;
  const bool joints = !model.cable.attachments.empty() || model.seabed.has_value();
  // The arrays' data through local pointers (as FactorPass).
  const Vec3 *es = s.e.data(), *Fs = iw.F.data(), *Moms = iw.Mom.data();
  const Eigen::Matrix<double, 3, 2>*Ts = iw.T.data(), *Hs = iw.H.data();
  const Eigen::Matrix2d* Phis = iw.Phi.data();
  const Mat3* THs = iw.TH.data();
  Vec3 *bs = iw.b.data(), *qs = iw.q.data();
  Eigen::Vector2d* Tr0s = iw.Tr0.data();
  const char* coupled = iw.coupled.data();

  /// The bias below element k: the body's at its bottom joint, or the joint's.
  const Vec3& below(std::size_t k, bool body) const {
    return body ? iw.bbQ[sweep::body_index(ws.body_at[k + 1])] : bs[k + 1];
  }
  const Vec3* Fa(std::size_t k) const { return joints ? &iw.Fa[k] : nullptr; }
  void end(std::size_t n) {
    iw.b[n] = -iw.Fa[n];
    if (ws.end_children) iw.b[n] += iw.end.b;  // the lines below a junction
  }
  void body(std::size_t b, std::size_t j) { BodyNode::stage_bias(model.bodies[b], ws.body[b], bs[j], b, iw); }
  void elastic(std::size_t k, bool body) {
    ElasticElement::stage_bias(iw.EAinv[k], iw.EG[k], iw.F[k], iw.Fd[k], below(k, body), Fa(k), iw.Er[k], iw.b[k]);
  }
  void paid_out_elastic(std::size_t k, bool body) { elastic(k, body); }
  void rigid_element(std::size_t k, double L, bool body) {
    if (kCoupled && coupled[k])  // coupled by a bending spring (out of line: the common step stays lean)
      parts::coupled_element_bias(k, L, body, below(k, body), joints, iw);
    else
      RigidElement::stage_bias(es[k], L, Fs[k], Moms[k], Ts[k], Hs[k], Phis[k], THs[k], below(k, body), Fa(k), bs[k],
                               Tr0s[k], qs[k]);
  }
  void rigid(std::size_t k, bool body) { rigid_element(k, model.cable.elements[k].length, body); }
  void paid_out(std::size_t k, bool body) { rigid_element(k, ws.top.length, body); }
  void joint(std::size_t) {}
};

/// Increments z down the chain (sweep::down): the tow point held (Motion) or
/// free with no force, the drum's pay-out, then each part's.
template <bool kCoupled>
struct IncrementPass {
  const Model& model;
  const PhysicalState& s;
  const Workspace& ws;
  ImplicitWorkspace& iw;
  // The arrays' data through local pointers (as FactorPass).
  const Vec3 *es = s.e.data(), *qs = iw.q.data();
  const Mat3* THs = iw.TH.data();
  Vec3* alphas = iw.alpha.data();
  double* zls = iw.zl.data();
  const char* coupled = iw.coupled.data();
  Vec3 a = Vec3::Zero();  // increment of the current joint's velocity [m/s]

  void top() {
    const bool free_top = model.tow.mode != Tow::Mode::Motion;
    a = free_top ? Vec3(iw.K[0].ldlt().solve(-iw.b[0])) : Vec3::Zero();
    if (iw.top_given) a = iw.top_a;  // a line hanging from a node
    iw.a0 = a;
    // The drum: (M_d + hg c) z_l = -hg c r_l' + dT, dT = -e_1.(K_0 z_l e_1 + b_0)
    // (the tension's response to the top's acceleration z_l e_1, as in fast.cpp).
    iw.z_winch = 0;
    if (iw.drum) {
      const Winch& w = model.winch;
      const Vec3& e1 = s.e[0];
      iw.z_winch = (iw.drum_rhs - e1.dot(iw.b[0])) / (w.drum_inertia + iw.hg * w.damping + e1.dot(iw.K[0] * e1));
      a = iw.z_winch * e1;
    }
  }
  void elastic(std::size_t k) {
    ElasticElement::stage_accelerate(iw.EAinv[k], iw.EG[k], iw.Er[k], s.e[k], s.length_of(model, k), a, iw.alpha[k],
                                     iw.zl[k]);
  }
  void paid_out_elastic(std::size_t k) { elastic(k); }
  void rigid_element(std::size_t k, double L) {
    zls[k] = 0;
    if (kCoupled && coupled[k])  // coupled by a bending spring (out of line)
      a += parts::coupled_element_acceleration(k, L, a, iw);
    else
      RigidElement::stage_accelerate(qs[k], THs[k], es[k], L, a, alphas[k]);
  }
  void rigid(std::size_t k) { rigid_element(k, model.cable.elements[k].length); }
  void paid_out(std::size_t k) { rigid_element(k, ws.top.length); }
  void body(std::size_t b, std::size_t) { BodyNode::stage_accelerate(model.bodies[b], ws.body[b], b, a, iw); }
  void joint(std::size_t) {}
};

/// The right-hand side's pass.
[[gnu::noinline, gnu::flatten]] void stage_loads(const Model& model, const PhysicalState& s, const Workspace& ws,
                                                 double hg, const StageRhs& r, ImplicitWorkspace& iw) {
  LoadPass loads{model, s, ws, hg, r, iw};
  sweep::down(model, ws, loads);
  loads.finish();
  iw.end.dv = loads.dv, iw.end.dx = loads.dx;  // the cable end's (a junction's)
}

/// The bias pass, kCoupled as FactorPass.
template <bool kCoupled>
[[gnu::noinline, gnu::flatten]] void stage_bias(const Model& model, const PhysicalState& s, const Workspace& ws,
                                                ImplicitWorkspace& iw) {
  BiasPass<kCoupled> bias{model, s, ws, iw};
  sweep::up(model, ws, bias);
}

/// The increments' pass, kCoupled as FactorPass.
template <bool kCoupled>
[[gnu::noinline, gnu::flatten]] void stage_increments(const Model& model, const PhysicalState& s, const Workspace& ws,
                                                      ImplicitWorkspace& iw) {
  IncrementPass<kCoupled> increments{model, s, ws, iw};
  sweep::down(model, ws, increments);
  iw.end.a = increments.a;  // the cable end's (a junction's)
}

}  // namespace

void stage::loads(const Model& model, const PhysicalState& s, const Workspace& ws, double hg, const StageRhs& r,
                  ImplicitWorkspace& iw) {
  stage_loads(model, s, ws, hg, r, iw);
}

void stage::bias(const Model& model, const PhysicalState& s, const Workspace& ws, ImplicitWorkspace& iw) {
  if (iw.any_coupled)
    stage_bias<true>(model, s, ws, iw);
  else
    stage_bias<false>(model, s, ws, iw);
}

void stage::increments(const Model& model, const PhysicalState& s, const Workspace& ws, ImplicitWorkspace& iw) {
  if (iw.any_coupled)
    stage_increments<true>(model, s, ws, iw);
  else
    stage_increments<false>(model, s, ws, iw);
}

void implicit_stage_solve(const Model& model, const PhysicalState& s, const Workspace& ws, double hg, const StageRhs& r,
                          ImplicitWorkspace& iw) {
  if (iw.hg != hg) implicit_factor(model, s, ws, hg, iw);
  stage_loads(model, s, ws, hg, r, iw);
  if (iw.any_coupled) {
    stage_bias<true>(model, s, ws, iw);
    stage_increments<true>(model, s, ws, iw);
  } else {
    stage_bias<false>(model, s, ws, iw);
    stage_increments<false>(model, s, ws, iw);
  }
}

}  // namespace towsim
