// The physical state of cable and body, and the workspace of intermediate
// results that the dynamics fill. Notation: docs/theory.md.
#pragma once

#include <vector>

#include "towsim/dynamics/elastic.hpp"
#include "towsim/model/model.hpp"

namespace towsim {

/// Attitude and angular velocity of one rigid body of the chain.
struct BodyState {
  Quat q = Quat::Identity();             // attitude: body axes -> R_g
  Vec3 w = Vec3::Zero();                 // angular velocity omega_B [rad/s, R_g]
  std::vector<ControlState> controls{};  // per surface with a depth controller, in surface order
};

/// Configuration and velocities in physical (chart-free) variables.
/// Every formulation maps its own coordinates to and from this.
struct PhysicalState {
  Vec3 r0 = Vec3::Zero();         // tow point O_r = P_0 [m, R_g]
  Vec3 v0 = Vec3::Zero();         // its velocity [m/s, R_g]
  std::vector<Vec3> e;            // e_k, unit vector P_{k-1} -> P_k, k = 1..n at index k-1 [-, R_g]
  std::vector<Vec3> w;            // omega_k, angular velocity of element k, perpendicular to e_k [rad/s, R_g]
  std::vector<BodyState> bodies;  // one per Model::bodies entry, same order
  // Current joint-to-joint length of each element and its rate (index k-1):
  // Element::length and 0 unless a winch (the top element) or elasticity
  // changes them. Empty = the model's lengths, at rest.
  std::vector<double> length;       // l_k [m]
  std::vector<double> length_rate;  // l_k' [m/s] (0 for an inextensible element)
  // Winch over an elastic top element (elastic_winch): the unstretched
  // length of material paid out into element 1 and its rate, the winch's
  // coordinate (length[0] is then the element's stretched length l_1).
  double top_unstretched = 0;       // L_1 [m]
  double top_unstretched_rate = 0;  // L_1', the pay-out speed of unstretched cable [m/s]

  /// Length of element i (0-based): length[i], or the element's own when the
  /// state carries no lengths [m].
  double length_of(const Model& model, std::size_t i) const {
    return i < length.size() ? length[i] : model.cable.elements[i].length;
  }
  /// Its rate [m/s] (0 when the state carries none).
  double length_rate_of(std::size_t i) const { return i < length_rate.size() ? length_rate[i] : 0.0; }

