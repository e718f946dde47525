// Part: a rigid body hanging from a joint of the chain by a ball joint at
// its link point Q (docs/theory.md §5.3): the end body, or an in-line body
// from whose lower link Q2 the next element hangs. Its coordinates are its
// attitude and angular velocity; its step of the recursion takes in the
// articulated cable below Q2 (in-line body) and eliminates its rotation,
// leaving the link force affine in the acceleration of Q.
//
// Forward dynamics: articulate (up), accelerate (down). Stage solve
// (inertia M + hg C + hg^2 K, zero velocity): factor, load, bias, accelerate.
#pragma once

#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/state.hpp"

namespace towsim::parts {

struct BodyNode {
  /// Forward dynamics, up: the body's (KQ, bQ) for the link force F_L = KQ a_Q
  /// + bQ, after eliminating its angular acceleration. An in-line body first
  /// takes in the articulated cable below it, (K2, b2) seen at its lower link
  /// Q2: with a_Q2 = J2 [a_O; alpha] + c2, J2 = [I, -[r2]x], the cable below
  /// adds J2^T K2 J2 to its inertia and J2^T (K2 c2 + b2) to its bias.
  static void articulate(const Body& body, BodyWork& bw, const Mat3& K2, const Vec3& b2) {
    bw.Me = bw.Mw;
    bw.he = bw.hw;
    if (body.inline_body) {
      Eigen::Matrix<double, 6, 3> J2t;
      J2t << Mat3::Identity(), skew(bw.rQ2);
      const Vec3 c2 = bw.w.cross(bw.w.cross(bw.rQ2));
      bw.Me += J2t * K2 * J2t.transpose();
      bw.he += J2t * (K2 * c2 + b2);
    }
    // Lines hanging from its points (a tree of lines) enter as the cable below Q2.
    for (const BodyChild& ch : bw.children) {
      Eigen::Matrix<double, 6, 3> Jt;
      Jt << Mat3::Identity(), skew(ch.r);
      const Vec3 c = bw.w.cross(bw.w.cross(ch.r));
      bw.Me += Jt * ch.K * Jt.transpose();
      bw.he += Jt * (ch.K * c + ch.b);
    }
    const Vec3 r = bw.rQ;  // Q - O_t [m, R_g]
    const Mat3 Rx = skew(r);
    const Mat3 Mll = bw.Me.topLeftCorner<3, 3>(), Mla = bw.Me.topRightCorner<3, 3>();
    const Mat3 Mal = bw.Me.bottomLeftCorner<3, 3>(), Maa = bw.Me.bottomRightCorner<3, 3>();
    const Vec3 hl = bw.he.head<3>(), ha = bw.he.tail<3>();
    // a_O = a_Q + [r]x alpha + w, with w the centripetal part.
    bw.wcent = bw.w.cross(bw.w.cross(-r));
    bw.C = Mal - Rx * Mll;
    const Mat3 D = bw.C * Rx + Maa - Rx * Mla;  // inertia about Q
    bw.Phi = D.inverse();
    bw.rhs = bw.Mb - r.cross(bw.Fb) - ha + r.cross(hl);
    bw.KQ = Mll - bw.C.transpose() * bw.Phi * bw.C;
    bw.bQ = Mll * bw.wcent + bw.C.transpose() * bw.Phi * (bw.rhs - bw.C * bw.wcent) + hl - bw.Fb;
  }

  /// Forward dynamics, down: from the acceleration a of its link point Q, its
  /// angular acceleration, link force and, for an in-line body, the
  /// acceleration of its lower link Q2 (returned in a) and the force there.
  static void accelerate(const Body& body, BodyWork& bw, const Mat3& K2, const Vec3& b2, std::size_t b, Vec3& a,
                         Accelerations& acc) {
    acc.alpha_b[b] = bw.Phi * (bw.rhs - bw.C * (a + bw.wcent));
    acc.link_force[b] = bw.KQ * a + bw.bQ;
    acc.lower_link_force[b].setZero();
    if (!body.inline_body && bw.children.empty()) return;
    const Vec3& al = acc.alpha_b[b];
    const Vec3 aO = a + bw.rQ.cross(al) + bw.wcent;
    // The points the lines below it hang from (a tree of lines).
    for (BodyChild& ch : bw.children) ch.a = aO + al.cross(ch.r) + bw.w.cross(bw.w.cross(ch.r));
    if (!body.inline_body) return;
    a = aO + al.cross(bw.rQ2) + bw.w.cross(bw.w.cross(bw.rQ2));
    acc.lower_link_force[b] = K2 * a + b2;
  }

