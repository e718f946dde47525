// The slow, independent reference of the O(n) recursion: the parts'
// Newton-Euler equations with one Lagrange multiplier per ball joint,
// assembled into one dense KKT system and solved by full-pivot LU, for a
// chain or a tree of lines (towsim/dynamics/tree.hpp). It uses the same load
// models (compute_loads, the axial force laws) as the recursion and nothing
// else of it, so agreement to round-off proves the recursion's algebra.
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "towsim/dynamics/elastic.hpp"
#include "towsim/dynamics/tree.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/model/winch.hpp"

namespace towsim::testing {

/// Unknowns: each part's accelerations (rigid element and body: a of its
/// reference point and alpha; elastic element: a of its centre G and d'',
/// its bottom end's acceleration relative to its top end; attachment: a),
/// one force per joint, one spin multiplier per rigid element (alpha . e =
/// 0) and, with a tension-controlled winch (line 0 only), the pay-out
/// acceleration. Lines hanging from a node are joined to it by one more
/// ball joint each, and each loop's cable end to its node by one more.
class KktReference {
 public:
  /// A chain: its top joint moves at a0 [m/s^2] (the tow law's acceleration at t).
  KktReference(const Model& m, const PhysicalState& s, const Workspace& ws, const Vec3& a0, double t)
      : KktReference(std::vector<const Model*>{&m}, std::vector<LineTop>{LineTop{}},
                     std::vector<const PhysicalState*>{&s}, std::vector<const Workspace*>{&ws}, std::vector<Vec3>{a0},
                     t) {}
  /// A tree: its lines' models, tops, states and evaluated workspaces; a0
  /// per line (read for the roots only).
  KktReference(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, const std::vector<Vec3>& a0,
               double t)
      : KktReference(pointers(tree.lines), tree.tops, pointers(s), pointers(ws.lines), a0, t, &ws.slot, &tree.loops,
                     &ws.loop_slot) {}

  /// A tree's stage system (tree_stage_solve at hg, iw after it: its loads
  /// pass's right-hand side as the loads): the same parts and joints at zero
  /// velocity with the stage's inertias M + hg C + hg^2 K, the roots held
  /// (tow mode motion, no winch, no seabed). Unknowns: the increments z;
  /// the joints' multipliers are impulses [N s].
  KktReference(const TreeModel& tree, const TreeState& s, const TreeWorkspace& ws, const TreeImplicitWorkspace& iw,
               double hg)
      : KktReference(pointers(tree.lines), tree.tops, pointers(s), pointers(ws.lines),
                     std::vector<Vec3>(tree.lines.size(), Vec3::Zero()), 0.0, &ws.slot, &tree.loops, &ws.loop_slot,
                     Stage{pointers(iw.lines), hg}) {}

  Vec3 alpha(std::size_t k, std::size_t line = 0) const { return alpha_[line][k]; }
  double length_acc(std::size_t k, std::size_t line = 0) const { return length_acc_[line][k]; }
  Vec3 alpha_body(std::size_t b, std::size_t line = 0) const { return x_.segment<3>(body_[line][b] + 3); }
  /// The winch's pay-out acceleration (l_1'' rigid, L_1'' elastic) [m/s^2].
  double pay_acc() const { return pay_acc_; }
  /// Force through a joint on the part below it (by the joint's index in order).
  Vec3 force(std::size_t j) const { return lambda_.segment<3>(static_cast<Eigen::Index>(3 * j)); }
  /// Loop j's force: its node's on its line's cable end [N].
  Vec3 loop_force(std::size_t j) const { return force(loop_joint_[j]); }
  // Per line: the joint below each cable joint k (k = 0..n) giving f_k
  // (kNone at a free end with nothing below it: f_n = 0), and per body its links.
  std::vector<std::vector<std::size_t>> joint_of_node, upper_link, lower_link;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

