// The paper's formulation: dense Lagrange equations in independent angles
// (paper sections 2-4), assembled in Kane's form (docs/theory.md §5.1).
#include "towsim/dynamics/paper.hpp"

#include <cmath>
#include <stdexcept>

#include "towsim/dynamics/dynamics.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim {

namespace {

constexpr double kElementSwitch = 0.9;  // re-chart an element when |cos theta| exceeds this
constexpr double kBodySwitch = 0.3;     // re-chart the body when |cos pitch| falls below this

/// Pole frame with third column `pole`; the identity for the paper's z_g.
Mat3 pole_frame(const Vec3& pole) {
  const Vec3 z = pole.normalized();
  if ((z - Vec3::UnitZ()).norm() < 1e-15) return Mat3::Identity();
  const Vec3 helper = std::abs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 y = z.cross(helper).normalized();
  Mat3 R;
  R << y.cross(z), y, z;
  return R;
}

/// A chart putting e on the equator (theta = pi/2, psi = 0): y' = -e, pole ⊥ e.
Mat3 equator_chart(const Vec3& e) {
  Eigen::Index i;
  e.cwiseAbs().minCoeff(&i);
  const Vec3 pole = e.cross(Vec3::Unit(i)).normalized();
  const Vec3 y = -e;
  Mat3 R;
  R << y.cross(pole), y, pole;
  return R;
}

/// Element angles and rates in a chart, from e and de/dt (R_g).
void element_angles(const Mat3& chart, const Vec3& e, const Vec3& edot, double& th, double& ps, double& thd,
                    double& psd) {
  const Vec3 l = chart.transpose() * e;
  const Vec3 ld = chart.transpose() * edot;
  th = std::acos(std::clamp(l.z(), -1.0, 1.0));
  ps = std::atan2(l.x(), -l.y());
  const double st = std::sin(th), ct = std::cos(th), sp = std::sin(ps), cp = std::cos(ps);
  thd = ld.dot(Vec3(ct * sp, -ct * cp, -st));
  psd = ld.dot(Vec3(st * cp, st * sp, 0)) / (st * st);
}

/// e, de/dtheta, de/dpsi and the velocity part of d2e/dt2 of an element, in R_g.
void element_basis(const Mat3& chart, double th, double ps, double thd, double psd, Vec3& e, Vec3& Et, Vec3& Ep,
                   Vec3& evp) {
  const double st = std::sin(th), ct = std::cos(th), sp = std::sin(ps), cp = std::cos(ps);
  const Vec3 el(st * sp, -st * cp, ct);
  const Vec3 ett = -el;
  const Vec3 etp(ct * cp, ct * sp, 0);
  const Vec3 epp(-st * sp, st * cp, 0);
  e = chart * el;
  Et = chart * Vec3(ct * sp, -ct * cp, -st);
  Ep = chart * Vec3(st * cp, st * sp, 0);
  evp = chart * (ett * thd * thd + 2 * etp * thd * psd + epp * psd * psd);
}

/// Body angular-velocity Jacobian columns a1 (yaw), a2 (pitch), a3 (roll), R_g.
Mat3 body_axes(const Mat3& chart, double yaw, double pitch) {
  const Mat3 Rz = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  const Mat3 Ry = Eigen::AngleAxisd(pitch, Vec3::UnitY()).toRotationMatrix();
  Mat3 A;
  A << chart * Vec3::UnitZ(), chart * Rz * Vec3::UnitY(), chart * Rz * Ry * Vec3::UnitX();
  return A;
}

/// Body angles (yaw, pitch, roll) and their rates in a chart.
void body_angles(const Mat3& chart, const Quat& q, const Vec3& wb, Vec3& ang, Vec3& rate) {
  const Vec3 rpy = roll_pitch_yaw(Quat(chart.transpose() * q.toRotationMatrix()));
  ang = Vec3(rpy.z(), rpy.y(), rpy.x());
  rate = body_axes(chart, ang.x(), ang.y()).lu().solve(wb);
}

/// Dense symmetric solve with one step of iterative refinement (the
/// generalized mass of a long chain is ill-conditioned; refinement recovers
/// the digits LDLT loses).
Eigen::VectorXd solve_refined(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  Eigen::VectorXd x = ldlt.solve(b);
  x += ldlt.solve(b - A * x);
  return x;
}

}  // namespace

int paper_angle_count(const Model& model) { return 2 * model.cable.n() + 3 * static_cast<int>(model.bodies.size()); }

PaperWorkspace::PaperWorkspace(const Model& model) : ws(model) {
  // The paper's form covers one cable and at most one body at its end.
  if (!model.cable.attachments.empty() || model.bodies.size() > 1 ||
      (!model.bodies.empty() && model.bodies[0].inline_body))
    throw std::invalid_argument("the paper formulation has no attachments and at most one body, at the end");
  const int N = 3 + paper_angle_count(model);
  const std::size_t n = model.cable.elements.size();
  M.resize(N, N);
  S.resize(N);
  JP.resize(3, N);
  JG.resize(3, N);
  Jw.resize(3, N);
  J6.resize(6, N);
  qdd.resize(N - 3);
  Et.resize(n);
  Ep.resize(n);
  evp.resize(n);
  acc.alpha.resize(n);
  acc.alpha_b.resize(model.bodies.size());
  acc.link_force.resize(model.bodies.size());
  acc.lower_link_force.resize(model.bodies.size());
}

