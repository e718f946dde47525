// The O(n) recursion on every topology of the chain (sections, an in-line
// body, attachments, an end body, rigid and elastic elements, a winch's
// paid-out top element) against a slow, independent reference: the parts'
// Newton-Euler equations with one Lagrange multiplier per ball joint,
// assembled into one dense KKT system and solved by full-pivot LU. Both use
// the same load models (compute_loads, the axial force laws); they differ in
// everything else, so agreement to round-off proves the recursion's algebra
// on the new topology.
#include <gtest/gtest.h>

#include <cstdio>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/elastic.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

/// The dense reference: unknowns are each part's accelerations (rigid
/// element and body: a of its reference point and alpha; elastic element:
/// a of its centre G and d'', its bottom end's acceleration relative to its
/// top end; attachment: a), one force per joint, one spin multiplier per
/// rigid element (alpha . e = 0) and, with a tension-controlled winch, the
/// pay-out acceleration.
class KktReference {
 public:
  KktReference(const Model& m, const PhysicalState& s, const Workspace& ws, const Vec3& a0, double t)
      : m_(m), s_(s), ws_(ws), a0_(a0) {
    const std::size_t n = m.cable.elements.size();
    // Parts: elements, bodies, attachments (in that order of unknowns).
    for (std::size_t k = 0; k < n; ++k) el_.push_back(add_part(6));
    for (std::size_t b = 0; b < m.bodies.size(); ++b) body_.push_back(add_part(6));
    for (std::size_t i = 0; i < m.cable.attachments.size(); ++i) att_.push_back(add_part(3));
    winch_setup(t);
    build_joints();
    solve();
  }
  Vec3 alpha(std::size_t k) const { return alpha_[k]; }
  double length_acc(std::size_t k) const { return length_acc_[k]; }
  Vec3 alpha_body(std::size_t b) const { return x_.segment<3>(body_[b] + 3); }
  /// The winch's pay-out acceleration (l_1'' rigid, L_1'' elastic) [m/s^2].
  double pay_acc() const { return pay_acc_; }
  /// Force through a joint on the part below it (by the joint's index in order).
  Vec3 force(std::size_t j) const { return lambda_.segment<3>(3 * j); }
  std::size_t tow_joint = 0;                        // the tow point's joint
  std::vector<std::size_t> joint_of_node;           // joint below each cable joint k (k = 0..n) giving f_k
  std::vector<std::size_t> upper_link, lower_link;  // per body

 private:
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
  const Element& element(std::size_t k) const { return current_element(m_, ws_, k); }
  bool elastic(std::size_t k) const { return is_elastic(m_.cable.elements[k]); }
  Point element_point(std::size_t k, double side) const {
    if (elastic(k)) return {el_[k], 6, Vec3::Zero(), Vec3::Zero(), 0.5 * side};
    const double L = s_.length_of(m_, k);  // current length [m]
    const Vec3 r = side * 0.5 * L * s_.e[k];
    return {el_[k], 6, r, s_.w[k].cross(s_.w[k].cross(r))};
  }
  Point body_point(std::size_t b, const Vec3& r) const {
    const Vec3& w = ws_.body[b].w;
    return {body_[b], 6, r, w.cross(w.cross(r))};
  }
  Point attachment_point(std::size_t i) const { return {att_[i], 3, Vec3::Zero(), Vec3::Zero()}; }
  void link(const Point& above, const Point& below) { joints_.push_back({above, below}); }