 private:
  struct Stage {
    std::vector<const ImplicitWorkspace*> iw;  // empty: the forward dynamics
    double hg;                                 // [s]
  };
  template <class T>
  static std::vector<const T*> pointers(const std::vector<T>& v) {
    std::vector<const T*> p;
    for (const T& x : v) p.push_back(&x);
    return p;
  }
  KktReference(std::vector<const Model*> m, std::vector<LineTop> tops, std::vector<const PhysicalState*> s,
               std::vector<const Workspace*> ws, std::vector<Vec3> a0, double t, const std::vector<int>* slot = nullptr,
               const std::vector<LoopJoint>* loops = nullptr, const std::vector<int>* loop_slot = nullptr,
               Stage stage = {})
      : m_(std::move(m)),
        tops_(std::move(tops)),
        s_(std::move(s)),
        ws_(std::move(ws)),
        a0_(std::move(a0)),
        stage_(std::move(stage)) {
    const std::size_t nl = m_.size();
    el_.resize(nl), body_.resize(nl), att_.resize(nl), end_point_.resize(nl);
    joint_of_node.resize(nl), upper_link.resize(nl), lower_link.resize(nl);
    alpha_.resize(nl), length_acc_.resize(nl);
    // Parts: per line its elements, bodies, attachments (in that order of unknowns).
    for (std::size_t l = 0; l < nl; ++l) {
      const Model& ml = *m_[l];
      for (std::size_t k = 0; k < ml.cable.elements.size(); ++k) el_[l].push_back(add_part(6));
      for (std::size_t b = 0; b < ml.bodies.size(); ++b) body_[l].push_back(add_part(6));
      for (std::size_t i = 0; i < ml.cable.attachments.size(); ++i) att_[l].push_back(add_part(3));
    }
    winch_setup(t);
    for (std::size_t l = 0; l < nl; ++l) build_joints(l, slot);
    // Loops: the node's point above, the loop line's cable end below.
    for (std::size_t j = 0; loops != nullptr && j < loops->size(); ++j) {
      const LoopJoint& lp = (*loops)[j];
      const auto nl_j = static_cast<std::size_t>(lp.node_line);
      Point node = end_point_[nl_j];
      if (lp.body >= 0) {
        const auto b = static_cast<std::size_t>(lp.body);
        node = body_point(nl_j, b, ws_[nl_j]->body[b].children[static_cast<std::size_t>((*loop_slot)[j])].r);
      }
      loop_joint_.push_back(joints_.size());
      link(node, end_point_[static_cast<std::size_t>(lp.line)]);
    }
    solve();
  }

  /// A point on a part: its part's offset, position r from the reference
  /// point, and the acceleration's part independent of the unknowns.
  /// Rigid part: a = a_ref + alpha x r + w x (w x r); particle: a = a_ref;
  /// elastic element: a = a_G + half d'' (half = -1/2 at the top, +1/2 at
  /// the bottom).
  struct Point {
    int part = -1;  // offset of the part's unknowns, -1 = the imposed tow point
    int dof = 6;
    Vec3 r = Vec3::Zero();
    Vec3 c = Vec3::Zero();
    double half = 0;  // elastic element's end: -1/2 top, +1/2 bottom; 0 = rigid part
  };
  int add_part(int dof) {
    const int o = static_cast<int>(dofs_);
    dofs_ += static_cast<std::size_t>(dof);
    return o;
  }
  const Element& element(std::size_t l, std::size_t k) const { return current_element(*m_[l], *ws_[l], k); }
  bool elastic(std::size_t l, std::size_t k) const { return is_elastic(m_[l]->cable.elements[k]); }
  Point element_point(std::size_t l, std::size_t k, double side) const {
    if (elastic(l, k)) return {el_[l][k], 6, Vec3::Zero(), Vec3::Zero(), 0.5 * side};
    const double L = s_[l]->length_of(*m_[l], k);  // current length [m]
    const Vec3 r = side * 0.5 * L * s_[l]->e[k];
    if (staged()) return {el_[l][k], 6, r, Vec3::Zero()};  // zero velocity
    return {el_[l][k], 6, r, s_[l]->w[k].cross(s_[l]->w[k].cross(r))};
  }
  Point body_point(std::size_t l, std::size_t b, const Vec3& r) const {
    const Vec3& w = ws_[l]->body[b].w;
    if (staged()) return {body_[l][b], 6, r, Vec3::Zero()};
    return {body_[l][b], 6, r, w.cross(w.cross(r))};
  }
  Point attachment_point(std::size_t l, std::size_t i) const { return {att_[l][i], 3, Vec3::Zero(), Vec3::Zero()}; }
  void link(const Point& above, const Point& below) { joints_.push_back({above, below}); }

