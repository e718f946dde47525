// Kinematics of the chain and body from a physical state (docs/theory.md §2, §4).
#include <cmath>

#include "towsim/dynamics/state.hpp"

namespace towsim {

Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

PhysicalState PhysicalState::hanging(int n) {
  PhysicalState s;
  s.e.assign(n, -Vec3::UnitZ());
  s.w.assign(n, Vec3::Zero());
  return s;
}

Workspace::Workspace(const Model& model) {
  const std::size_t n = model.cable.elements.size();
  P.resize(n + 1);
  vP.resize(n + 1);
  G.resize(n);
  vG.resize(n);
  edot.resize(n);
  F.resize(n);
  Mom.resize(n);
  Mt.resize(n);
  K.resize(n + 1);
  b.resize(n + 1);
  T.resize(n);
  GT.resize(n);
  Dinv.resize(n);
  y0.resize(n);
  c.resize(n);
  acc.alpha.resize(n);
  acc.joint_force.resize(n + 1);
}

void compute_kinematics(const Model& model, const PhysicalState& s, Workspace& ws) {
  const auto& els = model.cable.elements;
  // Joints and centres down the chain: P_k = P_{k-1} + L_k e_k.
  ws.P[0] = s.r0;
  ws.vP[0] = s.v0;
  for (std::size_t i = 0; i < els.size(); ++i) {
    const double L = els[i].length;
    ws.edot[i] = s.w[i].cross(s.e[i]);
    ws.G[i] = ws.P[i] + 0.5 * L * s.e[i];
    ws.vG[i] = ws.vP[i] + 0.5 * L * ws.edot[i];
    ws.P[i + 1] = ws.P[i] + L * s.e[i];
    ws.vP[i + 1] = ws.vP[i] + L * ws.edot[i];
  }
  // Body: hangs from the last joint at its link point Q.
  if (model.has_body) {
    const std::size_t n = els.size();
    ws.R = s.q.toRotationMatrix();
    ws.rQ = ws.R * model.body.link_point;
    ws.O = ws.P[n] - ws.rQ;
    ws.wB = s.wb;
    ws.vO = ws.vP[n] - s.wb.cross(ws.rQ);
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
