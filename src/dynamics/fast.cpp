// Default formulation: O(n) articulated recursion along the chain of parts
// (docs/theory.md §5.2 "Linear-cost recursion", §5.3 "Bodies in the chain").
//
// For the part of the system below joint k (everything hanging from it:
// elements, attachments, bodies), the force f_k it receives through the
// joint is affine in the joint's acceleration: f_k = K_k a_{P_k} + b_k. A
// backward pass builds (K_k, b_k) from the bottom of the chain up; a forward
// pass then gives each element's and body's angular acceleration from the
// acceleration of the joint above it.
#include <algorithm>
#include <stdexcept>

#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim {

namespace {

/// Index helper: body b of the model as a size_t.
inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// Body hanging at Q: its (KQ, bQ) for the link force F_L = KQ a_Q + bQ,
/// after eliminating its angular acceleration. An in-line body first takes
/// in the articulated cable below it, (K2, b2) seen at its lower link Q2:
/// with a_Q2 = J2 [a_O; alpha] + c2, J2 = [I, -[r2]x], the cable below adds
/// J2^T K2 J2 to its inertia and J2^T (K2 c2 + b2) to its bias.
void body_articulated(const Body& body, BodyWork& bw, const Mat3* K2, const Vec3* b2) {
  bw.Me = bw.Mw;
  bw.he = bw.hw;
  if (body.inline_body) {
    Eigen::Matrix<double, 6, 3> J2t;
    J2t << Mat3::Identity(), skew(bw.rQ2);
    const Vec3 c2 = bw.w.cross(bw.w.cross(bw.rQ2));
    bw.Me += J2t * *K2 * J2t.transpose();
    bw.he += J2t * (*K2 * c2 + *b2);
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

/// The backward pass's per-element arrays of a Workspace, as pointers taken
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
  Eigen::Matrix<double, 3, 2>*T, *GT;
  Eigen::Matrix2d* Phi;
  Eigen::Matrix<double, 3, 2>* H;
  Mat3* K;
  Vec3 *b, *c;
  Eigen::Vector2d* Tr0;
};

/// One element's backward step, its inertia part: the articulated inertia
/// K_{k-1} seen at the top joint of element k from Kk at its bottom joint,
/// and what the bias step and the forward pass read (T, G T, Phi, H). It
/// depends on the state's directions and lengths only, never on time or loads.
/// The rotation equation lives in the plane normal to e_k: it is solved in a
/// tangent basis T, where the element's own inertia is isotropic
/// (T^T Mt T = (m + ma) I, Mt e = m e).
/// kSymmetric: Kk is exactly symmetric (an element's K below, mirrored), so
/// its symmetric part is Kk itself (0.5 (a + a) = a in floating point).
template <bool kSymmetric>
void element_inertia(const Element& el, const Vec3& e, const Mat3& Kk, std::size_t k, const ElementArrays& ws) {
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

/// One element's backward step, its bias part: b_{k-1} at the top joint of
/// element k from (Kk, bk) at its bottom joint and the element's loads, with
/// the inertia part's T and H (element_inertia).
void element_bias(const Element& el, const Vec3& e, const Vec3& w, const Mat3& Kk, const Vec3& bk, std::size_t k,
                  const ElementArrays& ws) {
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

/// Backward pass, from the bottom of the chain up: at each joint, the part
/// below is the element under it plus any attachment there, or a body (which
/// carries the cable hanging from its lower link, if any). With
/// inertias_known, the rigid elements' inertia part (K, T, G T, Phi, H) is
/// the workspace's already, from an evaluation at the same directions and
/// lengths: only their bias part runs (elastic elements and bodies: all).
void backward_pass(const Model& model, const PhysicalState& s, Workspace& ws, bool inertias_known = false) {
  const std::size_t n = model.cable.elements.size();
  // Point loads and inertias at the joints exist only with attachments or a
  // seabed; else Ma and Fa are +0 (attachment_loads) and adding them changes
  // no bit: skipped.
  const bool joints = !model.cable.attachments.empty() || model.seabed.has_value();
  // Nothing hangs below the cable's end but its attachments.
  ws.K[n] = ws.Ma[n];
  ws.b[n] = -ws.Fa[n];
  bool symmetric = true;  // K[k+1] exactly symmetric (Ma[n]; a rigid element's K, mirrored)
  const ElementArrays arrays(ws);
  const int* body_at = ws.body_at.data();
  const Element* els = model.cable.elements.data();
  const Vec3 *e = s.e.data(), *w = s.w.data();
  for (std::size_t k = n; k-- > 0;) {
    // What the bottom joint of element k+1 carries: a body, or joint k+1.
    const int bi = body_at[k + 1];
    const Mat3* Kk = arrays.K + k + 1;
    const Vec3* bk = arrays.b + k + 1;
    if (bi >= 0) {
      BodyWork& bw = ws.body[idx(bi)];
      body_articulated(model.bodies[idx(bi)], bw, Kk, bk);
      Kk = &bw.KQ;
      bk = &bw.bQ;
      symmetric = false;
    }
    if (is_elastic(els[k])) {
      elastic_backward(s.e[k], s.length_of(model, k), ws.Mt[k], ws.F[k], ws.Mom[k], *Kk, *bk, ws.elastic[k], ws.K[k],
                       ws.b[k]);
      ws.K[k] += ws.Ma[k];
      symmetric = false;
    } else {
      const Element& el = k == 0 && ws.winch ? ws.top : els[k];  // current_element
      if (!inertias_known || (k == 0 && ws.winch)) {             // the winch's top: its length moves with time
        if (symmetric)
          element_inertia<true>(el, e[k], *Kk, k, arrays);
        else
          element_inertia<false>(el, e[k], *Kk, k, arrays);
        if (joints) ws.K[k] += ws.Ma[k];
      }
      element_bias(el, e[k], w[k], *Kk, *bk, k, arrays);
      symmetric = true;
    }
    // An attachment at joint k moves with it: its inertia (above) and loads add on.
    if (joints) ws.b[k] -= ws.Fa[k];
  }
}

/// A body's forward step from the acceleration a of its link point Q:
/// its angular acceleration, link force and, for an in-line body, the
/// acceleration of its lower link Q2 (returned in a) and the force there.
void body_forward(const Body& body, const BodyWork& bw, const Mat3& K2, const Vec3& b2, std::size_t b, Vec3& a,
                  Accelerations& acc) {
  acc.alpha_b[b] = bw.Phi * (bw.rhs - bw.C * (a + bw.wcent));
  acc.link_force[b] = bw.KQ * a + bw.bQ;
  acc.lower_link_force[b].setZero();
  if (!body.inline_body) return;
  const Vec3& al = acc.alpha_b[b];
  const Vec3 aO = a + bw.rQ.cross(al) + bw.wcent;
  a = aO + al.cross(bw.rQ2) + bw.w.cross(bw.w.cross(bw.rQ2));
  acc.lower_link_force[b] = K2 * a + b2;
}

/// The winch's deployed length: the paid-out top element plus the fixed
/// elements below it and the cable drawn in by removals (unstretched over an
/// elastic top; as the integrator's stops at min_length/max_length see it) [m].
double deployed_length(const Model& model, const PhysicalState& s) {
  double L = model.winch.length_offset + paid_out_length(model, s);
  const auto& els = model.cable.elements;
  for (std::size_t k = 1; k < els.size(); ++k) L += els[k].length;
  return L;
}

/// Tension-controlled winch: the pay-out acceleration l'' from the drum's
/// equation M_d l'' = T - T_set - c l', where the tension at the sheave
/// T = -e_1 . f_0 is affine in l'': f_0 = K_0 (a + l'' e_1) + b_0 = f + l'' K_0 e_1
/// (f the force at l'' = 0). Clamped to the acceleration limit, and to zero
/// where the speed limit is reached and l'' would pass it, and where the drum
/// is stopped at min_length or max_length (deployed length L [m]) and l''
/// would take it out: there the drum holds, so the forces are those of a
/// fixed length (not of a drum accelerating against its stop).
double drum_acceleration(const Winch& w, const Vec3& e1, double rate, double L, const Mat3& K0, const Vec3& f) {
  const double T0 = -e1.dot(f);      // tension at l'' = 0 [N]
  const double k = e1.dot(K0 * e1);  // dT/dl'' = -k [kg]
  double acc = (T0 - w.tension - w.damping * rate) / (w.drum_inertia + k);
  acc = std::clamp(acc, -w.max_acceleration, w.max_acceleration);
  if ((rate >= w.max_speed && acc > 0) || (rate <= -w.max_speed && acc < 0)) acc = 0;
  // The stop's round-off: the projection puts L back on the limit [m].
  const double eps = 1e-9 * std::max(1.0, L);
  if ((L <= w.min_length + eps && rate <= 0 && acc < 0) || (L >= w.max_length - eps && rate >= 0 && acc > 0)) acc = 0;
  return acc;
}

/// Forward pass: tow-point acceleration or tow force, then down the chain
/// each element's angular acceleration and joint force, and each body's.
void forward_pass(const Model& model, const PhysicalState& s, double t, Workspace& ws,
                  const Vec3* imposed_a0 = nullptr) {
  const auto& els = model.cable.elements;
  Accelerations& acc = ws.acc;
  // Winch: the top element's material at the sheave accelerates at
  // a_0 + l'' e_1 + 2 l' (omega_1 x e_1) (the tow point's, the pay-out's and
  // the Coriolis term); the recursion runs from there unchanged.
  Vec3 a_extra = Vec3::Zero();  // a_top - a_0 without the l'' term [m/s^2]
  acc.top_length_acc = 0;
  const bool winch = ws.winch && !imposed_a0;  // an impulse (imposed_a0) has no pay-out acceleration
  const bool elastic_top = winch && is_elastic(els[0]);
  const Vec3 e1 = s.e.empty() ? Vec3::UnitZ().eval() : s.e[0];  // [-, R_g]
  // Elastic top element: the material at the sheave accelerates at
  // a_0 + lam L_1'' e_1 + 2 lam L_1' (omega_1 x e_1) + 2 (L_1'/L_1)(l_1' - lam L_1') e_1,
  // lam = l_1/L_1 (its velocity v_0 + lam L_1' e_1 seen in the material).
  double lam = 1;       // stretch l_1/L_1 multiplying L_1'' [-]
  double pay_rate = 0;  // the winch's rate: l_1' (rigid) or L_1' (elastic) [m/s]
  if (elastic_top) {
    const double l = s.length_of(model, 0), Lu = s.top_unstretched;
    pay_rate = s.top_unstretched_rate;
    lam = l / Lu;
    a_extra = 2 * lam * pay_rate * ws.edot[0] + 2 * pay_rate / Lu * (s.length_rate_of(0) - lam * pay_rate) * e1;
  } else if (winch) {
    pay_rate = element_length_rate(s, 0);
    a_extra = 2 * pay_rate * ws.edot[0];
  }
  const Mat3 K_pay = elastic_top ? Mat3(lam * ws.K[0]) : ws.K[0];  // d(f_0)/d(L_1'') along e_1 [kg]
  if (winch && model.winch.mode == Winch::Mode::Imposed) acc.top_length_acc = winch_kinematics(model.winch, t).acc;
  if (imposed_a0 || model.tow.mode == Tow::Mode::Motion) {
    acc.a0 = imposed_a0 ? *imposed_a0 : tow_kinematics(model.tow, t, ws.course).acc;
    if (winch && model.winch.mode == Winch::Mode::Tension)
      acc.top_length_acc = drum_acceleration(model.winch, e1, pay_rate, deployed_length(model, s), K_pay,
                                             ws.K[0] * (acc.a0 + a_extra) + ws.b[0]);
  }
  const Vec3 a_pay = elastic_top ? Vec3(lam * acc.top_length_acc * e1) : Vec3(acc.top_length_acc * e1);
  if (imposed_a0 || model.tow.mode == Tow::Mode::Motion) {
    acc.tow_force = ws.K[0] * (acc.a0 + a_extra + a_pay) + ws.b[0];
  } else {
    acc.tow_force = tow_force(model.tow, t);
    acc.a0 = ws.K[0].ldlt().solve(acc.tow_force - ws.b[0]) - a_extra - a_pay;
  }
  acc.joint_force[0] = acc.tow_force;
  Vec3 a = acc.a0 + a_extra + a_pay;
  // The arrays' data through local pointers: the compiler cannot tell that
  // the stores into them leave the vectors alone, and would reload each
  // one's start per element.
  const Eigen::Matrix<double, 3, 2>*T = ws.T.data(), *GT = ws.GT.data();
  const Eigen::Matrix2d* Phi = ws.Phi.data();
  const Eigen::Vector2d* Tr0 = ws.Tr0.data();
  const Vec3 *c = ws.c.data(), *e = s.e.data(), *bs = ws.b.data();
  const double* Ls = ws.L.data();
  const Mat3* Ks = ws.K.data();
  const int* body_at = ws.body_at.data();
  Vec3 *alpha = acc.alpha.data(), *joint_force = acc.joint_force.data();
  for (std::size_t k = 0; k < els.size(); ++k) {
    if (k == 0 && elastic_top) {
      // The winch's elastic element: its top is the material at the sheave.
      a += elastic_forward(ws.elastic[0], s.e[0], s.w[0], s.length_of(model, 0), s.length_rate_of(0), a,
                           Vec3(a - acc.a0), acc.alpha[0], acc.length_acc[0]);
    } else if (is_elastic(els[k])) {
      // Elastic element: d'' from the top joint's acceleration (§5.4).
      a += elastic_forward(ws.elastic[k], s.e[k], s.w[k], s.length_of(model, k), s.length_rate_of(k), a, acc.alpha[k],
                           acc.length_acc[k]);
    } else {
      const Vec3 beta = T[k] * (Phi[k] * (Tr0[k] - GT[k].transpose() * a));  // alpha x e
      alpha[k] = e[k].cross(beta);
      a += Ls[k] * (beta + c[k]);
    }
    const int bi = body_at[k + 1];
    if (bi < 0) {
      joint_force[k + 1] = Ks[k + 1] * a + bs[k + 1];
      continue;
    }
    const Body& body = model.bodies[idx(bi)];
    body_forward(body, ws.body[idx(bi)], ws.K[k + 1], ws.b[k + 1], idx(bi), a, acc);
    acc.joint_force[k + 1] = body.inline_body ? acc.lower_link_force[idx(bi)] : acc.link_force[idx(bi)];
  }
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

/// A cable landing vertically on the bottom (docs/theory.md §3.2): a joint in
/// contact at the end of a vertical line of elements (the element above comes
/// down within kVertical of the vertical, and the one below, if any, is
/// vertical too) gets a push of kTip times its normal force along the bottom
/// (towards +x_g, or +y_g where the bottom's normal is along x_g). Such an
/// upright column standing on the bottom is an unstable equilibrium that the
/// exact symmetry of a vertical pay-out would otherwise keep for ever, driven
/// into the bottom by the winch; the push only starts its fall (it stops once
/// the element leans by kVertical). A cable lying on the bottom (horizontal
/// elements below its touchdown) never gets it.
void seabed_tipping(const Model& model, const PhysicalState& s, Workspace& ws) {
  if (!model.seabed) return;
  constexpr double kVertical = 1e-6;  // [rad]: an element leaning less is vertical
  constexpr double kTip = 1e-3;       // push / normal force [-]
  const std::size_t n = s.e.size();
  auto vertical = [&](std::size_t i) { return s.e[i].head<2>().norm() <= kVertical; };
  for (std::size_t k = 1; k <= n && k < ws.Fs.size(); ++k) {
    if (ws.ls[k] <= 0 || ws.body_at[k] >= 0) continue;
    // The element above points down to P_k; the one below stands on it.
    if (s.e[k - 1].z() >= 0 || !vertical(k - 1) || (k < n && !vertical(k))) continue;
    const Vec3 nb = model.seabed->normal(ws.P[k].x());  // the bottom's normal [-, R_g]
    Vec3 d = Vec3::UnitX() - nb.x() * nb;
    if (d.norm() < 0.1) d = Vec3::UnitY() - nb.y() * nb;
    const Vec3 push = kTip * std::abs(ws.Fs[k].dot(nb)) * d.normalized();  // [N, R_g]
    ws.Fs[k] += push;
    ws.Fa[k] += push;
  }
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
  seabed_tipping(model, s, ws);
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
  backward_pass(model, s0, ws);
  forward_pass(model, s0, 0.0, ws, &dv);
}

void forward_dynamics(const Model& model, const PhysicalState& s, double t, Workspace& ws, Fork* fork) {
  check_fits(model, s, ws);
  compute_kinematics(model, s, ws);
  compute_loads(model, s, t, ws, fork);
  backward_pass(model, s, ws);
  forward_pass(model, s, t, ws);
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
  backward_pass(model, s, ws, true);
  forward_pass(model, s, t, ws);
}

}  // namespace towsim