  /// Winch (line 0): the top element's material at the sheave. Rigid top
  /// (material fixed to P_1 = P_0 + l e_1, at the sheave at distance l from
  /// P_1): a = a_0 + l'' e_1 + 2 l' (w_1 x e_1). Elastic top (unstretched
  /// coordinate sigma from P_1, the point at P_0 + q e_1 with
  /// q = l (1 - sigma / L_1), sigma = L_1 at the sheave, q = 0):
  /// a = a_0 + q'' e_1 + 2 q' (w_1 x e_1), q' = (l / L_1) L_1',
  /// q'' = (l / L_1) L_1'' + 2 l' L_1' / L_1 - 2 l L_1'^2 / L_1^2.
  /// sheave_c_ is the part without L'', sheave_u_ the coefficient of L''.
  void winch_setup(double t) {
    if (!ws_[0]->winch || staged()) return;
    const Model& m = *m_[0];
    const PhysicalState& s = *s_[0];
    const Vec3& e1 = s.e[0];
    const Vec3 wxe = s.w[0].cross(e1);
    const double l = s.length_of(m, 0), lr = s.length_rate_of(0);
    double qd = lr, qdd0 = 0;  // q' [m/s], q'' without the L'' term [m/s^2]
    if (elastic(0, 0)) {
      const double Lu = s.top_unstretched, Lr = s.top_unstretched_rate;
      qd = l / Lu * Lr;
      qdd0 = 2 * lr * Lr / Lu - 2 * l * Lr * Lr / (Lu * Lu);
      sheave_u_ = l / Lu * e1;
      pay_rate_ = Lr;
    } else {
      sheave_u_ = e1;
      pay_rate_ = lr;
    }
    sheave_c_ = qdd0 * e1 + 2 * qd * wxe;
    if (m.winch.mode == Winch::Mode::Imposed) {
      pay_acc_ = winch_kinematics(m.winch, t).acc;
      sheave_c_ += pay_acc_ * sheave_u_;
    } else {
      drum_ = static_cast<int>(dofs_);
      dofs_ += 1;
    }
  }

  /// Line l's top: the vessel's imposed point, or its node on the line above.
  Point top_point(std::size_t l, const std::vector<int>* slot) const {
    const LineTop& top = tops_[l];
    if (top.line < 0) {
      Point p;
      p.c = a0_[l];  // imposed acceleration of the tow point
      return p;
    }
    const auto pl = static_cast<std::size_t>(top.line);
    if (top.body < 0) return end_point_[pl];
    const auto b = static_cast<std::size_t>(top.body);
    const BodyWork& bw = ws_[pl]->body[b];
    return body_point(pl, b, bw.children[static_cast<std::size_t>((*slot)[l])].r);
  }

  void build_joints(std::size_t l, const std::vector<int>* slot) {
    const Model& m = *m_[l];
    const Workspace& ws = *ws_[l];
    const std::size_t n = m.cable.elements.size();
    joint_of_node[l].assign(n + 1, 0);
    upper_link[l].assign(m.bodies.size(), 0);
    lower_link[l].assign(m.bodies.size(), 0);
    std::vector<int> att_at(n + 1, -1);
    for (std::size_t i = 0; i < m.cable.attachments.size(); ++i)
      att_at[static_cast<std::size_t>(m.cable.attachments[i].joint)] = static_cast<int>(i);
    // Joint k: what is above it (the line's top or the bottom of element k),
    // then an attachment, a body, or the top of element k+1.
    for (std::size_t k = 0; k <= n; ++k) {
      Point above = k == 0 ? top_point(l, slot) : element_point(l, k - 1, +1);
      joint_of_node[l][k] = joints_.size();
      if (att_at[k] >= 0) {
        const Point p = attachment_point(l, static_cast<std::size_t>(att_at[k]));
        link(above, p);
        above = p;
      }
      const int b = ws.body_at[k];
      if (b >= 0) {
        const auto bi = static_cast<std::size_t>(b);
        upper_link[l][bi] = joints_.size();
        link(above, body_point(l, bi, ws.body[bi].rQ));
        if (!m.bodies[bi].inline_body) continue;
        above = body_point(l, bi, ws.body[bi].rQ2);
        lower_link[l][bi] = joints_.size();
        joint_of_node[l][k] = joints_.size();
      }
      if (k == 0 && l == 0 && ws.winch) {
        // The top element hangs from its material at the sheave.
        sheave_joint_ = joints_.size();
        above.c += sheave_c_;
      }
      if (k < n) link(above, element_point(l, k, -1));
      if (k == n) end_point_[l] = above;  // a junction: the lines below hang from it
    }
    // A free end without attachment or body: nothing below it, no joint.
    if (joint_of_node[l][n] == joints_.size()) joint_of_node[l][n] = kNone;
  }

