// Part: the rigid element (docs/theory.md §5.2), an inextensible straight
// element of length L hanging from a ball joint at its top. Its coordinates
// are its direction e and angular velocity omega (normal to e); its step of
// the recursion eliminates the rotation in the plane normal to e, in the
// tangent basis T = [t1 t2] where its own inertia is isotropic.
//
// Forward dynamics: inertia (depends on directions and lengths only), bias
// (loads and velocities), accelerate. Stage solve (inertia M + hg C + hg^2 K,
// zero velocity): factor, load, bias, accelerate.
#pragma once

#include "towsim/dynamics/state.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim::parts {

using Mat32 = Eigen::Matrix<double, 3, 2>;

/// The forward dynamics' per-element arrays of a Workspace, as pointers taken
/// once per pass: the compiler cannot tell that the stores into them leave
/// the vectors alone, and would reload each one's start per element.
struct ElementArrays {
  explicit ElementArrays(Workspace& ws)
      : L(ws.L.data()),
        F(ws.F.data()),
        Mom(ws.Mom.data()),
        T(ws.T.data()),
        GT(ws.GT.data()),
        Phi(ws.Phi.data()),
        H(ws.H.data()),
        K(ws.K.data()),
        b(ws.b.data()),
        c(ws.c.data()),
        Tr0(ws.Tr0.data()) {}
  const double* L;
  const Vec3 *F, *Mom;
  Mat32 *T, *GT;
  Eigen::Matrix2d* Phi;
  Mat32* H;
  Mat3* K;
  Vec3 *b, *c;
  Eigen::Vector2d* Tr0;
};

struct RigidElement {
  /// Forward dynamics, inertia part: the articulated inertia K_{k-1} seen at
  /// the top joint of element k from Kk at its bottom joint, and what the
  /// bias step and the forward step read (T, G T, Phi, H). The rotation
  /// equation lives in the plane normal to e_k: in the tangent basis T the
  /// element's own inertia is isotropic (T^T Mt T = (m + ma) I, Mt e = m e).
  /// kSymmetric: Kk is exactly symmetric (an element's K below, mirrored), so
  /// its symmetric part is Kk itself (0.5 (a + a) = a in floating point).
  template <bool kSymmetric>
  [[gnu::always_inline]] static void inertia(const Element& el, const Vec3& e, const Mat3& Kk, std::size_t k,
                                             const ElementArrays& ws) {
    const double L = ws.L[k], m = el.mass, ma = el.added_mass, mn = m + ma;
    // Tangent basis normal to e.
    ws.T[k] = tangent_basis(e);
    const Vec3 t1 = ws.T[k].col(0), t2 = ws.T[k].col(1);
    // K T (K symmetric), G T = L (mn/2 T + K T), and the 2x2 rotational block
    // D = T^T (L^2/4 Mt + L^2 K) T + Ir (symmetric), inverted in closed form.
    const Vec3 u1 = Kk * t1, u2 = Kk * t2;
    const Vec3 g1 = L * (0.5 * mn * t1 + u1), g2 = L * (0.5 * mn * t2 + u2);
    ws.GT[k].col(0) = g1;
    ws.GT[k].col(1) = g2;
    const double L2 = L * L, dd = 0.25 * L2 * mn + element_rot_inertia(el);
    const double d11 = L2 * t1.dot(u1) + dd, d22 = L2 * t2.dot(u2) + dd, d12 = L2 * t1.dot(u2);
    // H = G T Phi, Phi = adj(D) / det D; the force through the top joint is
    // affine in its acceleration: K_{k-1} = K - H (G T)^T + mn I - ma e e^T
    // (symmetric: the upper triangle, mirrored). The products with adj(D) run
    // while the division does (the recursion's critical path is K_k -> K_{k-1}).
    const double det = d11 * d22 - d12 * d12;
    const Vec3 a1 = d22 * g1 - d12 * g2, a2 = d11 * g2 - d12 * g1;  // G T adj(D)
    Mat3 S;                                                         // G T adj(D) (G T)^T
    for (int r = 0; r < 3; ++r)
      for (int q = r; q < 3; ++q) S(r, q) = a1[r] * g1[q] + a2[r] * g2[q];
    const double idet = 1.0 / det;
    const double p11 = d22 * idet, p22 = d11 * idet, p12 = -d12 * idet;
    ws.Phi[k](0, 0) = p11;
    ws.Phi[k](0, 1) = ws.Phi[k](1, 0) = p12;
    ws.Phi[k](1, 1) = p22;
    ws.H[k].col(0) = idet * a1;
    ws.H[k].col(1) = idet * a2;
    Mat3& K = ws.K[k];
    for (int r = 0; r < 3; ++r)
      for (int q = r; q < 3; ++q) {
        const double ks = kSymmetric ? Kk(r, q) : 0.5 * (Kk(r, q) + Kk(q, r));
        K(r, q) = K(q, r) = (ks - ma * e[r] * e[q] + (r == q ? mn : 0.0)) - idet * S(r, q);
      }
  }

