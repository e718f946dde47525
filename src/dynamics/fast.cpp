// Default formulation: O(n) articulated recursion along the chain
// (docs/theory.md §5.2 "Default formulation: linear-cost recursion").
//
// For the part of the system below joint k (elements k+1..n and the body),
// the force f_k it receives through the joint is affine in the joint's
// acceleration: f_k = K_k a_{P_k} + b_k. A backward pass builds (K_k, b_k)
// from the body up; a forward pass then gives each element's angular
// acceleration from the acceleration of the joint above it.
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim {

namespace {

/// Body at the end of the chain: its (K_n, b_n) for the link force
/// F_L = K_n a_Q + b_n, after eliminating its angular acceleration.
void body_articulated(const Model& model, Workspace& ws) {
  const std::size_t n = model.cable.elements.size();
  const Vec3 r = ws.rQ;  // Q - O_t [m, R_g]
  const Mat3 Rx = skew(r);
  const Mat3 Mll = ws.Mw.topLeftCorner<3, 3>(), Mla = ws.Mw.topRightCorner<3, 3>();
  const Mat3 Mal = ws.Mw.bottomLeftCorner<3, 3>(), Maa = ws.Mw.bottomRightCorner<3, 3>();
  const Vec3 hl = ws.hw.head<3>(), ha = ws.hw.tail<3>();
  // a_O = a_Q + [r]x alpha + w, with w the centripetal part.
  ws.wcent = ws.wB.cross(ws.wB.cross(-r));
  ws.CB = Mal - Rx * Mll;
  const Mat3 DB = ws.CB * Rx + Maa - Rx * Mla;  // inertia about Q
  ws.PhiB = DB.inverse();
  ws.rhsB = ws.Mb - r.cross(ws.Fb) - ha + r.cross(hl);
  ws.K[n] = Mll - ws.CB.transpose() * ws.PhiB * ws.CB;
  ws.b[n] = Mll * ws.wcent + ws.CB.transpose() * ws.PhiB * (ws.rhsB - ws.CB * ws.wcent) + hl - ws.Fb;
}

/// Backward pass: articulated inertia K_{k-1} and bias b_{k-1} seen at the top
/// joint of element k, from those at its bottom joint. The rotation equation
/// lives in the plane normal to e_k: it is solved in a tangent basis T, where
/// the element's own inertia is isotropic (T^T Mt T = (m + ma) I, Mt e = m e).
void backward_pass(const Model& model, const PhysicalState& s, Workspace& ws) {
  const auto& els = model.cable.elements;
  for (std::size_t k = els.size(); k-- > 0;) {
    const Element& el = els[k];
    const double L = el.length, m = el.mass, mn = el.mass + el.added_mass;
    const Vec3& e = s.e[k];
    const Mat3& Kk = ws.K[k + 1];
    const Vec3& bk = ws.b[k + 1];
    // Tangent basis normal to e.
    Eigen::Index i;
    e.cwiseAbs().minCoeff(&i);
    const Vec3 t1 = e.cross(Vec3::Unit(i)).normalized();
    auto& T = ws.T[k];
    T << t1, e.cross(t1);
    ws.c[k] = -s.w[k].squaredNorm() * e;  // Mt c = m c
    const Vec3& c = ws.c[k];
    // [T^T (L^2/4 Mt + L^2 K) T + Ir] z = T^T r0 - (G T)^T a_top, beta = T z.
    const Eigen::Matrix<double, 3, 2> KT = Kk * T;
    ws.GT[k] = 0.5 * L * mn * T + L * KT;
    Eigen::Matrix2d D = L * L * (T.transpose() * KT);
    D.diagonal().array() += 0.25 * L * L * mn + element_rot_inertia(el);
    ws.Dinv[k] = D.inverse();
    const Vec3 Kc = Kk * c;
    const Vec3 r0 = 0.5 * L * (ws.F[k] - 0.5 * L * m * c) - L * (L * Kc + bk) - e.cross(ws.Mom[k]);
    ws.y0[k] = T.transpose() * r0;
    // Force through the top joint, affine in its acceleration.
    const Eigen::Matrix<double, 3, 2> H = ws.GT[k] * ws.Dinv[k];
    ws.K[k] = Kk - H * ws.GT[k].transpose();
    ws.K[k] = 0.5 * (ws.K[k] + ws.K[k].transpose()).eval();  // symmetric in exact arithmetic
    ws.K[k].diagonal().array() += mn;
    ws.K[k] -= el.added_mass * e * e.transpose();
    ws.b[k] = H * ws.y0[k] + 0.5 * L * m * c + L * Kc + bk - ws.F[k];
  }
}

/// Forward pass: tow-point acceleration or tow force, then each element's
/// angular acceleration and joint force, then the body's.
void forward_pass(const Model& model, const PhysicalState& s, double t, Workspace& ws,
                  const Vec3* imposed_a0 = nullptr) {
  const auto& els = model.cable.elements;
  Accelerations& acc = ws.acc;
  if (imposed_a0 || model.tow.mode == Tow::Mode::Motion) {
    acc.a0 = imposed_a0 ? *imposed_a0 : tow_kinematics(model.tow, t).acc;
    acc.tow_force = ws.K[0] * acc.a0 + ws.b[0];
  } else {
    acc.tow_force = tow_force(model.tow, t);
    acc.a0 = ws.K[0].ldlt().solve(acc.tow_force - ws.b[0]);
  }
  acc.joint_force[0] = acc.tow_force;
  Vec3 a = acc.a0;
  for (std::size_t k = 0; k < els.size(); ++k) {
    const Vec3 beta = ws.T[k] * (ws.Dinv[k] * (ws.y0[k] - ws.GT[k].transpose() * a));  // alpha x e
    acc.alpha[k] = s.e[k].cross(beta);
    a += els[k].length * (beta + ws.c[k]);
    acc.joint_force[k + 1] = ws.K[k + 1] * a + ws.b[k + 1];
  }
  acc.link_force = acc.joint_force[els.size()];
  if (model.has_body) acc.alpha_b = ws.PhiB * (ws.rhsB - ws.CB * (a + ws.wcent));
}

}  // namespace

void compute_loads(const Model& model, const PhysicalState& s, double t, Workspace& ws) {
  const auto& els = model.cable.elements;
  for (std::size_t k = 0; k < els.size(); ++k) {
    element_loads(model, els[k], s.e[k], ws.edot[k], ws.vG[k], ws.G[k].z(), ws.F[k], ws.Mom[k]);
    ws.Mt[k] = element_mass(els[k], s.e[k]);
  }
  if (model.has_body) {
    body_inertia(model, s, ws);
    body_loads(model, s, t, ws);
  }
}

void tow_velocity_jump(const Model& model, const PhysicalState& s, const Vec3& dv, Workspace& ws) {
  // Same recursion at zero velocity with zero finite loads: only inertia and
  // the joint impulses remain; "accelerations" are then velocity jumps.
  PhysicalState s0 = s;
  s0.v0.setZero();
  for (auto& w : s0.w) w.setZero();
  s0.wb.setZero();
  compute_kinematics(model, s0, ws);
  compute_loads(model, s0, 0.0, ws);
  for (std::size_t k = 0; k < ws.F.size(); ++k) ws.F[k].setZero(), ws.Mom[k].setZero();
  const std::size_t n = model.cable.elements.size();
  if (model.has_body) {
    ws.Fb.setZero(), ws.Mb.setZero(), ws.hw.setZero();
    body_articulated(model, ws);
  } else {
    ws.K[n].setZero();
    ws.b[n].setZero();
  }
  backward_pass(model, s0, ws);
  forward_pass(model, s0, 0.0, ws, &dv);
}

void forward_dynamics(const Model& model, const PhysicalState& s, double t, Workspace& ws) {
  compute_kinematics(model, s, ws);
  compute_loads(model, s, t, ws);
  const std::size_t n = model.cable.elements.size();
  if (model.has_body) {
    body_articulated(model, ws);
  } else {
    ws.K[n].setZero();
    ws.b[n].setZero();
  }
  backward_pass(model, s, ws);
  forward_pass(model, s, t, ws);
}

}  // namespace towsim