PaperState to_paper(const Model& model, const PhysicalState& s, const Vec3& pole) {
  const int n = model.cable.n();
  PaperState p;
  p.r0 = s.r0;
  p.v0 = s.v0;
  p.q.resize(paper_angle_count(model));
  p.qd.resize(p.q.size());
  p.chart.assign(n, pole_frame(pole));
  for (int k = 0; k < n; ++k) {
    if (std::abs((p.chart[k].transpose() * s.e[k]).z()) > kElementSwitch) p.chart[k] = equator_chart(s.e[k]);
    element_angles(p.chart[k], s.e[k], s.w[k].cross(s.e[k]), p.q[2 * k], p.q[2 * k + 1], p.qd[2 * k], p.qd[2 * k + 1]);
  }
  if (!model.bodies.empty()) {
    const BodyState& bs = s.bodies[0];
    Vec3 ang, rate;
    body_angles(p.body_chart, bs.q, bs.w, ang, rate);
    if (std::abs(std::cos(ang.y())) < kBodySwitch) {
      p.body_chart = bs.q.toRotationMatrix();
      body_angles(p.body_chart, bs.q, bs.w, ang, rate);
    }
    p.q.tail<3>() = ang;
    p.qd.tail<3>() = rate;
  }
  return p;
}

PaperState to_paper_in_charts(const Model& model, const PhysicalState& s, const PaperState& charts) {
  PaperState p = charts;
  p.r0 = s.r0;
  p.v0 = s.v0;
  for (int k = 0; k < model.cable.n(); ++k)
    element_angles(p.chart[k], s.e[k], s.w[k].cross(s.e[k]), p.q[2 * k], p.q[2 * k + 1], p.qd[2 * k], p.qd[2 * k + 1]);
  if (!model.bodies.empty()) {
    Vec3 ang, rate;
    body_angles(p.body_chart, s.bodies[0].q, s.bodies[0].w, ang, rate);
    p.q.tail<3>() = ang;
    p.qd.tail<3>() = rate;
  }
  return p;
}

PhysicalState from_paper(const Model& model, const PaperState& p) {
  const int n = model.cable.n();
  PhysicalState s = PhysicalState::hanging(model);
  s.r0 = p.r0;
  s.v0 = p.v0;
  for (int k = 0; k < n; ++k) {
    Vec3 e, Et, Ep, evp;
    element_basis(p.chart[k], p.q[2 * k], p.q[2 * k + 1], p.qd[2 * k], p.qd[2 * k + 1], e, Et, Ep, evp);
    s.e[k] = e;
    s.w[k] = e.cross(Et * p.qd[2 * k] + Ep * p.qd[2 * k + 1]);
  }
  if (!model.bodies.empty()) {
    const Vec3 ang = p.q.tail<3>();
    s.bodies[0].q = Quat(p.body_chart * quat_from_rpy(ang.z(), ang.y(), ang.x()).toRotationMatrix());
    s.bodies[0].w = body_axes(p.body_chart, ang.x(), ang.y()) * p.qd.tail<3>();
  }
  return s;
}

int rechart(const Model& model, PaperState& p) {
  const int n = model.cable.n();
  int changed = 0;
  const PhysicalState s = from_paper(model, p);
  for (int k = 0; k < n; ++k) {
    if (std::abs(std::cos(p.q[2 * k])) <= kElementSwitch) continue;
    p.chart[k] = equator_chart(s.e[k]);
    element_angles(p.chart[k], s.e[k], s.w[k].cross(s.e[k]), p.q[2 * k], p.q[2 * k + 1], p.qd[2 * k], p.qd[2 * k + 1]);
    ++changed;
  }
  if (!model.bodies.empty() && std::abs(std::cos(p.q[2 * n + 1])) < kBodySwitch) {
    p.body_chart = s.bodies[0].q.toRotationMatrix();
    Vec3 ang, rate;
    body_angles(p.body_chart, s.bodies[0].q, s.bodies[0].w, ang, rate);
    p.q.tail<3>() = ang;
    p.qd.tail<3>() = rate;
    ++changed;
  }
  return changed;
}