  /// Winch: the top element's material at the sheave. Rigid top (material
  /// fixed to P_1 = P_0 + l e_1, at the sheave at distance l from P_1):
  /// a = a_0 + l'' e_1 + 2 l' (w_1 x e_1). Elastic top (unstretched
  /// coordinate sigma from P_1, the point at P_0 + q e_1 with
  /// q = l (1 - sigma / L_1), sigma = L_1 at the sheave, q = 0):
  /// a = a_0 + q'' e_1 + 2 q' (w_1 x e_1), q' = (l / L_1) L_1',
  /// q'' = (l / L_1) L_1'' + 2 l' L_1' / L_1 - 2 l L_1'^2 / L_1^2.
  /// sheave_c_ is the part without L'', sheave_u_ the coefficient of L''.
  void winch_setup(double t) {
    if (!ws_.winch) return;
    const Vec3& e1 = s_.e[0];
    const Vec3 wxe = s_.w[0].cross(e1);
    const double l = s_.length_of(m_, 0), lr = s_.length_rate_of(0);
    double qd = lr, qdd0 = 0;  // q' [m/s], q'' without the L'' term [m/s^2]
    if (elastic(0)) {
      const double Lu = s_.top_unstretched, Lr = s_.top_unstretched_rate;
      qd = l / Lu * Lr;
      qdd0 = 2 * lr * Lr / Lu - 2 * l * Lr * Lr / (Lu * Lu);
      sheave_u_ = l / Lu * e1;
      pay_rate_ = Lr;
    } else {
      sheave_u_ = e1;
      pay_rate_ = lr;
    }
    sheave_c_ = qdd0 * e1 + 2 * qd * wxe;
    if (m_.winch.mode == Winch::Mode::Imposed) {
      pay_acc_ = winch_kinematics(m_.winch, t).acc;
      sheave_c_ += pay_acc_ * sheave_u_;
    } else {
      drum_ = static_cast<int>(dofs_);
      dofs_ += 1;
    }
  }

  void build_joints() {
    const std::size_t n = m_.cable.elements.size();
    joint_of_node.assign(n + 1, 0);
    upper_link.assign(m_.bodies.size(), 0);
    lower_link.assign(m_.bodies.size(), 0);
    std::vector<int> att_at(n + 1, -1);
    for (std::size_t i = 0; i < m_.cable.attachments.size(); ++i)
      att_at[static_cast<std::size_t>(m_.cable.attachments[i].joint)] = static_cast<int>(i);
    // Joint k: what is above it (tow point or the bottom of element k), then
    // an attachment, a body, or the top of element k+1.
    for (std::size_t k = 0; k <= n; ++k) {
      Point above = k == 0 ? Point{} : element_point(k - 1, +1);
      if (k == 0) above.c = a0_;  // imposed acceleration of the tow point
      joint_of_node[k] = joints_.size();
      if (att_at[k] >= 0) {
        const Point p = attachment_point(static_cast<std::size_t>(att_at[k]));
        link(above, p);
        above = p;
      }
      const int b = ws_.body_at[k];
      if (b >= 0) {
        const auto bi = static_cast<std::size_t>(b);
        upper_link[bi] = joints_.size();
        link(above, body_point(bi, ws_.body[bi].rQ));
        if (!m_.bodies[bi].inline_body) continue;
        above = body_point(bi, ws_.body[bi].rQ2);
        lower_link[bi] = joints_.size();
        joint_of_node[k] = joints_.size();
      }
      if (k == 0 && ws_.winch) {
        // The top element hangs from its material at the sheave.
        sheave_joint_ = joints_.size();
        above.c += sheave_c_;
      }
      if (k < n) link(above, element_point(k, -1));
    }
  }

  /// Rows of J for a point: a_X = J x + c, J = [I, -[r]x] (rigid),
  /// [I, half I] (elastic) or I (particle).
  void put_point(Eigen::MatrixXd& A, std::size_t row, std::size_t col_base, const Point& p, double sign) {
    if (p.part < 0) return;
    const auto c = col_base + static_cast<std::size_t>(p.part);
    const auto r = static_cast<Eigen::Index>(row), c0 = static_cast<Eigen::Index>(c);
    A.block<3, 3>(r, c0) += sign * Mat3::Identity();
    if (p.half != 0)
      A.block<3, 3>(r, c0 + 3) += sign * p.half * Mat3::Identity();
    else if (p.dof == 6)
      A.block<3, 3>(r, c0 + 3) -= sign * skew(p.r);
  }

