// The paper's formulation (Jacquot & Marichal, sections 1-4; docs/theory.md §2, §4, §5.1):
// independent parameters (tow point x, y, z; two angles theta_k, psi_k per
// element; yaw, pitch, roll of the body), Lagrange's equations in the form
// M(q) q'' = S(q, q'), assembled in Kane's form from element Jacobians and
// solved densely. Each element's angles are measured in its own pole frame
// (chart), re-chosen between steps when theta nears 0 or pi, so the
// formulation never meets its singularity; likewise the body's angles.
#pragma once

#include <Eigen/Dense>

#include "towsim/dynamics/state.hpp"

namespace towsim {

/// Coordinates of the paper's formulation, with their charts.
struct PaperState {
  Vec3 r0 = Vec3::Zero(), v0 = Vec3::Zero();  // tow point [m], [m/s], R_g
  Eigen::VectorXd q, qd;               // [theta_1, psi_1, ..., theta_n, psi_n, (yaw, pitch, roll)] [rad], [rad/s]
  std::vector<Mat3> chart;             // element pole frames: local -> R_g (pole = third column)
  Mat3 body_chart = Mat3::Identity();  // body reference frame: R = body_chart Rz Ry Rx
};

/// Dense workspace for the paper's formulation.
struct PaperWorkspace {
  Eigen::MatrixXd M;               // generalized mass, (3 + na)^2
  Eigen::VectorXd S;               // right-hand side
  Eigen::MatrixXd JP, JG, Jw, J6;  // Jacobians of a joint, a centre, a rotation, the body
  Eigen::VectorXd qdd;             // solved angular accelerations (na)
  std::vector<Vec3> Et, Ep, evp;   // de/dtheta, de/dpsi, velocity part of d2e/dt2 (R_g)
  Accelerations acc;               // physical results
  Workspace ws;                    // loads and kinematics (shared code)
  explicit PaperWorkspace(const Model& model);
};

/// Number of angle coordinates: 2n (+3 with a body).
int paper_angle_count(const Model& model);

/// Coordinates of a physical state. Element charts take `pole` as pole axis
/// (the paper's z_g by default); charts are then re-chosen for elements within
/// the singular zone (|cos theta| > 0.9). Body chart: identity unless near
/// pitch +-90 deg.
PaperState to_paper(const Model& model, const PhysicalState& s, const Vec3& pole = Vec3::UnitZ());

/// Coordinates of a physical state in the charts of `charts` (none re-chosen).
PaperState to_paper_in_charts(const Model& model, const PhysicalState& s, const PaperState& charts);

/// Physical state of paper coordinates.
PhysicalState from_paper(const Model& model, const PaperState& p);

/// Re-choose charts of elements (|cos theta| > 0.9) and body (|cos pitch| < 0.3)
/// near their singularity, keeping the same physical state. Returns how many
/// charts changed.
int rechart(const Model& model, PaperState& p);

/// Accelerations by the paper's formulation: assemble M and S, solve densely
/// (Motion mode: the tow-force components replace the tow point's
/// accelerations as unknowns, paper section 3). Fills pw.qdd, pw.acc
/// (a0, alpha, alpha_b, tow and link force; joint_force left empty).
void paper_dynamics(const Model& model, const PaperState& p, double t, PaperWorkspace& pw);

}  // namespace towsim