void paper_dynamics(const Model& model, const PaperState& p, double t, PaperWorkspace& pw) {
  const int n = model.cable.n();
  const int N = 3 + paper_angle_count(model);
  const auto& els = model.cable.elements;
  Workspace& ws = pw.ws;
  // Loads need the physical state (same load code as the default formulation).
  const PhysicalState s = from_paper(model, p);
  compute_kinematics(model, s, ws);
  compute_loads(model, s, t, ws);

  // Kane's form: M = sum J^T M_i J, S = sum J^T (F_i - M_i (dJ/dt) q').
  pw.M.setZero();
  pw.S.setZero();
  pw.JP.setZero();
  pw.JP.leftCols<3>().setIdentity();
  Vec3 aP = Vec3::Zero();  // velocity part of the current joint's acceleration
  for (int k = 0; k < n; ++k) {
    const double L = els[k].length, Ir = element_rot_inertia(els[k]);
    Vec3 e;
    element_basis(p.chart[k], p.q[2 * k], p.q[2 * k + 1], p.qd[2 * k], p.qd[2 * k + 1], e, pw.Et[k], pw.Ep[k],
                  pw.evp[k]);
    const int ct = 3 + 2 * k, cp = ct + 1;
    // Centre G_k: J_G = J_P + L/2 [Et Ep]; rotation: omega = e x de/dt.
    pw.JG = pw.JP;
    pw.JG.col(ct) += 0.5 * L * pw.Et[k];
    pw.JG.col(cp) += 0.5 * L * pw.Ep[k];
    const Vec3 aG = aP + 0.5 * L * pw.evp[k];
    pw.Jw.setZero();
    pw.Jw.col(ct) = e.cross(pw.Et[k]);
    pw.Jw.col(cp) = e.cross(pw.Ep[k]);
    const Vec3 aw = e.cross(pw.evp[k]);
    const Mat3& Mt = ws.Mt[k];
    pw.M.noalias() += pw.JG.transpose() * Mt * pw.JG;
    pw.M.noalias() += Ir * pw.Jw.transpose() * pw.Jw;
    pw.S.noalias() += pw.JG.transpose() * (ws.F[k] - Mt * aG) + pw.Jw.transpose() * (ws.Mom[k] - Ir * aw);
    // Next joint.
    pw.JP.col(ct) += L * pw.Et[k];
    pw.JP.col(cp) += L * pw.Ep[k];
    aP += L * pw.evp[k];
  }
  Vec3 aO = Vec3::Zero(), ab = Vec3::Zero();
  if (!model.bodies.empty()) {
    const BodyWork& bw = ws.body[0];
    // Body: v_O = v_Q + [r]x omega, omega = A (yaw, pitch, roll)'.
    const Vec3 ang = p.q.tail<3>(), rate = p.qd.tail<3>();
    const Mat3 A = body_axes(p.body_chart, ang.x(), ang.y());
    const Vec3 w1 = rate.x() * A.col(0), w2 = w1 + rate.y() * A.col(1);
    ab = rate.y() * w1.cross(A.col(1)) + rate.z() * w2.cross(A.col(2));
    const Vec3 r = bw.rQ, w = bw.w;
    aO = aP + ab.cross(-r) + w.cross(w.cross(-r));
    pw.J6.setZero();
    pw.J6.topRows<3>() = pw.JP;
    pw.J6.block<3, 3>(0, N - 3) += skew(r) * A;
    pw.J6.block<3, 3>(3, N - 3) = A;
    Vec6 load, avp;
    load << bw.Fb, bw.Mb;
    avp << aO, ab;
    pw.M.noalias() += pw.J6.transpose() * bw.Mw * pw.J6;
    pw.S.noalias() += pw.J6.transpose() * (load - bw.hw - bw.Mw * avp);
  }

  // Solve: tow motion imposed -> F_R unknown (paper section 3); else F_R given.
  Accelerations& acc = pw.acc;
  const int na = N - 3;
  if (model.tow.mode == Tow::Mode::Motion) {
    acc.a0 = tow_kinematics(model.tow, t).acc;
    const Eigen::VectorXd rhs = pw.S.tail(na) - pw.M.bottomLeftCorner(na, 3) * acc.a0;
    pw.qdd = solve_refined(pw.M.bottomRightCorner(na, na), rhs);
    acc.tow_force = pw.M.topRightCorner(3, na) * pw.qdd + pw.M.topLeftCorner<3, 3>() * acc.a0 - pw.S.head<3>();
  } else {
    acc.tow_force = tow_force(model.tow, t);
    Eigen::VectorXd rhs = pw.S;
    rhs.head<3>() += acc.tow_force;
    const Eigen::VectorXd x = solve_refined(pw.M, rhs);
    acc.a0 = x.head<3>();
    pw.qdd = x.tail(na);
  }
  // Physical accelerations and the link force.
  for (int k = 0; k < n; ++k) {
    const Vec3 edd = pw.Et[k] * pw.qdd[2 * k] + pw.Ep[k] * pw.qdd[2 * k + 1] + pw.evp[k];
    acc.alpha[k] = s.e[k].cross(edd);
  }
  if (!model.bodies.empty()) {
    const BodyWork& bw = ws.body[0];
    Vec6 a6 = pw.J6.rightCols(na) * pw.qdd + pw.J6.leftCols<3>() * acc.a0;
    a6.head<3>() += aO;
    a6.tail<3>() += ab;
    acc.alpha_b[0] = a6.tail<3>();
    acc.link_force[0] = bw.Mw.topRows<3>() * a6 + bw.hw.head<3>() - bw.Fb;
    acc.lower_link_force[0].setZero();
  }
}

}  // namespace towsim
