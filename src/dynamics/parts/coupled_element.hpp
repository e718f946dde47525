// Part: a rigid element whose rotation a bending spring couples to its
// neighbours' in the Rosenbrock stage solve (docs/theory.md §6.3 "Bending in
// the stage solve"). The bending spring is a joint part (bending.hpp: its
// couples and its self-stiffness); where it joins two rigid elements the
// stage solve keeps its off-diagonal stiffness exactly, and each element it
// couples is eliminated together with the response of the part below to
// the rotation of the element above. Its forward-dynamics steps are the
// rigid element's (the spring's couples are loads there).
#pragma once

#include <algorithm>

#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/implicit.hpp"

namespace towsim::parts {

/// E = [t2, -t1] = T J: alpha = E z for beta = alpha x e = T z (alpha normal to e).
inline Eigen::Matrix<double, 3, 2> rotation_basis(const Eigen::Matrix<double, 3, 2>& T) {
  Eigen::Matrix<double, 3, 2> E;
  E.col(0) = T.col(1);
  E.col(1) = -T.col(0);
  return E;
}

/// The bending springs the stage solve couples (kappa, any_coupled, coupled).
inline void couple_bending_springs(const Model& model, const Workspace& ws, ImplicitWorkspace& iw) {
  bending_stage_couplings(model, ws, iw.kappa);
  iw.any_coupled = std::any_of(iw.kappa.begin(), iw.kappa.end(), [](double x) { return x > 0; });
  const std::size_t n = iw.coupled.size();
  for (std::size_t k = 0; k < n; ++k) iw.coupled[k] = static_cast<char>(iw.kappa[k] > 0 || iw.kappa[k + 1] > 0);
}

/// The coupled springs' off-diagonal terms of -hg K (hg dw + rot): a couple on
/// each element from its neighbour's turn (dw, rot normal to its own e).
inline void coupled_spring_loads(const PhysicalState& s, double hg, const StageRhs& r, ImplicitWorkspace& iw) {
  auto turn = [&](std::size_t k) {
    const Vec3 u = hg * r.dw[k] + r.rot[k];
    return Vec3(u - u.dot(s.e[k]) * s.e[k]);
  };
  for (std::size_t j = 1; j + 1 < iw.kappa.size(); ++j) {
    if (!(iw.kappa[j] > 0)) continue;
    iw.Mom[j - 1] += hg * iw.kappa[j] * turn(j);
    iw.Mom[j] += hg * iw.kappa[j] * turn(j - 1);
  }
}

/// A rigid element whose rotation a bending spring couples to a neighbour's
/// (docs/theory.md §6.3 "Bending in the stage solve"), factor step: from the
/// part below's response at its bottom joint (K, Qb, Rb, Sb at k+1, spring
/// kappa_b) and its own modified inertias (Mt' [kg], Ir' [kg m^2]), the
/// response at its top joint, with kappa_t the spring above it.
struct CoupledBelow {
  const Mat3& K;
  const Mat3& Q;
  const Mat3& R;
  const Mat3& S;
};
[[gnu::noinline]] inline void coupled_element_factor(const Eigen::Matrix<double, 3, 2>& T, double L, const Mat3& Mt,
                                                     double Ir, const CoupledBelow& below, double kappa_b,
                                                     double kappa_t, double hg, std::size_t k, ImplicitWorkspace& iw) {
  const Eigen::Matrix<double, 3, 2> E = rotation_basis(T);
  const double cb = hg * hg * kappa_b, ct = hg * hg * kappa_t;  // the springs in the stage [N m s^2/rad]
  // The rotation equation D z = r0' - G~ a + ct E^T alpha_above (2x2).
  const Eigen::Matrix<double, 2, 3> Gt = 0.5 * L * T.transpose() * Mt + L * T.transpose() * below.K +
                                         cb * E.transpose() * below.R;
  const Eigen::Matrix2d D = Ir * Eigen::Matrix2d::Identity() + 0.25 * L * L * T.transpose() * Mt * T +
                            L * L * T.transpose() * below.K * T + L * T.transpose() * below.Q * E +
                            cb * L * E.transpose() * below.R * T - cb * E.transpose() * below.S * E;
  const Eigen::Matrix2d Phi = D.inverse();
  // The force through the top joint: f = (Mt' + K) a + H' z - F + b.
  const Eigen::Matrix<double, 3, 2> Hp = 0.5 * L * Mt * T + L * below.K * T + below.Q * E;
  iw.Phi[k] = Phi;
  iw.H[k] = Hp * Phi;
  iw.PG[k] = Phi * Gt;
  iw.PE[k] = Phi * E.transpose();
  const Mat3 Kn = Mt + below.K - iw.H[k] * Gt;
  iw.K[k] = 0.5 * (Kn + Kn.transpose());
  iw.Qb[k] = ct * iw.H[k] * E.transpose();
  iw.Rb[k] = E * iw.PG[k];
  iw.Sb[k] = ct * E * iw.PE[k];
}

/// The same element's bias step: r0' = E^T Mom + L/2 T^T F - L T^T b_below +
/// cb E^T q_below; z at zero inputs Phi r0'; b = H' Phi r0' - F + b_below (- Fa);
/// q = E Phi r0'. body_below: a body's ball joint below (no spring there).
[[gnu::noinline]] inline void coupled_element_bias(std::size_t k, double L, bool body_below, const Vec3& b_below,
                                                   bool joints, ImplicitWorkspace& iw) {
  const Eigen::Matrix<double, 3, 2>& T = iw.T[k];
  const Eigen::Matrix<double, 3, 2> E = rotation_basis(T);
  const double cb = body_below ? 0.0 : iw.hg * iw.hg * iw.kappa[k + 1];
  const Vec3 qk = cb > 0 ? iw.qb[k + 1] : Vec3::Zero().eval();
  const Eigen::Vector2d r0 = E.transpose() * iw.Mom[k] + T.transpose() * (0.5 * L * iw.F[k] - L * b_below) +
                             cb * (E.transpose() * qk);
  iw.zr[k] = iw.Phi[k] * r0;
  iw.b[k] = iw.H[k] * r0 - iw.F[k] + b_below;
  if (joints) iw.b[k] -= iw.Fa[k];
  iw.qb[k] = E * iw.zr[k];
}

/// The same element's forward step from its top joint's a: z = Phi (r0' -
/// G~ a + ct E^T alpha_above), alpha = E z; returns the move of the bottom
/// joint, L T z.
[[gnu::noinline]] inline Vec3 coupled_element_acceleration(std::size_t k, double L, const Vec3& a,
                                                           ImplicitWorkspace& iw) {
  const double ct = iw.hg * iw.hg * iw.kappa[k];
  Eigen::Vector2d z = iw.zr[k] - iw.PG[k] * a;
  if (ct > 0) z += ct * (iw.PE[k] * iw.alpha[k - 1]);
  const Eigen::Matrix<double, 3, 2>& T = iw.T[k];
  iw.alpha[k] = z[0] * T.col(1) - z[1] * T.col(0);  // E z
  return L * (T * z);
}

}  // namespace towsim::parts