  void solve() {
    const std::size_t n = m_.cable.elements.size(), nj = joints_.size();
    const std::size_t N = dofs_ + 3 * nj + n;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N));
    // Inertia and known loads of each part: M x = F - h + sum J^T lambda.
    for (std::size_t k = 0; k < n; ++k) {
      const auto o = static_cast<Eigen::Index>(el_[k]);
      const Vec3& e = s_.e[k];
      const Mat3 Mt = element_mass(element(k), e);  // m I + ma (I - e e^T) [kg]
      A.block<3, 3>(o, o) = Mt;
      rhs.segment<3>(o) = ws_.F[k];
      if (elastic(k)) {
        // Uniform rod from its top end to its bottom end (material point at
        // fraction s moves with a_top + s d''): kinetic energy
        // (1/2) a_G^T Mt a_G + (1/24) d'^T Mt d', so the d-equation is
        // (Mt/12) d'' = (M x e)/l - T e + (f_bottom - f_top)/2, the joint
        // forces entering through J^T (half = +-1/2). T: axial force (tension
        // + compression stop) pulling the two ends together [N].
        const double l = s_.length_of(m_, k), lr = s_.length_rate_of(k);
        const double T = k == 0 && ws_.winch ? paid_out_tension(element(0), l, lr, s_.top_unstretched_rate)
                                             : element_axial_force(m_.cable.elements[k], l, lr);
        A.block<3, 3>(o + 3, o + 3) = Mt / 12;
        rhs.segment<3>(o + 3) = ws_.Mom[k].cross(e) / l - T * e;
      } else {
        A.block<3, 3>(o + 3, o + 3) = element_rot_inertia(element(k)) * (Mat3::Identity() - e * e.transpose());
        rhs.segment<3>(o + 3) = ws_.Mom[k];
      }
    }
    for (std::size_t b = 0; b < body_.size(); ++b) {
      const auto o = static_cast<Eigen::Index>(body_[b]);
      const BodyWork& bw = ws_.body[b];
      A.block<6, 6>(o, o) = bw.Mw;
      rhs.segment<3>(o) = bw.Fb - bw.hw.head<3>();
      rhs.segment<3>(o + 3) = bw.Mb - bw.hw.tail<3>();
    }
    for (std::size_t i = 0; i < att_.size(); ++i) {
      const auto o = static_cast<Eigen::Index>(att_[i]);
      const auto j = static_cast<std::size_t>(m_.cable.attachments[i].joint);
      A.block<3, 3>(o, o) = ws_.Ma[j];
      rhs.segment<3>(o) = ws_.Fa[j];
    }
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
      A(d, d) = m_.winch.drum_inertia;
      A.block<1, 3>(d, row) = s_.e[0].transpose();
      rhs(d) = -m_.winch.tension - m_.winch.damping * pay_rate_;
    }
    // No spin about a rigid element's own axis.
    for (std::size_t k = 0; k < n; ++k) {
      const auto row = static_cast<Eigen::Index>(dofs_ + 3 * nj + k), o = static_cast<Eigen::Index>(el_[k]);
      if (elastic(k)) {
        A(row, row) = 1;  // unused row
        continue;
      }
      A.block<1, 3>(row, o + 3) = s_.e[k].transpose();
      A.block<3, 1>(o + 3, row) = -s_.e[k];
    }
    const Eigen::VectorXd z = A.fullPivLu().solve(rhs);
    x_ = z.head(static_cast<Eigen::Index>(dofs_));
    lambda_ = z.segment(static_cast<Eigen::Index>(dofs_), static_cast<Eigen::Index>(3 * nj));
    if (drum_ >= 0) pay_acc_ = x_(drum_);
    // Angular and length accelerations: a rigid element's alpha is an
    // unknown; an elastic element's follow from d = l e, d'' = l'' e +
    // 2 l' (w x e) + l (alpha x e) - l |w|^2 e, with d'' the bottom end's
    // acceleration minus that of its top joint (the tow point under a winch).
    alpha_.assign(n, Vec3::Zero());
    length_acc_.assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const auto o = static_cast<Eigen::Index>(el_[k]);
      if (!elastic(k)) {
        alpha_[k] = x_.segment<3>(o + 3);
        continue;
      }
      const Vec3 aG = x_.segment<3>(o), dd = x_.segment<3>(o + 3);
      const Vec3 a_bottom = aG + 0.5 * dd;
      const Vec3 a_joint = k == 0 && ws_.winch ? a0_ : Vec3(aG - 0.5 * dd);
      const Vec3 d2 = a_bottom - a_joint;  // d_k'' [m/s^2]
      const Vec3& e = s_.e[k];
      const Vec3& w = s_.w[k];
      const double l = s_.length_of(m_, k), lr = s_.length_rate_of(k);
      length_acc_[k] = e.dot(d2) + l * w.squaredNorm();
      alpha_[k] = e.cross(d2 - length_acc_[k] * e - 2 * lr * w.cross(e) + l * w.squaredNorm() * e) / l;
    }
  }

  struct Joint {
    Point above, below;
  };
  const Model& m_;
  const PhysicalState& s_;
  const Workspace& ws_;
  Vec3 a0_;
  std::size_t dofs_ = 0;
  std::vector<int> el_, body_, att_;
  std::vector<Joint> joints_;
  int drum_ = -1;                      // offset of the unknown L'' (tension winch), -1 = none
  std::size_t sheave_joint_ = 0;       // the joint at the winch's sheave
  Vec3 sheave_c_ = Vec3::Zero();       // sheave material's acceleration minus a_0, without L'' [m/s^2]
  Vec3 sheave_u_ = Vec3::Zero();       // its coefficient of L'' [-]
  double pay_rate_ = 0, pay_acc_ = 0;  // winch L' [m/s], L'' [m/s^2]
  Eigen::VectorXd x_, lambda_;
  std::vector<Vec3> alpha_;         // [rad/s^2]
  std::vector<double> length_acc_;  // [m/s^2]
};

