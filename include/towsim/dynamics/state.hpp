// The physical state of cable and body, and the workspace of intermediate
// results that the dynamics fill. Notation: docs/theory.md.
#pragma once

#include <vector>

#include "towsim/model/model.hpp"

namespace towsim {

/// Configuration and velocities in physical (chart-free) variables.
/// Every formulation maps its own coordinates to and from this.
struct PhysicalState {
  Vec3 r0 = Vec3::Zero();     // tow point O_r = P_0 [m, R_g]
  Vec3 v0 = Vec3::Zero();     // its velocity [m/s, R_g]
  std::vector<Vec3> e;        // e_k, unit vector P_{k-1} -> P_k, k = 1..n at index k-1 [-, R_g]
  std::vector<Vec3> w;        // omega_k, angular velocity of element k, perpendicular to e_k [rad/s, R_g]
  Quat q = Quat::Identity();  // body attitude: body axes -> R_g
  Vec3 wb = Vec3::Zero();     // body angular velocity [rad/s, R_g]

  /// A state of n elements hanging straight down, at rest.
  static PhysicalState hanging(int n);
};

/// Everything the dynamics compute at one instant (outputs of one evaluation).
struct Accelerations {
  Vec3 a0 = Vec3::Zero();         // tow point acceleration [m/s^2, R_g]
  std::vector<Vec3> alpha;        // element angular accelerations, perpendicular to e_k [rad/s^2, R_g]
  Vec3 alpha_b = Vec3::Zero();    // body angular acceleration [rad/s^2, R_g]
  Vec3 tow_force = Vec3::Zero();  // F_R on the cable at O_r [N, R_g]
  Vec3 link_force = Vec3::Zero(); // F_L on the body at Q [N, R_g]
  std::vector<Vec3> joint_force;  // f_k, force through joint k on the part below it, k = 0..n [N, R_g]
};

/// Preallocated intermediate results: kinematics, loads and the recursion's
/// articulated quantities. Sized once per model (no allocation per evaluation).
struct Workspace {
  // Kinematics
  std::vector<Vec3> P, vP;      // joints P_0..P_n and their velocities [m], [m/s]
  std::vector<Vec3> G, vG;      // element centres G_k and velocities (index k-1)
  std::vector<Vec3> edot;       // de_k/dt = omega_k x e_k [1/s]
  Mat3 R = Mat3::Identity();    // body rotation matrix, body axes -> R_g
  Vec3 rQ = Vec3::Zero();       // Q - O_t in R_g [m]
  Vec3 O = Vec3::Zero(), vO = Vec3::Zero();  // body origin O_t and its velocity
  Vec3 wB = Vec3::Zero();       // body angular velocity [rad/s, R_g]
  // Loads on each element at G_k, added-mass acceleration terms excluded
  std::vector<Vec3> F, Mom;     // force [N] and moment about G_k [N m], R_g
  std::vector<Mat3> Mt;         // translational inertia m I + ma (I - ee^T) [kg]
  // Body: d(momentum)/dt = Mw [a_O; alpha] + hw; external loads Fb, Mb about O_t
  Mat6 Mw = Mat6::Zero();
  Vec6 hw = Vec6::Zero();
  Vec3 Fb = Vec3::Zero(), Mb = Vec3::Zero();
  // Articulated quantities of the recursion (index k = 0..n)
  std::vector<Mat3> K;          // f_k = K_k a_{P_k} + b_k [kg]
  std::vector<Vec3> b;          // [N]
  // Per element (index k-1), in the tangent basis T = [t1 t2] normal to e_k:
  std::vector<Eigen::Matrix<double, 3, 2>> T;   // tangent basis [-]
  std::vector<Eigen::Matrix<double, 3, 2>> GT;  // G T, G = (L/2) Mt + L K_k [kg m]
  std::vector<Eigen::Matrix2d> Dinv;            // (T^T (L^2/4 Mt + L^2 K_k) T + Ir)^-1 [1/(kg m^2)]
  std::vector<Eigen::Vector2d> y0;              // T^T r_0 (moment of the known loads) [N m]
  std::vector<Vec3> c;                          // centripetal part of d2e/dt2: -|w|^2 e [1/s^2]
  Mat3 PhiB = Mat3::Zero(), CB = Mat3::Zero();
  Vec3 rhsB = Vec3::Zero(), wcent = Vec3::Zero();
  Accelerations acc;            // result of the last evaluation

  /// Allocate for a model.
  explicit Workspace(const Model& model);
};

/// Positions and velocities of joints, centres and body from a physical state.
void compute_kinematics(const Model& model, const PhysicalState& s, Workspace& ws);

/// Unit-vector quaternion body attitude -> roll, pitch, yaw (ZYX, the paper's
/// lacet/tangage/roulis order) [rad].
Vec3 roll_pitch_yaw(const Quat& q);

/// Quaternion from roll, pitch, yaw [rad], R = Rz(yaw) Ry(pitch) Rx(roll).
Quat quat_from_rpy(double roll, double pitch, double yaw);

/// Skew-symmetric matrix: skew(a) b = a x b.
Mat3 skew(const Vec3& a);

}  // namespace towsim
