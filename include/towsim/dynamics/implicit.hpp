// Linear stage solves of the linearly implicit integrator (docs/theory.md
// §6.3 "Rosenbrock-W"): the O(n) recursion run with modified inertias
// M + hg C + hg^2 K and a right-hand side of arbitrary generalized forces.
//
// C and K are LOCAL: each part of the chain contributes the damping and the
// stiffness of its own coordinates only (per-part hooks below). The W-method
// keeps its order whatever this approximate Jacobian is; the local terms only
// have to capture the stiff modes (rocking of short tensioned elements, drag
// damping of light elements) for the step to be bounded by accuracy.
#pragma once

#include <vector>

#include "towsim/dynamics/state.hpp"

namespace towsim {

/// The local (per-part) Jacobian approximation at one state. A new kind of
/// part (an elastic element's stretch, a seabed spring at a joint) adds its
/// own entries here and its own terms in `implicit_stage_solve`.
struct LocalJacobian {
  std::vector<Mat3> element_damping;      // C_k = -dF_k/dv(G_k), drag at G_k [kg/s, R_g]
  std::vector<double> element_stiffness;  // K_k, rocking stiffness of element k about its top joint
                                          // (geometric: axial force times length) [N m/rad]
  std::vector<Mat3> joint_damping;        // attachments and seabed at joint k: -dF_a/dv(P_k) [kg/s, R_g]
  std::vector<Mat3> joint_stiffness;      // seabed spring at joint k: -dF_s/dx(P_k) [N/m, R_g]
  std::vector<Mat3> bodyq_damping;        // seabed at body b's link point Q (end body's P_n, or an
  std::vector<Mat3> bodyq_stiffness;      //   in-line body's upper link): [kg/s], [N/m], R_g
  std::vector<Mat6> body_damping;         // -d(F; M about O_t)/d(v_O; omega_B) [SI, R_g]
  std::vector<Mat3> body_stiffness;       // rotation of the body about its link point Q, loads held
                                          // in space: moment per radian [N m/rad, R_g]
  // Seabed at body b's own hull points: -d(F; M about O_t)/d(v_O; omega_B) and
  // -d(F; M about O_t)/d(x_O; theta) [SI, R_g] (body_contact_local_jacobian).
  std::vector<Mat6> body_contact_damping;
  std::vector<Mat6> body_contact_stiffness;
};

/// Per-part hook, element: drag damping at G and rocking stiffness, from the
/// loads of the last evaluation. F: the element's loads at G [N]; f_bottom:
/// the force through its bottom joint onto the part below [N, R_g]; `water`:
/// the water's velocity at G as those loads took it (else computed) [m/s, R_g].
void element_local_jacobian(const Model& model, const Element& el, const Vec3& e, const Vec3& vG, const Vec3& xG,
                            double t, const Vec3& F, const Vec3& f_bottom, Mat3& C, double& K,
                            const Vec3* water = nullptr);

/// Derivatives of a body's loads (body_loads, F_b and M_b about O_t, R_g):
/// damping D = -d(F_b; M_b)/d(v_O; omega_B) (6x6) and stiffness about O_t
/// KO = -dM_b/dtheta, turning the body about O_t (3x3). Analytic (gravity,
/// buoyancy, thrusters, sphere and cylinder drag, lifting surfaces, generic
/// damping); in a non-uniform flow the water's velocity and acceleration
/// gradients by central differences (docs/theory.md §6.3).
void body_load_derivatives(const Fluid& fluid, const Body& body, const BodyWork& bw, double t, Mat6& D, Mat3& KO);

/// Symmetric part of A with its negative eigenvalues dropped: a damping or a
/// stiffness the W-method may use, never one that feeds energy in. 3x3 by the
/// closed-form eigen-decomposition (within ~sqrt(eps) |A| of the exact part),
/// 6x6 by QR iteration.
Mat3 psd_part(const Mat3& A);
Mat6 psd_part(const Mat6& A);

/// Per-part hook, body: damping C (6x6 on v_O, omega_B) and rotational
/// stiffness K about the link point Q, from body_load_derivatives (symmetric
/// parts, negative eigenvalues dropped). bw: the body's evaluation;
/// lines: the stiffness about Q of the lines' pull on its points
/// (body_line_stiffness), added before the negative eigenvalues are dropped.
void body_local_jacobian(const Fluid& fluid, const Body& body, const BodyWork& bw, double t, Mat6& C, Mat3& K,
                         const Mat3& lines = Mat3::Zero());

/// The rotational stiffness about the link point Q [N m/rad, R_g] of the
/// cable below a body (below an in-line body's lower link, the lines of a
/// tree from its points): turning the body by dtheta moves a point by
/// dtheta x r (r = point - Q) against the cable's pull f held there, the
/// second variation of -f.x: (f.r) I - f r^T (as an element's rocking
/// stiffness -L f_bottom.e). `lower_link_force`: the force on the cable
/// below an in-line body (Accelerations::lower_link_force).
Mat3 body_line_stiffness(const Body& body, const BodyWork& bw, const Vec3& lower_link_force);

/// Per-part hook, attachment at a joint: drag damping on the joint's velocity.
Mat3 attachment_local_damping(const Model& model, const Attachment& a, const Vec3& x, const Vec3& v, double t);

/// Per-part hook, a body's own seabed contact (its hull points, hull_points):
/// each point p in contact adds its Seabed::contact_slopes (C_p, K_p) through
/// dp = dx_O + dtheta x r, r = p - O_t: C = sum J^T C_p J, K = sum J^T K_p J,
/// J = [I, -[r]x] (6x6 on (v_O, omega_B) and (x_O, theta)); zero off the bottom.
void body_contact_local_jacobian(const Seabed& sb, const Body& body, const BodyWork& bw, Mat6& C, Mat6& K);

/// Fill `jac` for the state whose evaluation `ws` holds (forward_dynamics at (s, t)).
void local_jacobian(const Model& model, const PhysicalState& s, const Workspace& ws, double t, LocalJacobian& jac);

/// Work arrays of the stage solve, sized once per model.
struct ImplicitWorkspace {
  explicit ImplicitWorkspace(const Model& model);
  LocalJacobian jac;
  // Right-hand side of one stage solve, as loads (built from the increments):
  std::vector<Vec3> F, Mom;  // per element: force at G [N] and couple [N m], R_g
  std::vector<Vec3> Fa;      // per joint (attachments, seabed; else +0) [N, R_g]
  std::vector<Vec3> Fb, Mb;  // per body: force and moment about O_t [N], [N m], R_g
  std::vector<Vec3> FQ;      // per body: seabed force at its link point Q [N, R_g]
  std::vector<Vec3> Fd;      // per elastic element: spring and axial damper force on d_k [N, R_g]
  // Recursion with modified inertias (zero velocities: no centripetal terms).
  std::vector<Mat3> K;  // f_k = K_k a_k + b_k [kg] (k = 0..n)
  std::vector<Vec3> b;  // [N]
  // Factorisation (implicit_factor: depends on hg and the Jacobian point only):
  std::vector<Eigen::Matrix<double, 3, 2>> T;  // tangent basis [-]
  std::vector<Eigen::Matrix2d> Phi;            // inverse rotational block [1/(kg m^2)]
  std::vector<Eigen::Matrix<double, 3, 2>> H;  // G T Phi [1/m]
  std::vector<Mat3> TH;                        // T H^T = T Phi (G T)^T: beta's slope on the top
                                               // joint's acceleration, beta = q - TH a [1/m]
  std::vector<Mat3> bPhi, bC, bKQ;             // per body: as BodyWork, modified inertia
  std::vector<Mat3> EAinv, EG;                 // per elastic element: as ElasticWork, modified
                                               // (A^-1 [1/kg], G [kg])
  std::vector<Vec3> Er;                        // per elastic element: d-equation's right side [N]
  // Bending springs coupling two rigid elements (docs/theory.md §6.3 "Bending
  // in the stage solve"): per joint j (0..n), the stage's spring kappa_j
  // (0 where it does not couple two rigid elements) and the part below's
  // response to the rotation alpha_{j-1} of the element above:
  //   f_j = K_j a_j + Qb_j alpha_{j-1} + b_j,  alpha_j = -Rb_j a_j + Sb_j alpha_{j-1} + qb_j.
  std::vector<double> kappa;  // [N m/rad]
  // In the stage solve's units (a [m/s], alpha [rad/s], f [N s]):
  std::vector<Mat3> Qb;                         // the force's slope on the rotation above [kg m]
  std::vector<Mat3> Rb;                         // alpha's slope on the joint's velocity increment [1/m]
  std::vector<Mat3> Sb;                         // alpha's slope on the rotation above [-]
  std::vector<Vec3> qb;                         // alpha at zero inputs [rad/s]
  std::vector<char> coupled;                    // per element: its rotation is coupled to a neighbour's [-]
  bool any_coupled = false;                     // some kappa > 0 (else the coupling passes are skipped)
  std::vector<Eigen::Matrix<double, 2, 3>> PG;  // per coupled element: Phi G~ [1/m]
  std::vector<Eigen::Matrix<double, 2, 3>> PE;  // per coupled element: Phi E^T [1/(kg m^2)]
  std::vector<Eigen::Vector2d> zr;              // per coupled element: Phi r0' (bias sweep) [rad/s]
  double hg = -1;                               // h gamma of the factorisation [s]; < 0: none
  // Right-hand-side sweeps (implicit_stage_solve):
  std::vector<Eigen::Vector2d> Tr0;  // T^T r_0 [N m]
  std::vector<Vec3> q;               // T Phi T^T r_0, beta at zero joint acceleration [rad/s]
  std::vector<Vec3> brhs, bbQ;       // per body [N m], [N]
  std::vector<Vec3> dvP;             // velocity increments of the joints [m/s] (with joint terms only)
  std::vector<Vec3> dxP;             // position increments of the joints [m] (with joint terms only)
  // Solution: tow point (Force mode) and angular increments (z below).
  Vec3 a0 = Vec3::Zero();     // [m/s] (0 in Motion mode)
  std::vector<Vec3> alpha;    // per element, normal to e_k [rad/s]
  std::vector<Vec3> alpha_b;  // per body [rad/s]
  std::vector<double> zl;     // per elastic element: increment of l_k' [m/s] (0 for rigid ones)
  double z_winch = 0;         // tension-controlled winch (tow point held): increment of l_1' [m/s]
  bool drum = false;          // the stage solve has the drum's rows (set by the loads pass)
  double drum_rhs = 0;        // the drum's own right-hand side -hg c r_l' [N s]
  // A tree of lines (docs/theory.md §5.7), as in Workspace: the lines below
  // the cable's end and below the bodies' points, in the stage's units.
  struct Child {
    Mat3 K = Mat3::Zero();   // the line's top: f_0 = K a + b [kg]
    Vec3 b = Vec3::Zero();   // [N s]
    Vec3 dv = Vec3::Zero();  // the point's increments carried down (right-hand side) [m/s]
    Vec3 dx = Vec3::Zero();  // [m]
    Vec3 a = Vec3::Zero();   // the point's increment z [m/s]
  };
  Child end;                                      // the lines below the cable's end (summed K, b) and its increments
  std::vector<std::vector<Child>> body_children;  // per body, per BodyWork::children entry
  // A line hanging from a node: its top's increments are the node's.
  bool top_given = false;
  Vec3 top_dv = Vec3::Zero(), top_dx = Vec3::Zero(), top_a = Vec3::Zero();  // [m/s], [m], [m/s]
};

/// Velocity-side inputs of one stage solve (increments r_v of the velocities
/// and the rotation vectors of the position increments r_x, all R_g).
struct StageRhs {
  Vec3 dv0 = Vec3::Zero();             // tow point velocity increment (Force mode) [m/s]
  Vec3 dx0 = Vec3::Zero();             // tow point position increment (Force mode) [m]
  std::vector<Vec3> dw;                // per element: omega increment [rad/s]
  std::vector<Vec3> rot;               // per element: e_k x (increment of e_k) [rad]
  std::vector<Vec3> dwb;               // per body: omega_B increment [rad/s]
  std::vector<Vec3> rotb;              // per body: rotation vector of the attitude increment [rad]
  std::vector<double> dl, dlr;         // per element: increments of l_k [m] and l_k' [m/s] (elastic; else 0)
  double winch_dl = 0, winch_dlr = 0;  // tension-controlled winch: increments of l_1 [m] and l_1' [m/s]
  // Winch over an elastic top element: the increments of L_1, L_1' times
  // l_1/L_1, as its spring and damper see them (T depends on l_1 - lam L_1).
  double top_dL = 0;   // [m]
  double top_dLr = 0;  // [m/s]
};

/// Factorise M + hg C + hg^2 K in O(n): the backward pass of the recursion
/// (articulated inertias K_k, rotation blocks Phi) with modified inertias.
/// `ws` holds the evaluation at the state s the Jacobian iw.jac belongs to
/// (kinematics, inertias, the rigid elements' tangent bases T). Valid for
/// every stage solve with the same hg.
void implicit_factor(const Model& model, const PhysicalState& s, const Workspace& ws, double hg, ImplicitWorkspace& iw);

/// Solve (M + hg C + hg^2 K) z = -(hg C + hg^2 K) r_v - hg K r_x in O(n)
/// (r_x: the rotations rot(r_x), and the joints' displacements for springs at joints)
/// with the factorisation of implicit_factor (same hg, same s and ws): the
/// right-hand side as loads, the bias sweep up the chain, the accelerations
/// down. Result z in iw.a0, iw.alpha, iw.alpha_b; the stage increment of the
/// velocities is then r_v + z. A tension-controlled winch with the tow point
/// held adds its pay-out l_1' as a prismatic joint at the top with inertia
/// M_d + hg c (drum, damping c): its increment in iw.z_winch.
void implicit_stage_solve(const Model& model, const PhysicalState& s, const Workspace& ws, double hg, const StageRhs& r,
                          ImplicitWorkspace& iw);

}  // namespace towsim