  /// Forward dynamics, bias part: b_{k-1} at the top joint of element k from
  /// (Kk, bk) at its bottom joint and the element's loads, with the inertia
  /// part's T and H.
  [[gnu::always_inline]] static void bias(const Element& el, const Vec3& e, const Vec3& w, const Mat3& Kk,
                                          const Vec3& bk, std::size_t k, const ElementArrays& ws) {
    const double L = ws.L[k], m = el.mass;
    const Vec3 t1 = ws.T[k].col(0), t2 = ws.T[k].col(1);
    const Vec3 c = -w.squaredNorm() * e;  // Mt c = m c
    ws.c[k] = c;
    // [T^T (L^2/4 Mt + L^2 K) T + Ir] z = T^T r0 - (G T)^T a_top, beta = T z.
    const Vec3 Kc = Kk * c;
    const Vec3 r0 = 0.5 * L * (ws.F[k] - 0.5 * L * m * c) - L * (L * Kc + bk) - e.cross(ws.Mom[k]);
    const double z1 = t1.dot(r0), z2 = t2.dot(r0);
    ws.Tr0[k] = Eigen::Vector2d(z1, z2);
    ws.b[k] = z1 * ws.H[k].col(0) + z2 * ws.H[k].col(1) + 0.5 * L * m * c + L * Kc + bk - ws.F[k];
  }

  /// Forward dynamics, forward step: from the top joint's acceleration a, the
  /// angular acceleration alpha (normal to e) and a moved to the bottom joint.
  [[gnu::always_inline]] static void accelerate(const Mat32& T, const Eigen::Matrix2d& Phi, const Eigen::Vector2d& Tr0,
                                                const Mat32& GT, const Vec3& c, const Vec3& e, double L, Vec3& a,
                                                Vec3& alpha) {
    const Vec3 beta = T * (Phi * (Tr0 - GT.transpose() * a));  // alpha x e
    alpha = e.cross(beta);
    a += L * (beta + c);
  }