  /// Rows of J for a point: a_X = J x + c, J = [I, -[r]x] (rigid),
  /// [I, half I] (elastic) or I (particle).
  static void put_point(Eigen::MatrixXd& A, std::size_t row, std::size_t col_base, const Point& p, double sign) {
    if (p.part < 0) return;
    const auto c = col_base + static_cast<std::size_t>(p.part);
    const auto r = static_cast<Eigen::Index>(row), c0 = static_cast<Eigen::Index>(c);
    A.block<3, 3>(r, c0) += sign * Mat3::Identity();
    if (p.half != 0)
      A.block<3, 3>(r, c0 + 3) += sign * p.half * Mat3::Identity();
    else if (p.dof == 6)
      A.block<3, 3>(r, c0 + 3) -= sign * skew(p.r);
  }

  bool staged() const { return !stage_.iw.empty(); }

  /// The stage's inertias M + hg C + hg^2 K and its right-hand side's loads
  /// of line l's parts (as put_parts): a rigid element's damping at G and
  /// rocking stiffness in its rotation block, an elastic element's spring S
  /// on d (the KKT's d-block Mt/12 + S: the recursion's Mt/3 + hg C/4 + S on
  /// (v_top, d') seen from G), a body's damping and rotational stiffness, an
  /// attachment's damping and stiffness at its joint.
  void put_stage_parts(std::size_t l, Eigen::MatrixXd& A, Eigen::VectorXd& rhs) const {
    const Model& m = *m_[l];
    const PhysicalState& s = *s_[l];
    const Workspace& ws = *ws_[l];
    const ImplicitWorkspace& iw = *stage_.iw[l];
    const LocalJacobian& jac = iw.jac;
    const double hg = stage_.hg;
    for (std::size_t k = 0; k < m.cable.elements.size(); ++k) {
      const auto o = static_cast<Eigen::Index>(el_[l][k]);
      const Vec3& e = s.e[k];
      const Element& el = element(l, k);
      const Mat3 P = Mat3::Identity() - e * e.transpose();
      A.block<3, 3>(o, o) = element_mass(el, e) + hg * jac.element_damping[k];
      rhs.segment<3>(o) = iw.F[k];
      if (elastic(l, k)) {
        const double len = s.length_of(m, k);
        const Mat3 S = (hg * element_axial_damping_rate(el, len) + hg * hg * element_axial_stiffness(el, len)) *
                           (e * e.transpose()) +
                       hg * hg * jac.element_stiffness[k] / (len * len) * P;
        A.block<3, 3>(o + 3, o + 3) = element_mass(el, e) / 12 + S;
        rhs.segment<3>(o + 3) = iw.Fd[k];
      } else {
        A.block<3, 3>(o + 3, o + 3) = (element_rot_inertia(el) + hg * hg * jac.element_stiffness[k]) * P;
        rhs.segment<3>(o + 3) = iw.Mom[k];
      }
    }
    for (std::size_t b = 0; b < body_[l].size(); ++b) {
      const auto o = static_cast<Eigen::Index>(body_[l][b]);
      Mat6 Me = ws.body[b].Mw + hg * jac.body_damping[b];
      Me.bottomRightCorner<3, 3>() += hg * hg * jac.body_stiffness[b];
      A.block<6, 6>(o, o) = Me;
      rhs.segment<3>(o) = iw.Fb[b];
      rhs.segment<3>(o + 3) = iw.Mb[b];
    }
    for (std::size_t i = 0; i < att_[l].size(); ++i) {
      const auto o = static_cast<Eigen::Index>(att_[l][i]);
      const auto j = static_cast<std::size_t>(m.cable.attachments[i].joint);
      A.block<3, 3>(o, o) = ws.Ma[j] + hg * jac.joint_damping[j] + hg * hg * jac.joint_stiffness[j];
      rhs.segment<3>(o) = iw.Fa[j];
    }
  }