  /// A state of the model's chain hanging straight down, at rest, bodies
  /// at their initial attitude, elements at their unstretched lengths.
  static PhysicalState hanging(const Model& model);
};

/// Everything the dynamics compute at one instant (outputs of one evaluation).
struct Accelerations {
  Vec3 a0 = Vec3::Zero();              // tow point acceleration [m/s^2, R_g]
  std::vector<Vec3> alpha;             // element angular accelerations, perpendicular to e_k [rad/s^2, R_g]
  std::vector<double> length_acc;      // l_k'', element length accelerations (0: inextensible) [m/s^2]
  std::vector<Vec3> alpha_b;           // body angular accelerations, per body [rad/s^2, R_g]
  Vec3 tow_force = Vec3::Zero();       // F_R on the cable at O_r [N, R_g]
  double top_length_acc = 0;           // winch: l_1'' of the top element (imposed or from the drum) [m/s^2]
  std::vector<Vec3> link_force;        // F_L on each body at its link point Q, from the cable above [N, R_g]
  std::vector<Vec3> lower_link_force;  // force of each in-line body on the cable below at Q2 [N, R_g]
                                       // (zero for the end body)
  std::vector<Vec3> joint_force;       // f_k, force through joint k on the part below it, k = 0..n;
                                       // at an in-line body's joint: through its lower link Q2 [N, R_g]
  Vec3 end_acc = Vec3::Zero();         // acceleration of the cable's end P_n (an end body's link point Q) [m/s^2, R_g]
};

/// A line hanging from a point of a body (a tree of lines, docs/theory.md
/// §5.7): where it hangs, and the line's articulated response there.
struct BodyChild {
  Vec3 point = Vec3::Zero();  // the point, body axes [m]
  Vec3 r = Vec3::Zero();      // point - O_t [m, R_g]
  Mat3 K = Mat3::Zero();      // the line's top force f_0 = K a + b (force on the line) [kg]
  Vec3 b = Vec3::Zero();      // [N]
  Vec3 a = Vec3::Zero();      // the point's acceleration (forward dynamics' pass down) [m/s^2, R_g]
};

/// Intermediate results of one rigid body (index b of Model::bodies).
struct BodyWork {
  // Kinematics
  Mat3 R = Mat3::Identity();         // rotation, body axes -> R_g [-]
  Vec3 rQ = Vec3::Zero();            // Q - O_t [m, R_g]
  Vec3 rQ2 = Vec3::Zero();           // Q2 - O_t (in-line body's lower link) [m, R_g]
  Vec3 O = Vec3::Zero();             // body origin O_t [m, R_g]
  Vec3 vO = Vec3::Zero();            // its velocity [m/s, R_g]
  Vec3 Q = Vec3::Zero();             // link point Q = bottom of the element above [m, R_g]
  Vec3 vQ = Vec3::Zero();            // its velocity [m/s, R_g]
  Vec3 w = Vec3::Zero();             // angular velocity omega_B [rad/s, R_g]
  std::vector<double> deflection{};  // applied deflection of each controlled surface (BodyState::controls) [rad]
  // d(momentum, moment of momentum about O_t)/dt = Mw [a_O; alpha] + hw
  Mat6 Mw = Mat6::Zero();    // [kg, kg m, kg m^2] blocks, R_g
  Vec6 hw = Vec6::Zero();    // [N; N m], R_g
  Vec3 Fb = Vec3::Zero();    // external force but the links' [N, R_g]
  Vec3 Mb = Vec3::Zero();    // its moment about O_t [N m, R_g]
  Vec3 Fs_q = Vec3::Zero();  // in-line body: seabed force on the cable's half-element at Q (in Fb) [N, R_g]
  double ls_q = 0;           // that half-element's length in contact [m]
  // Articulated quantities (docs/theory.md "Bodies in the chain"):
  Mat6 Me = Mat6::Zero();             // Mw plus the cable below seen at Q2 [SI, R_g]
  Vec6 he = Vec6::Zero();             // hw plus the cable below's bias [N; N m]
  Mat3 Phi = Mat3::Zero();            // (inertia about Q after elimination)^-1 [1/(kg m^2)]
  Mat3 C = Mat3::Zero();              // coupling of a_Q into the moment about Q [kg m]
  Vec3 rhs = Vec3::Zero();            // known moment about Q [N m]
  Vec3 wcent = Vec3::Zero();          // centripetal part of a_O - a_Q [m/s^2]
  Mat3 KQ = Mat3::Zero();             // F_L = KQ a_Q + bQ [kg]
  Vec3 bQ = Vec3::Zero();             // [N]
  std::vector<BodyChild> children{};  // lines hanging from its points (a tree of lines; empty in a chain)
};

/// Preallocated intermediate results: kinematics, loads and the recursion's
/// articulated quantities. Sized once per model (no allocation per
/// evaluation); `fits(model)` is checked at the entry of the dynamics.
struct Workspace {
  // Kinematics (index k = 0..n for joints; k-1 for element k)
  std::vector<Vec3> P, vP;  // top joint of element k+1 (P_n: the cable end) and velocity [m], [m/s], R_g
                            // (at an in-line body's joint: its lower link Q2)
  std::vector<Vec3> G, vG;  // element centres G_k and velocities [m], [m/s], R_g
  std::vector<Vec3> edot;   // de_k/dt = omega_k x e_k [1/s, R_g]
  // Current length of element k (index k-1) [m]: PhysicalState::length_of
  // gathered by compute_kinematics, the state's length when it carries one
  // (winch, elastic) else the model's, so the sweeps read one dense array
  // without that branch per element and per pass.
  std::vector<double> L;
  // Winch: the top element at its current length (scaled_element), and the
  // velocity of its material at the sheave, v_0 + l' e_1.
  // Over an elastic top element: scaled to the paid-out L_1, and the
  // material leaves the sheave at v_0 + (l_1/L_1) L_1' e_1.
  bool winch = false;         // true when element 1 is the winch's [-]
  Element top{};              // element 1 scaled to l_1 (elastic: to L_1) [SI]
  Vec3 v_top = Vec3::Zero();  // [m/s, R_g]
  // Loads on each element at G_k, added-mass acceleration terms excluded
  std::vector<Vec3> F, Mom;  // force [N] and moment about G_k [N m], R_g
  std::vector<Vec3> Uw;      // the water's velocity at G_k (current and waves) those loads took [m/s, R_g]
  std::vector<Mat3> Mt;      // translational inertia m I + ma (I - ee^T) [kg]
  // Bending springs (bending_loads; zero without bending stiffness), at P_k
  // (index k = 0..n): the moment the joint's spring exerts on the element
  // above it; the element below takes its opposite [N m, R_g].
  std::vector<Vec3> bend;
  bool bending = false;  // some element of the model has bending stiffness (has_bending, at construction)
  // Attachments: inertia and known force at their joint (index k = 0..n)
  std::vector<Mat3> Ma;  // summed mass + added mass [kg]
  std::vector<Vec3> Fa;  // summed loads [N, R_g]
  // Seabed contact (seabed_loads; zero without a seabed), at P_k (index k = 0..n):
  std::vector<Vec3> Fs;      // force on the cable there, normal + friction [N, R_g] (in Fa; in the end body's Fb at Q)
  std::vector<double> ls;    // length of cable in contact that the joint represents [m]
  double seabed_normal = 0;  // sum of |normal force| over the cable and the bodies [N]
  double seabed_friction = 0;  // sum of |friction force| over the cable and the bodies [N]
  // Articulated quantities of the recursion (index k = 0..n)
  std::vector<Mat3> K;  // f_k = K_k a_{P_k} + b_k [kg]
  std::vector<Vec3> b;  // [N]
  // Per element (index k-1), in the tangent basis T = [t1 t2] normal to e_k:
  std::vector<Eigen::Matrix<double, 3, 2>> T;   // tangent basis [-]
  std::vector<Eigen::Matrix<double, 3, 2>> GT;  // G T, G = (L/2) Mt + L K_k [kg m]
  std::vector<Eigen::Matrix2d> Phi;             // (T^T (L^2/4 Mt + L^2 K_k) T + Ir)^-1 [1/(kg m^2)]
  std::vector<Eigen::Vector2d> Tr0;             // T^T r_0 (moment of the known loads) [N m]
  std::vector<Eigen::Matrix<double, 3, 2>> H;   // G T Phi (b's gain on T^T r_0) [1/m]
  std::vector<Vec3> c;                          // centripetal part of d2e/dt2: -|w|^2 e [1/s^2]
  std::vector<ElasticWork> elastic;             // elastic elements' articulated quantities and tension
  std::vector<BodyWork> body;                   // per Model::bodies entry
  std::vector<int> body_at;                     // index of the body hanging at joint k, or -1 (k = 0..n)
  // Lines hanging from the cable's end (a junction of a tree of lines,
  // docs/theory.md §5.7): their summed top forces f = K a + b, added to
  // what hangs at joint n. Zero in a chain.
  bool end_children = false;  // some line hangs from the cable's end [-]
  Mat3 end_K = Mat3::Zero();  // [kg]
  Vec3 end_b = Vec3::Zero();  // [N]
  Accelerations acc;          // result of the last evaluation
  CourseCursor course;        // the tow law's last result (the course plan is the tow's)