  /// Stage solve, factor: with the modified inertia Mt' = Mt + hg C [kg] and
  /// rotational inertia dd = Ir + hg^2 K_rock [kg m^2], G T = L (Mt'/2 + K) T
  /// and D = T^T (L^2/4 Mt' + L^2 K) T + dd (Mt' and K symmetric: D symmetric,
  /// inverted in closed form); then Phi, H = G T Phi, T H^T and the
  /// articulated K = Mt' + K_below - H (G T)^T (the upper triangle, mirrored).
  [[gnu::always_inline]] static void factor(const Mat32& T, double L, const Mat3& Mt, double dd, const Mat3& Kk,
                                            Eigen::Matrix2d& Phi, Mat32& H, Mat3& TH, Mat3& Kn) {
    const Vec3 t1 = T.col(0), t2 = T.col(1);
    const Mat3 A = 0.5 * Mt + Kk, B = 0.25 * Mt + Kk;
    const Vec3 g1 = L * (A * t1), g2 = L * (A * t2), v2 = B * t2;
    const double L2 = L * L;
    const double d11 = L2 * t1.dot(B * t1) + dd, d22 = L2 * t2.dot(v2) + dd, d12 = L2 * t1.dot(v2);
    const double idet = 1.0 / (d11 * d22 - d12 * d12);
    const double p11 = d22 * idet, p22 = d11 * idet, p12 = -d12 * idet;
    Phi(0, 0) = p11;
    Phi(0, 1) = Phi(1, 0) = p12;
    Phi(1, 1) = p22;
    const Vec3 h1 = p11 * g1 + p12 * g2, h2 = p12 * g1 + p22 * g2;  // H = G T Phi
    H.col(0) = h1;
    H.col(1) = h2;
    TH.noalias() = t1 * h1.transpose() + t2 * h2.transpose();
    for (int r = 0; r < 3; ++r)
      for (int q = r; q < 3; ++q)
        Kn(r, q) = Kn(q, r) = 0.5 * (Mt(r, q) + Mt(q, r) + Kk(r, q) + Kk(q, r)) - (h1[r] * g1[q] + h2[r] * g2[q]);
  }

  /// Stage solve, right-hand side as loads: -hg C at G on the velocity
  /// increment dv of the top joint plus the rotation's, -hg K_rock (hg dw +
  /// rot) as a couple; dv, dx carried to the bottom joint.
  [[gnu::always_inline]] static void load(const Vec3& e, double L, const Vec3& rdw, const Vec3& rrot, const Mat3& C,
                                          double Kr, double hg, Vec3& dv, Vec3& dx, Vec3& F, Vec3& Mom) {
    const Vec3 dw = rdw - rdw.dot(e) * e;
    const Vec3 rot = rrot - rrot.dot(e) * e;
    const Vec3 de = dw.cross(e);
    F = -hg * (C * (dv + 0.5 * L * de));
    Mom = -hg * Kr * (hg * dw + rot);
    dv += L * de;
    dx += L * rot.cross(e);
  }

  /// Stage solve, bias: b = H T^T r0 + b_below - F (- Fa), r0 = r0' - L
  /// b_below (r0' the loads' moment): the part through b_below as one 3x3
  /// product (H T^T = TH^T), off the rest; and q = T Phi T^T r0, the rotation
  /// at zero joint acceleration. Fa: the joint's load, or nullptr for none.
  [[gnu::always_inline]] static void stage_bias(const Vec3& e, double L, const Vec3& F, const Vec3& Mom, const Mat32& T,
                                                const Mat32& H, const Eigen::Matrix2d& Phi, const Mat3& TH,
                                                const Vec3& bk, const Vec3* Fa, Vec3& b, Eigen::Vector2d& Tr0,
                                                Vec3& q) {
    const Vec3 r0p = 0.5 * L * F - e.cross(Mom);  // r0 without the bias below
    const Vec3 t1 = T.col(0), t2 = T.col(1);
    const Vec3& h1 = H.col(0);
    const Vec3& h2 = H.col(1);
    const Vec3 loads = t1.dot(r0p) * h1 + t2.dot(r0p) * h2 - F;
    b = (Fa ? Vec3(loads - *Fa) : loads) + (bk - L * (TH.transpose() * bk));
    const Vec3 r0 = r0p - L * bk;
    Tr0 = Eigen::Vector2d(t1.dot(r0), t2.dot(r0));
    q = T * (Phi * Tr0);
  }

  /// Stage solve, increments: beta = q - TH a (= T Phi (T^T r0 - (G T)^T a)),
  /// alpha = e x beta, a moved to the bottom joint.
  [[gnu::always_inline]] static void stage_accelerate(const Vec3& q, const Mat3& TH, const Vec3& e, double L, Vec3& a,
                                                      Vec3& alpha) {
    const Vec3 beta = q - TH * a;
    alpha = e.cross(beta);
    a += L * beta;
  }
};

}  // namespace towsim::parts
