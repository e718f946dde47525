// The O(n) recursion on every topology of the chain (sections, an in-line
// body, attachments, an end body) against a slow, independent reference: the
// parts' Newton-Euler equations with one Lagrange multiplier per ball joint,
// assembled into one dense KKT system and solved by full-pivot LU. Both use
// the same load models (compute_loads); they differ in everything else, so
// agreement to round-off proves the recursion's algebra on the new topology.
#include <gtest/gtest.h>

#include <cstdio>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

/// The dense reference: unknowns are each part's accelerations (element and
/// body: a of its reference point and alpha; attachment: a), one force per
/// joint and one spin multiplier per element (alpha . e = 0).
class KktReference {
 public:
  KktReference(const Model& m, const PhysicalState& s, const Workspace& ws, const Vec3& a0) : m_(m), s_(s), ws_(ws) {
    const std::size_t n = m.cable.elements.size();
    // Parts: elements, bodies, attachments (in that order of unknowns).
    for (std::size_t k = 0; k < n; ++k) el_.push_back(add_part(6));
    for (std::size_t b = 0; b < m.bodies.size(); ++b) body_.push_back(add_part(6));
    for (std::size_t i = 0; i < m.cable.attachments.size(); ++i) att_.push_back(add_part(3));
    build_joints(a0);
    solve();
  }
  Vec3 alpha(std::size_t k) const { return x_.segment<3>(el_[k] + 3); }
  Vec3 alpha_body(std::size_t b) const { return x_.segment<3>(body_[b] + 3); }
  /// Force through a joint on the part below it (by the joint's index in order).
  Vec3 force(std::size_t j) const { return lambda_.segment<3>(3 * j); }
  std::size_t tow_joint = 0;                        // the tow point's joint
  std::vector<std::size_t> joint_of_node;           // joint below each cable joint k (k = 0..n) giving f_k
  std::vector<std::size_t> upper_link, lower_link;  // per body

 private:
  /// A point on a part: its part's offset, position r from the reference
  /// point, and centripetal acceleration w x (w x r).
  struct Point {
    int part = -1;  // offset of the part's unknowns, -1 = the imposed tow point
    int dof = 6;
    Vec3 r = Vec3::Zero();
    Vec3 c = Vec3::Zero();
  };
  int add_part(int dof) {
    const int o = static_cast<int>(dofs_);
    dofs_ += static_cast<std::size_t>(dof);
    return o;
  }
  Point element_point(std::size_t k, double side) const {
    const double L = m_.cable.elements[k].length;
    const Vec3 r = side * 0.5 * L * s_.e[k];
    return {el_[k], 6, r, s_.w[k].cross(s_.w[k].cross(r))};
  }
  Point body_point(std::size_t b, const Vec3& r) const {
    const Vec3& w = ws_.body[b].w;
    return {body_[b], 6, r, w.cross(w.cross(r))};
  }
  Point attachment_point(std::size_t i) const { return {att_[i], 3, Vec3::Zero(), Vec3::Zero()}; }
  /// The part hanging from joint k (k = 1..n-1 below an element): attachment,
  /// then the element below.
  void link(const Point& above, const Point& below) { joints_.push_back({above, below}); }

  void build_joints(const Vec3& a0) {
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
      if (k == 0) above.c = a0;  // imposed acceleration of the tow point
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
      if (k < n) link(above, element_point(k, -1));
    }
  }

  /// Rows of J for a point: a_X = J x + c, J = [I, -[r]x] (or I for a particle).
  void put_point(Eigen::MatrixXd& A, std::size_t row, std::size_t col_base, const Point& p, double sign) {
    if (p.part < 0) return;
    const auto c = col_base + static_cast<std::size_t>(p.part);
    A.block<3, 3>(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c)) += sign * Mat3::Identity();
    if (p.dof == 6) A.block<3, 3>(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(c + 3)) -= sign * skew(p.r);
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
      A.block<3, 3>(o, o) = ws_.Mt[k];
      A.block<3, 3>(o + 3, o + 3) = element_rot_inertia(m_.cable.elements[k]) * (Mat3::Identity() - e * e.transpose());
      rhs.segment<3>(o) = ws_.F[k];
      rhs.segment<3>(o + 3) = ws_.Mom[k];
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
    // No spin about an element's own axis.
    for (std::size_t k = 0; k < n; ++k) {
      const auto row = static_cast<Eigen::Index>(dofs_ + 3 * nj + k), o = static_cast<Eigen::Index>(el_[k]);
      A.block<1, 3>(row, o + 3) = s_.e[k].transpose();
      A.block<3, 1>(o + 3, row) = -s_.e[k];
    }
    const Eigen::VectorXd z = A.fullPivLu().solve(rhs);
    x_ = z.head(static_cast<Eigen::Index>(dofs_));
    lambda_ = z.segment(static_cast<Eigen::Index>(dofs_), static_cast<Eigen::Index>(3 * nj));
  }

  struct Joint {
    Point above, below;
  };
  const Model& m_;
  const PhysicalState& s_;
  const Workspace& ws_;
  std::size_t dofs_ = 0;
  std::vector<int> el_, body_, att_;
  std::vector<Joint> joints_;
  Eigen::VectorXd x_, lambda_;
};