  /// Stage solve, factor: the modified inertia Me = Mw + hg C + hg^2 K (its
  /// loads' damping and rotational stiffness, its own seabed contact); an
  /// in-line body first takes in the cable below, K2 at its lower link Q2;
  /// then the elimination about Q, and the seabed's terms at Q on KQ.
  static void factor(const Body& body, const BodyWork& bw, const LocalJacobian& jac, double hg, const Mat3& K2,
                     std::size_t b, ImplicitWorkspace& iw) {
    Mat6 Me = bw.Mw + hg * jac.body_damping[b];
    Me.bottomRightCorner<3, 3>() += hg * hg * jac.body_stiffness[b];
    Me += hg * jac.body_contact_damping[b] + hg * hg * jac.body_contact_stiffness[b];  // its own seabed contact
    if (body.inline_body) {
      Eigen::Matrix<double, 6, 3> J2t;
      J2t << Mat3::Identity(), skew(bw.rQ2);
      Me += J2t * K2 * J2t.transpose();
    }
    // Lines hanging from its points (a tree of lines) enter as the cable below Q2.
    for (std::size_t c = 0; c < bw.children.size(); ++c) {
      Eigen::Matrix<double, 6, 3> Jt;
      Jt << Mat3::Identity(), skew(bw.children[c].r);
      Me += Jt * iw.body_children[b][c].K * Jt.transpose();
    }
    const Mat3 Rx = skew(bw.rQ);  // rQ = Q - O_t [m, R_g]
    const Mat3 Mll = Me.topLeftCorner<3, 3>(), Mla = Me.topRightCorner<3, 3>();
    const Mat3 Mal = Me.bottomLeftCorner<3, 3>(), Maa = Me.bottomRightCorner<3, 3>();
    iw.bC[b] = Mal - Rx * Mll;
    iw.bPhi[b] = (iw.bC[b] * Rx + Maa - Rx * Mla).inverse();  // inertia about Q
    iw.bKQ[b] = Mll - iw.bC[b].transpose() * iw.bPhi[b] * iw.bC[b];
    iw.bKQ[b] += hg * jac.bodyq_damping[b] + hg * hg * jac.bodyq_stiffness[b];  // seabed at Q
  }

  /// Stage solve, right-hand side as loads: from the increments (dv, dx) of
  /// Q and the body's own (dwb, rotb), -hg C dnu - hg K (hg dnu + dxi) on the
  /// body (loads and its own seabed contact), the seabed's at Q (FQ); for an
  /// in-line body, (dv, dx) carried to its lower link Q2.
  static void load(const Body& body, const BodyWork& bw, const LocalJacobian& jac, double hg, const Vec3& dwb,
                   const Vec3& rotb, std::size_t b, Vec3& dv, Vec3& dx, ImplicitWorkspace& iw) {
    const Vec3 dvO = dv - dwb.cross(bw.rQ);  // v_O = v_Q + omega x (O - Q)
    const Vec3 dxO = dx - rotb.cross(bw.rQ);
    Vec6 dnu, dxi;
    dnu << dvO, dwb;
    dxi << dxO, rotb;
    Vec6 g = -hg * (jac.body_damping[b] * dnu);
    // Its own seabed contact: -hg C_c dnu - hg K_c (hg dnu + dxi).
    g -= hg * (jac.body_contact_damping[b] * dnu) + hg * (jac.body_contact_stiffness[b] * (hg * dnu + dxi));
    iw.Fb[b] = g.head<3>();
    iw.Mb[b] = g.tail<3>() - hg * (jac.body_stiffness[b] * (hg * dwb + rotb));
    // Seabed at Q (a force there, on the articulated body at Q: see the bias step).
    iw.FQ[b] = -hg * (jac.bodyq_damping[b] * dv) - hg * (jac.bodyq_stiffness[b] * (hg * dv + dx));
    // The points the lines below it hang from.
    for (std::size_t c = 0; c < bw.children.size(); ++c) {
      iw.body_children[b][c].dv = dvO + dwb.cross(bw.children[c].r);
      iw.body_children[b][c].dx = dxO + rotb.cross(bw.children[c].r);
    }
    if (body.inline_body) {
      dv = dvO + dwb.cross(bw.rQ2);
      dx = dxO + rotb.cross(bw.rQ2);
    }
  }

  /// Stage solve, bias: the loads (Fb, Mb about O_t), the cable below's bias
  /// b2 at Q2 (in-line body) and the seabed's force at Q.
  static void stage_bias(const Body& body, const BodyWork& bw, const Vec3& b2, std::size_t b, ImplicitWorkspace& iw) {
    Vec3 hl = Vec3::Zero(), ha = Vec3::Zero();
    if (body.inline_body) hl = b2, ha = bw.rQ2.cross(b2);   // J2^T b2
    for (std::size_t c = 0; c < bw.children.size(); ++c) {  // the lines below its points, likewise
      const Vec3& bc = iw.body_children[b][c].b;
      hl += bc, ha += bw.children[c].r.cross(bc);
    }
    const Vec3& r = bw.rQ;
    iw.brhs[b] = iw.Mb[b] - r.cross(iw.Fb[b]) - ha + r.cross(hl);
    iw.bbQ[b] = iw.bC[b].transpose() * iw.bPhi[b] * iw.brhs[b] + hl - iw.Fb[b];
    iw.bbQ[b] -= iw.FQ[b];
  }

  /// Stage solve, increments: the body's rotation from Q's increment a, and
  /// for an in-line body a moved to its lower link Q2.
  static void stage_accelerate(const Body& body, const BodyWork& bw, std::size_t b, Vec3& a, ImplicitWorkspace& iw) {
    const Vec3 al = iw.bPhi[b] * (iw.brhs[b] - iw.bC[b] * a);
    iw.alpha_b[b] = al;
    for (std::size_t c = 0; c < bw.children.size(); ++c)  // the points the lines below it hang from
      iw.body_children[b][c].a = a + bw.rQ.cross(al) + al.cross(bw.children[c].r);
    if (body.inline_body) a = a + bw.rQ.cross(al) + al.cross(bw.rQ2);
  }
};

}  // namespace towsim::parts