  /// Inertia and known loads of line l's parts: M x = F - h + sum J^T lambda.
  void put_parts(std::size_t l, Eigen::MatrixXd& A, Eigen::VectorXd& rhs) const {
    if (staged()) return put_stage_parts(l, A, rhs);
    const Model& m = *m_[l];
    const PhysicalState& s = *s_[l];
    const Workspace& ws = *ws_[l];
    for (std::size_t k = 0; k < m.cable.elements.size(); ++k) {
      const auto o = static_cast<Eigen::Index>(el_[l][k]);
      const Vec3& e = s.e[k];
      const Mat3 Mt = element_mass(element(l, k), e);  // m I + ma (I - e e^T) [kg]
      A.block<3, 3>(o, o) = Mt;
      rhs.segment<3>(o) = ws.F[k];
      if (elastic(l, k)) {
        // Uniform rod from its top end to its bottom end (material point at
        // fraction s moves with a_top + s d''): kinetic energy
        // (1/2) a_G^T Mt a_G + (1/24) d'^T Mt d', so the d-equation is
        // (Mt/12) d'' = (M x e)/l - T e + (f_bottom - f_top)/2, the joint
        // forces entering through J^T (half = +-1/2). T: axial force (tension
        // + compression stop) pulling the two ends together [N].
        const double len = s.length_of(m, k), lr = s.length_rate_of(k);
        const double T = k == 0 && ws.winch ? paid_out_tension(element(l, 0), len, lr, s.top_unstretched_rate)
                                            : element_axial_force(m.cable.elements[k], len, lr);
        A.block<3, 3>(o + 3, o + 3) = Mt / 12;
        rhs.segment<3>(o + 3) = ws.Mom[k].cross(e) / len - T * e;
      } else {
        A.block<3, 3>(o + 3, o + 3) = element_rot_inertia(element(l, k)) * (Mat3::Identity() - e * e.transpose());
        rhs.segment<3>(o + 3) = ws.Mom[k];
      }
    }
    for (std::size_t b = 0; b < body_[l].size(); ++b) {
      const auto o = static_cast<Eigen::Index>(body_[l][b]);
      const BodyWork& bw = ws.body[b];
      A.block<6, 6>(o, o) = bw.Mw;
      rhs.segment<3>(o) = bw.Fb - bw.hw.head<3>();
      rhs.segment<3>(o + 3) = bw.Mb - bw.hw.tail<3>();
    }
    for (std::size_t i = 0; i < att_[l].size(); ++i) {
      const auto o = static_cast<Eigen::Index>(att_[l][i]);
      const auto j = static_cast<std::size_t>(m.cable.attachments[i].joint);
      A.block<3, 3>(o, o) = ws.Ma[j];
      rhs.segment<3>(o) = ws.Fa[j];
    }
  }