struct ChainCase {
  int n_top, n_low;
  bool current;
  double EI = 0;  // bending stiffness of every element [N m^2] (joint springs: couples in ws.Mom)
};

class ChainReference : public ::testing::TestWithParam<ChainCase> {};

// Every acceleration and joint force of the recursion equals the KKT
// solution. Tolerance 1e-9 relative to the largest force (and to the largest
// angular acceleration): the dense LU of a system of up to ~200 unknowns
// with condition numbers ~1e6 loses ~1e-10; a wrong term would show at
// O(1e-2) or more.
TEST_P(ChainReference, RecursionEqualsDenseMultiplierSolution) {
  const ChainCase c = GetParam();
  Model m = testing::two_part_model(c.n_top, c.n_low);
  if (c.current) {
    m.fluid.current_depth = {0, 40, 300};
    m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.4, 0.1, 0), Vec3(0.1, 0, 0)};
  }
  for (Element& el : m.cable.elements) el.bending_stiffness = c.EI;
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  std::mt19937 rng(77 + c.n_top);
  Workspace ws(m);
  double worst_f = 0, worst_a = 0;
  for (int trial = 0; trial < 4; ++trial) {
    PhysicalState s = testing::random_state(m, rng);
    const auto k = tow_kinematics(m.tow, 4.2);
    s.r0 = k.pos, s.v0 = k.vel;
    forward_dynamics(m, s, 4.2, ws);
    const KktReference ref(m, s, ws, k.acc);
    const Accelerations& acc = ws.acc;
    double fs = 1, as = 1;
    for (const Vec3& f : acc.joint_force) fs = std::max(fs, f.norm());
    for (const Vec3& a : acc.alpha) as = std::max(as, a.norm());
    double ef = (acc.tow_force - ref.force(ref.joint_of_node[0])).norm(), ea = 0;
    for (std::size_t j = 1; j < acc.joint_force.size(); ++j)
      ef = std::max(ef, (acc.joint_force[j] - ref.force(ref.joint_of_node[j])).norm());
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      ef = std::max(ef, (acc.link_force[b] - ref.force(ref.upper_link[b])).norm());
      if (m.bodies[b].inline_body) ef = std::max(ef, (acc.lower_link_force[b] - ref.force(ref.lower_link[b])).norm());
      ea = std::max(ea, (acc.alpha_b[b] - ref.alpha_body(b)).norm());
    }
    for (std::size_t e = 0; e < acc.alpha.size(); ++e) ea = std::max(ea, (acc.alpha[e] - ref.alpha(e)).norm());
    worst_f = std::max(worst_f, ef / fs);
    worst_a = std::max(worst_a, ea / as);
  }
  std::printf("[measured] chain %d+body+%d+sphere, 2 attachments%s: force rel err %.2e, alpha rel err %.2e\n", c.n_top,
              c.n_low, c.current ? ", sheared current" : "", worst_f, worst_a);
  EXPECT_LT(worst_f, 1e-9);
  EXPECT_LT(worst_a, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Topologies, ChainReference,
                         ::testing::Values(ChainCase{3, 4, false}, ChainCase{3, 4, true}, ChainCase{1, 1, false},
                                           ChainCase{12, 20, true}, ChainCase{3, 4, true, 500.0}),
                         [](const auto& i) {
                           return "top" + std::to_string(i.param.n_top) + "_low" + std::to_string(i.param.n_low) +
                                  (i.param.current ? "_current" : "_still") + (i.param.EI > 0 ? "_bending" : "");
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