/// The winch over the top element in a test case.
enum class WinchCase { None, Imposed, Tension };

struct ChainCase {
  int n_top, n_low;
  bool current;
  double EI = 0;             // bending stiffness of every element [N m^2] (joint springs: couples in ws.Mom)
  bool elastic_top = false;  // upper section elastic
  bool elastic_low = false;  // lower section elastic
  WinchCase winch = WinchCase::None;
};

class ChainReference : public ::testing::TestWithParam<ChainCase> {};

// Every acceleration and joint force of the recursion, and every length and
// pay-out acceleration, equals the KKT solution. Tolerance 1e-9 relative to
// the largest force (and to the largest angular and length acceleration):
// the dense LU of a system of up to ~350 unknowns with condition numbers
// ~1e6 loses ~1e-10 (the axial springs are loads, not inertia: they add no
// stiffness to the system); a wrong inertia, load or pay-out term shows at
// 1e-5 or more.
TEST_P(ChainReference, RecursionEqualsDenseMultiplierSolution) {
  const ChainCase c = GetParam();
  Model m = testing::two_part_model(c.n_top, c.n_low);
  if (c.current) {
    m.fluid.current_depth = {0, 40, 300};
    m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.4, 0.1, 0), Vec3(0.1, 0, 0)};
  }
  for (Element& el : m.cable.elements) el.bending_stiffness = c.EI;
  // Axial stiffness EA [N] and damping c_a [N s] of the elastic sections.
  for (int k = 0; k < m.cable.n(); ++k) {
    Element& el = m.cable.elements[static_cast<std::size_t>(k)];
    const bool top = k < c.n_top;
    if (top ? c.elastic_top : c.elastic_low) el.axial_stiffness = top ? 2e6 : 3e5, el.axial_damping = top ? 4e3 : 900;
  }
  if (c.winch == WinchCase::Imposed) {
    // Pay-out speed ramping from 0.2 to 1.2 m/s over 10 s: L'' = 0.1 m/s^2.
    m.winch.mode = Winch::Mode::Imposed;
    m.winch.nominal_length = m.cable.elements[0].length;
    m.winch.schedule = schedule_from_rate({0, 10}, {0.2, 1.2}, 200.0, 0, m.winch.max_length);
  } else if (c.winch == WinchCase::Tension) {
    m.winch.mode = Winch::Mode::Tension;
    m.winch.nominal_length = m.cable.elements[0].length;
    m.winch.tension = 1500;     // [N]
    m.winch.drum_inertia = 80;  // [kg]
    m.winch.damping = 300;      // [N s/m]
  }
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  std::mt19937 rng(77 + c.n_top);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Workspace ws(m);
  double worst_f = 0, worst_a = 0, worst_l = 0;
  for (int trial = 0; trial < 4; ++trial) {
    PhysicalState s = testing::random_state(m, rng);
    // Element lengths [m] and rates [m/s]: strains from -0.3 % (slack) to
    // +0.7 %, one trial with an element on its compression stop; the winch's
    // top element between 0.6 and 1.4 of its nominal length.
    for (std::size_t k = 0; k < s.length.size(); ++k) {
      const Element& el = m.cable.elements[k];
      if (!is_elastic(el)) continue;
      s.length[k] = el.length * (1.002 + 0.005 * U(rng));
      s.length_rate[k] = 0.3 * U(rng);
    }
    if (trial == 3 && is_elastic(m.cable.elements.back())) s.length.back() = 0.05 * m.cable.elements.back().length;
    if (m.winch.active()) {
      const double L1 = m.cable.elements[0].length * (1.0 + 0.4 * U(rng));
      if (is_elastic(m.cable.elements[0])) {
        s.top_unstretched = L1, s.top_unstretched_rate = 0.8 * U(rng);
        s.length[0] = L1 * (1.002 + 0.005 * U(rng));
      } else {
        s.length[0] = L1;
      }
      s.length_rate[0] = 0.8 * U(rng);
    }
    const auto k = tow_kinematics(m.tow, 4.2);
    s.r0 = k.pos, s.v0 = k.vel;
    forward_dynamics(m, s, 4.2, ws);
    const KktReference ref(m, s, ws, k.acc, 4.2);
    const Accelerations& acc = ws.acc;
    double fs = 1, as = 1, ls = 1;
    for (const Vec3& f : acc.joint_force) fs = std::max(fs, f.norm());
    for (const Vec3& a : acc.alpha) as = std::max(as, a.norm());
    for (const double a : acc.length_acc) ls = std::max(ls, std::abs(a));
    double ef = (acc.tow_force - ref.force(ref.joint_of_node[0])).norm(), ea = 0, el = 0;
    for (std::size_t j = 1; j < acc.joint_force.size(); ++j)
      ef = std::max(ef, (acc.joint_force[j] - ref.force(ref.joint_of_node[j])).norm());
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      ef = std::max(ef, (acc.link_force[b] - ref.force(ref.upper_link[b])).norm());
      if (m.bodies[b].inline_body) ef = std::max(ef, (acc.lower_link_force[b] - ref.force(ref.lower_link[b])).norm());
      ea = std::max(ea, (acc.alpha_b[b] - ref.alpha_body(b)).norm());
    }
    for (std::size_t e = 0; e < acc.alpha.size(); ++e) {
      ea = std::max(ea, (acc.alpha[e] - ref.alpha(e)).norm());
      el = std::max(el, std::abs(acc.length_acc[e] - ref.length_acc(e)));
    }
    // The winch's pay-out acceleration (drum's l_1'' or L_1'').
    if (m.winch.active()) el = std::max(el, std::abs(acc.top_length_acc - ref.pay_acc()));
    worst_f = std::max(worst_f, ef / fs);
    worst_a = std::max(worst_a, ea / as);
    worst_l = std::max(worst_l, el / ls);
  }
  std::printf(
      "[measured] chain %d+body+%d+sphere, 2 attachments%s%s%s%s: force rel err %.2e, alpha rel err %.2e, length acc "
      "rel err %.2e\n",
      c.n_top, c.n_low, c.current ? ", sheared current" : "", c.elastic_top ? ", elastic top section" : "",
      c.elastic_low ? ", elastic lower section" : "",
      c.winch == WinchCase::Imposed   ? ", imposed winch"
      : c.winch == WinchCase::Tension ? ", tension winch"
                                      : "",
      worst_f, worst_a, worst_l);
  EXPECT_LT(worst_f, 1e-9);
  EXPECT_LT(worst_a, 1e-9);
  EXPECT_LT(worst_l, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Topologies, ChainReference,
                         ::testing::Values(ChainCase{3, 4, false}, ChainCase{3, 4, true}, ChainCase{1, 1, false},
                                           ChainCase{12, 20, true}, ChainCase{3, 4, true, 500.0},
                                           ChainCase{3, 4, true, 0.0, true, true},
                                           ChainCase{12, 20, true, 500.0, true, true},
                                           ChainCase{3, 4, true, 0.0, false, true},
                                           ChainCase{3, 4, true, 500.0, true, false},
                                           ChainCase{3, 4, true, 0.0, false, false, WinchCase::Imposed},
                                           ChainCase{3, 4, true, 0.0, false, false, WinchCase::Tension},
                                           ChainCase{3, 4, true, 0.0, true, true, WinchCase::Imposed},
                                           ChainCase{3, 4, true, 500.0, true, false, WinchCase::Tension}),
                         [](const auto& i) {
                           const ChainCase& c = i.param;
                           return "top" + std::to_string(c.n_top) + "_low" + std::to_string(c.n_low) +
                                  (c.current ? "_current" : "_still") + (c.EI > 0 ? "_bending" : "") +
                                  (c.elastic_top ? "_elastictop" : "") + (c.elastic_low ? "_elasticlow" : "") +
                                  (c.winch == WinchCase::Imposed   ? "_winchimposed"
                                   : c.winch == WinchCase::Tension ? "_winchtension"
                                                                   : "");
                         });

}  // namespace
}  // namespace towsim

