// Kinematics of the chain and its bodies from a physical state (docs/theory.md §2, §4).
#include <algorithm>
#include <cmath>

#include "towsim/dynamics/state.hpp"

namespace towsim {

Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

PhysicalState PhysicalState::hanging(const Model& model) {
  PhysicalState s;
  s.e.assign(model.cable.elements.size(), -Vec3::UnitZ());
  s.w.assign(model.cable.elements.size(), Vec3::Zero());
  s.bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    s.bodies[b].q = model.bodies[b].initial_attitude;
    // Depth controllers start with no integral, at their initial deflection.
    for (const LiftingSurface& ls : model.bodies[b].surfaces)
      if (ls.depth_control) s.bodies[b].controls.push_back({0.0, ls.depth_control->initial_deflection});
  }
  return s;
}

Workspace::Workspace(const Model& model) {
  const std::size_t n = model.cable.elements.size();
  // Every entry starts at zero: no evaluation ever reads an unset value.
  for (auto* v : {&P, &vP, &b, &Fa}) v->assign(n + 1, Vec3::Zero());
  for (auto* v : {&G, &vG, &edot, &F, &Mom, &c}) v->assign(n, Vec3::Zero());
  Mt.assign(n, Mat3::Zero());
  Ma.assign(n + 1, Mat3::Zero());
  K.assign(n + 1, Mat3::Zero());
  T.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  GT.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  Phi.assign(n, Eigen::Matrix2d::Zero());
  Tr0.assign(n, Eigen::Vector2d::Zero());
  body.resize(model.bodies.size());
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    body[i].deflection.assign(static_cast<std::size_t>(control_count(model.bodies[i])), 0.0);
  body_at.assign(n + 1, -1);
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    body_at[static_cast<std::size_t>(body_joint(model, model.bodies[i]))] = static_cast<int>(i);
  acc.alpha.assign(n, Vec3::Zero());
  acc.joint_force.assign(n + 1, Vec3::Zero());
  acc.alpha_b.assign(model.bodies.size(), Vec3::Zero());
  acc.link_force.assign(model.bodies.size(), Vec3::Zero());
  acc.lower_link_force.assign(model.bodies.size(), Vec3::Zero());
}

bool Workspace::fits(const Model& model) const {
  const std::size_t n = model.cable.elements.size();
  return P.size() == n + 1 && G.size() == n && K.size() == n + 1 && Phi.size() == n &&
         body.size() == model.bodies.size() && acc.alpha.size() == n &&
         acc.link_force.size() == model.bodies.size() && body_at.size() == n + 1 &&
         std::all_of(model.bodies.begin(), model.bodies.end(), [&](const Body& b) {
           const int k = body_joint(model, b);
           return k >= 1 && k <= static_cast<int>(n) && body.size() > static_cast<std::size_t>(body_at[static_cast<std::size_t>(k)]) &&
                  body_at[static_cast<std::size_t>(k)] >= 0;
         });
}

namespace {
/// Body b hangs at joint k from Q = (P, vP): its origin, attitude and, for an
/// in-line body, the lower link Q2 from which the next element hangs.
void body_kinematics(const Body& body, const BodyState& bs, const Vec3& Q, const Vec3& vQ, BodyWork& bw) {
  bw.R = bs.q.toRotationMatrix();
  bw.w = bs.w;
  bw.Q = Q;
  bw.vQ = vQ;
  bw.rQ = bw.R * body.link_point;
  bw.O = Q - bw.rQ;
  bw.vO = vQ - bs.w.cross(bw.rQ);
  bw.rQ2 = bw.R * body.lower_link_point;
  // Controlled surfaces: the servo's deflection within the limits.
  std::size_t c = 0;
  for (const LiftingSurface& ls : body.surfaces)
    if (ls.depth_control) bw.deflection[c] = applied_deflection(*ls.depth_control, bs.controls[c]), ++c;
}
}  // namespace

void compute_kinematics(const Model& model, const PhysicalState& s, Workspace& ws) {
  const auto& els = model.cable.elements;
  // Joints and centres down the chain: P_k = P_{k-1} + L_k e_k; at a body,
  // the chain goes on from its lower link Q2 (in-line) or ends (end body).
  ws.P[0] = s.r0;
  ws.vP[0] = s.v0;
  for (std::size_t i = 0; i < els.size(); ++i) {
    const double L = els[i].length;
    ws.edot[i] = s.w[i].cross(s.e[i]);
    ws.G[i] = ws.P[i] + 0.5 * L * s.e[i];
    ws.vG[i] = ws.vP[i] + 0.5 * L * ws.edot[i];
    ws.P[i + 1] = ws.P[i] + L * s.e[i];
    ws.vP[i + 1] = ws.vP[i] + L * ws.edot[i];
    const int b = ws.body_at[i + 1];
    if (b < 0) continue;
    BodyWork& bw = ws.body[static_cast<std::size_t>(b)];
    body_kinematics(model.bodies[static_cast<std::size_t>(b)], s.bodies[static_cast<std::size_t>(b)], ws.P[i + 1],
                    ws.vP[i + 1], bw);
    if (!model.bodies[static_cast<std::size_t>(b)].inline_body) continue;
    ws.P[i + 1] = bw.O + bw.rQ2;
    ws.vP[i + 1] = bw.vO + bw.w.cross(bw.rQ2);
  }
}

Vec3 roll_pitch_yaw(const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  // R = Rz(yaw) Ry(pitch) Rx(roll): R(2,0) = -sin(pitch).
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return Vec3(roll, pitch, yaw);
}

Quat quat_from_rpy(double roll, double pitch, double yaw) {
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

}  // namespace towsim