  void solve() {
    std::size_t n = 0;  // rigid-element spin rows: one per element of every line
    for (const Model* m : m_) n += m->cable.elements.size();
    const std::size_t nj = joints_.size();
    const std::size_t N = dofs_ + 3 * nj + n;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N));
    for (std::size_t l = 0; l < m_.size(); ++l) put_parts(l, A, rhs);
    // Joints: the part below receives +lambda, the one above -lambda; the
    // acceleration rows say both points move together.
    for (std::size_t j = 0; j < nj; ++j) {
      const std::size_t row = dofs_ + 3 * j;
      Eigen::MatrixXd Jrow = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(N));
      put_point(Jrow, 0, 0, joints_[j].below, +1);
      put_point(Jrow, 0, 0, joints_[j].above, -1);
      A.middleRows(static_cast<Eigen::Index>(row), 3) += Jrow;
      A.middleCols(static_cast<Eigen::Index>(row), 3) -= Jrow.transpose();
      rhs.segment<3>(static_cast<Eigen::Index>(row)) = joints_[j].above.c - joints_[j].below.c;
    }
    // Tension-controlled drum: the sheave's material moves with L''
    // (coefficient sheave_u_), and M_d L'' = T - T_set - c L' with the
    // tension at the sheave T = -e_1 . f_0 (f_0: the force on the cable).
    if (drum_ >= 0) {
      const auto d = static_cast<Eigen::Index>(drum_);
      const auto row = static_cast<Eigen::Index>(dofs_ + 3 * sheave_joint_);
      A.block<3, 1>(row, d) -= sheave_u_;
      A(d, d) = m_[0]->winch.drum_inertia;
      A.block<1, 3>(d, row) = s_[0]->e[0].transpose();
      rhs(d) = -m_[0]->winch.tension - m_[0]->winch.damping * pay_rate_;
    }
    // No spin about a rigid element's own axis.
    std::size_t row = dofs_ + 3 * nj;
    for (std::size_t l = 0; l < m_.size(); ++l)
      for (std::size_t k = 0; k < m_[l]->cable.elements.size(); ++k, ++row) {
        const auto r = static_cast<Eigen::Index>(row), o = static_cast<Eigen::Index>(el_[l][k]);
        if (elastic(l, k)) {
          A(r, r) = 1;  // unused row
          continue;
        }
        A.block<1, 3>(r, o + 3) = s_[l]->e[k].transpose();
        A.block<3, 1>(o + 3, r) = -s_[l]->e[k];
      }
    const Eigen::VectorXd z = A.fullPivLu().solve(rhs);
    x_ = z.head(static_cast<Eigen::Index>(dofs_));
    lambda_ = z.segment(static_cast<Eigen::Index>(dofs_), static_cast<Eigen::Index>(3 * nj));
    if (drum_ >= 0) pay_acc_ = x_(drum_);
    for (std::size_t l = 0; l < m_.size(); ++l) recover(l);
  }

  /// Line l's angular and length accelerations: a rigid element's alpha is
  /// an unknown; an elastic element's follow from d = l e, d'' = l'' e +
  /// 2 l' (w x e) + l (alpha x e) - l |w|^2 e, with d'' the bottom end's
  /// acceleration minus that of its top joint (the tow point under a winch).
  void recover(std::size_t l) {
    const Model& m = *m_[l];
    const PhysicalState& s = *s_[l];
    const std::size_t n = m.cable.elements.size();
    alpha_[l].assign(n, Vec3::Zero());
    length_acc_[l].assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const auto o = static_cast<Eigen::Index>(el_[l][k]);
      if (!elastic(l, k)) {
        alpha_[l][k] = x_.segment<3>(o + 3);
        continue;
      }
      const Vec3 aG = x_.segment<3>(o), dd = x_.segment<3>(o + 3);
      if (staged()) {
        // The stage's d-increment: l' along e, l (z x e) normal to it.
        length_acc_[l][k] = s.e[k].dot(dd);
        alpha_[l][k] = s.e[k].cross(dd) / s.length_of(m, k);
        continue;
      }
      const Vec3 a_bottom = aG + 0.5 * dd;
      const Vec3 a_joint = k == 0 && l == 0 && ws_[0]->winch ? a0_[0] : Vec3(aG - 0.5 * dd);
      const Vec3 d2 = a_bottom - a_joint;  // d_k'' [m/s^2]
      const Vec3& e = s.e[k];
      const Vec3& w = s.w[k];
      const double len = s.length_of(m, k), lr = s.length_rate_of(k);
      length_acc_[l][k] = e.dot(d2) + len * w.squaredNorm();
      alpha_[l][k] = e.cross(d2 - length_acc_[l][k] * e - 2 * lr * w.cross(e) + len * w.squaredNorm() * e) / len;
    }
  }

  struct Joint {
    Point above, below;
  };
  std::vector<const Model*> m_;
  std::vector<LineTop> tops_;
  std::vector<const PhysicalState*> s_;
  std::vector<const Workspace*> ws_;
  std::vector<Vec3> a0_;
  Stage stage_;
  std::size_t dofs_ = 0;
  std::vector<std::vector<int>> el_, body_, att_;
  std::vector<Point> end_point_;  // per line: the point at its cable end (after an attachment there)
  std::vector<Joint> joints_;
  std::vector<std::size_t> loop_joint_;  // per loop: its joint
  int drum_ = -1;                        // offset of the unknown L'' (tension winch), -1 = none
  std::size_t sheave_joint_ = 0;         // the joint at the winch's sheave
  Vec3 sheave_c_ = Vec3::Zero();         // sheave material's acceleration minus a_0, without L'' [m/s^2]
  Vec3 sheave_u_ = Vec3::Zero();         // its coefficient of L'' [-]
  double pay_rate_ = 0, pay_acc_ = 0;    // winch L' [m/s], L'' [m/s^2]
  Eigen::VectorXd x_, lambda_;
  std::vector<std::vector<Vec3>> alpha_;         // [rad/s^2]
  std::vector<std::vector<double>> length_acc_;  // [m/s^2]
};

}  // namespace towsim::testing