namespace towsim {
namespace {

// Steady tow of the whole chain (sections, in-line body, attachments, end
// body) in a sheared current: the statics solve converges and the tow force
// equals minus the sum of every part's fluid and gravity loads (the MODEL's
// cross-check of all formulations; nothing accelerates, so no inertia).
// Tolerance 1e-9 of the tow force: the solve stops at angular accelerations
// below 1e-12 rad/s^2; the balance is then exact to round-off.
TEST(ChainStatics, TowForceBalancesEveryLoad) {
  Model m = testing::two_part_model(6, 5);
  // A depressor the solve can settle: a heavy sphere jointed top and bottom
  // (the rich body of the dynamics test has a fin and no stable attitude).
  Body& dep = m.bodies[0];
  const double r = 0.2, mass = 150;
  dep.mass = mass;
  dep.inertia_cg = 0.4 * mass * r * r * Mat3::Identity();
  dep.cg = Vec3::Zero();
  dep.volume = 0, dep.added_mass.setZero(), dep.linear_damping.setZero(), dep.quadratic_damping.setZero();
  dep.link_point = Vec3(0, 0, r);
  dep.lower_link_point = Vec3(0, 0, -r);
  dep.spheres = {{Vec3::Zero(), r, 0.5, 0.5}};
  dep.cylinders.clear();
  dep.surfaces.clear();
  finalize_body(dep, m.fluid);
  m.fluid.current_depth = {0, 40, 300};
  m.fluid.current_velocity = {Vec3(0.3, 0.2, 0), Vec3(0.1, 0.1, 0), Vec3(0, 0, 0)};
  const Vec3 V(2.0, 0.5, 0);
  const StaticsResult res = solve_statics(m, V);
  ASSERT_TRUE(res.converged) << res.message;
  Workspace ws(m);
  PhysicalState s = res.state;
  compute_kinematics(m, s, ws);
  compute_loads(m, s, 0.0, ws);
  Vec3 sum = res.tow_force;
  for (const Vec3& F : ws.F) sum += F;
  for (const Vec3& F : ws.Fa) sum += F;
  for (const BodyWork& bw : ws.body) sum += bw.Fb;
  std::printf("[measured] chain statics: |F_R + sum of loads| / |F_R| = %.2e (%d iterations)\n",
              sum.norm() / res.tow_force.norm(), res.iterations);
  EXPECT_LT(sum.norm(), 1e-9 * res.tow_force.norm());
  // The in-line body is in equilibrium between its two links and its loads.
  const Vec3 body_sum = res.link_force[0] - res.body_force[0] + ws.body[0].Fb;
  EXPECT_LT(body_sum.norm(), 1e-9 * res.tow_force.norm());
}

}  // namespace
}  // namespace towsim
