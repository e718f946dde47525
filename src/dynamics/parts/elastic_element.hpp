// Part: the elastic element (docs/theory.md §5.4), a straight rod from its
// top joint to P_k = P_{k-1} + d_k, d_k = l e, whose three coordinates
// relative to its top joint are d_k itself (direction and stretch). Its
// forward-dynamics steps are elastic_backward and elastic_forward
// (towsim/dynamics/elastic.hpp); this file holds its steps of the
// Rosenbrock stage solve (docs/theory.md §6.3), on the increment of d_k'.
#pragma once

#include "towsim/dynamics/elastic.hpp"
#include "towsim/dynamics/state.hpp"

namespace towsim::parts {

struct ElasticElement {
  /// Stage solve, factor: A = Mdd + Kk + S, S = (hg c_a + hg^2 EA/L) e e^T +
  /// hg^2 K_rock / l^2 (I - e e^T) (the spring's axial and geometric
  /// stiffness in d). The drag acts at G, whose velocity is v + d'/2: its
  /// damping on (v, d') is C [1, 1/2; 1/2, 1/4], not the rod mass's [1, 1/2;
  /// 1/2, 1/3], so the d-d block is Mdd = M_t/3 + hg C/4, the same C as the
  /// right-hand side's load -hg C (dv + ddv/2) (else the solve is not
  /// (I - hg W)^-1 for one W). K = Mdd + S - N A^-1 N, N = Mt'/2 - Mdd - S
  /// (= Mt' + Kk - G A^-1 G, G = Mt'/2 + Kk, without the difference of large
  /// terms when Kk >> Mt). el: the element as the dynamics use it (the
  /// winch's: unstretched L_1); Mt: its inertia [kg]; Mtp = Mt + hg C.
  [[gnu::always_inline]] static void factor(const Element& el, const Vec3& e, double l, const Mat3& Mt, const Mat3& Mtp,
                                            const Mat3& C, double Kr, double hg, const Mat3& Kk, Mat3& Ainv, Mat3& G,
                                            Mat3& K) {
    const Mat3 ee = e * e.transpose();
    const Mat3 S = (hg * element_axial_damping_rate(el, l) + hg * hg * element_axial_stiffness(el, l)) * ee +
                   hg * hg * Kr / (l * l) * (Mat3::Identity() - ee);
    const Mat3 Mdd = Mt / 3 + 0.25 * hg * C;
    Ainv = (Mdd + Kk + S).inverse();
    G = 0.5 * Mtp + Kk;
    const Mat3 N = 0.5 * Mtp - Mdd - S;
    const Mat3 Kn = Mdd + S - N * Ainv * N;
    K = 0.5 * (Kn + Kn.transpose());
  }

  /// Stage solve, right-hand side as loads: the increments of d' and d (the
  /// stretch's along e, the rotation's normal to it), the drag's -hg C at G,
  /// and Fd, the spring's and axial damper's force on d; dv, dx carried to
  /// the bottom joint. pL, pLr: the winch's paid-out increments of L_1, L_1'
  /// (times l_1/L_1) over an elastic top element, else 0.
  [[gnu::always_inline]] static void load(const Element& el, const Vec3& e, double l, const Vec3& rdw, const Vec3& rrot,
                                          double dl, double dlr, double pL, double pLr, const Mat3& C, double Kr,
                                          double hg, Vec3& dv, Vec3& dx, Vec3& F, Vec3& Mom, Vec3& Fd) {
    const Vec3 dw = rdw - rdw.dot(e) * e;
    const Vec3 rot = rrot - rrot.dot(e) * e;
    const Vec3 de = dw.cross(e);
    const Vec3 ddv = dlr * e + l * de, ddx = dl * e + l * rot.cross(e);
    const double ka = element_axial_stiffness(el, l), ca = element_axial_damping_rate(el, l);
    const double kr = Kr / (l * l);
    F = -hg * (C * (dv + 0.5 * ddv));
    Mom.setZero();
    Fd = -hg * (ca * (e.dot(ddv) - pLr) + ka * (hg * e.dot(ddv) + e.dot(ddx) - pL)) * e -
         hg * kr * (hg * l * de + l * rot.cross(e));
    dv += ddv;
    dx += ddx;
  }

  /// Stage solve, bias: the d-equation's right side r = F/2 + Fd - b_below
  /// and b = G A^-1 r + b_below - F (- Fa; nullptr for none).
  [[gnu::always_inline]] static void stage_bias(const Mat3& Ainv, const Mat3& G, const Vec3& F, const Vec3& Fd,
                                                const Vec3& bk, const Vec3* Fa, Vec3& r, Vec3& b) {
    r = 0.5 * F + Fd - bk;
    b = G * (Ainv * r) + bk - F;
    if (Fa) b -= *Fa;
  }

  /// Stage solve, increments: z_d = A^-1 (r - G a), its part along e the
  /// increment of l', normal to it l (alpha x e); a moved to the bottom joint.
  [[gnu::always_inline]] static void stage_accelerate(const Mat3& Ainv, const Mat3& G, const Vec3& r, const Vec3& e,
                                                      double l, Vec3& a, Vec3& alpha, double& zl) {
    const Vec3 zd = Ainv * (r - G * a);
    zl = e.dot(zd);
    alpha = e.cross(zd) / l;
    a += zd;
  }
};

}  // namespace towsim::parts