  /// Allocate for a model.
  explicit Workspace(const Model& model);
  /// True when this workspace was sized for `model`'s chain.
  bool fits(const Model& model) const;
};

/// True when the winch pays out into an elastic top element: its
/// unstretched length L_1 is the winch's coordinate, its stretched length
/// l_1 the element's own (docs/theory.md "Winch", "Elastic elements").
inline bool elastic_winch(const Model& model) {
  return model.winch.active() && !model.cable.elements.empty() && is_elastic(model.cable.elements.front());
}

/// True when the model's state carries element lengths and their rates
/// (an elastic element anywhere).
bool lengths_in_state(const Model& model);

/// Positions and velocities of joints, centres and body from a physical state.
void compute_kinematics(const Model& model, const PhysicalState& s, Workspace& ws);

/// The same with the top joint P_0 at r0 moving at v0 [m], [m/s], R_g (a
/// line hanging from another line's node; s.r0, s.v0 unused).
void compute_kinematics(const Model& model, const PhysicalState& s, const Vec3& r0, const Vec3& v0, Workspace& ws);

/// Unit-vector quaternion body attitude -> roll, pitch, yaw (ZYX, the paper's
/// lacet/tangage/roulis order) [rad].
Vec3 roll_pitch_yaw(const Quat& q);

/// Quaternion from roll, pitch, yaw [rad], R = Rz(yaw) Ry(pitch) Rx(roll).
Quat quat_from_rpy(double roll, double pitch, double yaw);

/// Current length of element k (0-based): s.length[k], or the model's when s has none [m].
inline double element_length(const Model& model, const PhysicalState& s, std::size_t k) {
  return s.length_of(model, k);
}

/// Current rate of the length of element k (0-based) [m/s].
inline double element_length_rate(const PhysicalState& s, std::size_t k) { return s.length_rate_of(k); }

/// The winch's coordinate, the paid-out length of the top element: its
/// unstretched L_1 over an elastic top element, else its length l_1 [m].
inline double paid_out_length(const Model& model, const PhysicalState& s) {
  return elastic_winch(model) ? s.top_unstretched : element_length(model, s, 0);
}

/// Its rate, the pay-out speed: L_1' over an elastic top element, else l_1' [m/s].
inline double payout_rate(const Model& model, const PhysicalState& s) {
  return elastic_winch(model) ? s.top_unstretched_rate : element_length_rate(s, 0);
}

/// The element k (0-based) as the dynamics use it: the model's, or the
/// winch's top element at its current length (filled by compute_kinematics).
inline const Element& current_element(const Model& model, const Workspace& ws, std::size_t k) {
  return k == 0 && ws.winch ? ws.top : model.cable.elements[k];
}

/// Orthonormal basis T = [t1 t2] of the plane normal to a unit vector e
/// (an element's rotation plane, docs/theory.md §5.2): t1 = e x u / |e x u|,
/// u the axis of e's smallest component (|e x u| >= sqrt(2/3)), t2 = e x t1.
/// The one construction of the recursion, the stage solves, the statics and
/// the tests: their bases are the same bits.
inline Eigen::Matrix<double, 3, 2> tangent_basis(const Vec3& e) {
  Eigen::Index i = 0;
  e.cwiseAbs().minCoeff(&i);
  const Vec3 t1 = e.cross(Vec3::Unit(i)).normalized();
  Eigen::Matrix<double, 3, 2> T;
  T.col(0) = t1;
  T.col(1) = e.cross(t1);
  return T;
}

/// Kinetic energy of cable and bodies, added mass included (the fluid's
/// kinetic energy in the ideal-fluid model), from kinematics in ws [J].
/// Needs compute_kinematics and compute_loads (inertias) for s.
double kinetic_energy(const Model& model, const PhysicalState& s, const Workspace& ws);

/// Skew-symmetric matrix: skew(a) b = a x b.
Mat3 skew(const Vec3& a);

}  // namespace towsim
