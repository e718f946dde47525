// Elastic cable elements: tension law, slack, and the element's step of the
// O(n) recursion (docs/theory.md §5.4 "Elastic elements").
//
// An elastic element k is a straight rod from joint P_{k-1} to
// P_k = P_{k-1} + d_k, d_k = l_k e_k, its material (mass m_k, constant)
// spread uniformly along it: the point at fraction s in [0, 1] moves with
// v_{k-1} + s d_k'. Relative to its top joint it has three degrees of
// freedom (ball joint + stretch): e_k, omega_k (normal to e_k) and the
// joint-to-joint length l_k with its rate l_k'. It carries the tension
// T = EA max(l/L - 1, 0) (+ axial damping while taut), never a compression.
#pragma once

#include "towsim/model/model.hpp"

namespace towsim {

/// True when the element stretches (axial_stiffness given).
inline bool is_elastic(const Element& el) { return el.axial_stiffness > 0; }

/// Strain of an element of current joint-to-joint length l: l / L - 1 [-]
/// (L = Element::length, the unstretched length; < 0: slack).
inline double element_strain(const Element& el, double l) { return l / el.length - 1; }

/// Tension of an elastic element of length l [m] stretching at l_rate [m/s]:
/// EA strain + c_a strain rate while taut (strain > 0), never below zero;
/// zero when slack (strain <= 0) [N]. Zero for an inextensible element.
inline double element_tension(const Element& el, double l, double l_rate) {
  const double strain = element_strain(el, l);
  if (!is_elastic(el) || strain <= 0) return 0.0;
  const double T = el.axial_stiffness * strain + el.axial_damping * l_rate / el.length;
  return T > 0 ? T : 0.0;
}

/// Tension of the winch's elastic top element (unstretched length
/// el.length = L_1 growing at L_rate = L_1' [m/s]): as element_tension, the
/// damping on the strain rate (l' - (l/L_1) L_1') / L_1 [N].
inline double paid_out_tension(const Element& el, double l, double l_rate, double L_rate) {
  const double strain = element_strain(el, l);
  if (strain <= 0) return 0.0;
  const double T = el.axial_stiffness * strain + el.axial_damping * (l_rate - l / el.length * L_rate) / el.length;
  return T > 0 ? T : 0.0;
}

/// Stop length of a slack elastic element, as a fraction of L [-]: below
/// it the compression stop acts (docs/theory.md §5.4 "Compression stop").
inline constexpr double kStopFraction = 0.1;

/// Compression stop of a slack elastic element shorter than l_s =
/// kStopFraction L: the axial force -(EA (l_s - l)/L - c_a l'/L), never
/// pulling, so that a slack cable piling up on itself (a straight rod cannot
/// loop sideways as a real cable does) does not fold an element to l -> 0
/// [N, axial force: < 0 pushes the joints apart]. Zero above l_s (every taut
/// or mildly slack element) and for an inextensible element. Not a tension:
/// element_tension stays >= 0.
inline double element_stop_force(const Element& el, double l, double l_rate) {
  const double ls = kStopFraction * el.length;
  if (!is_elastic(el) || l >= ls) return 0.0;
  const double C = (el.axial_stiffness * (ls - l) - el.axial_damping * l_rate) / el.length;
  return C > 0 ? -C : 0.0;
}

/// Axial force the dynamics use: tension + compression stop [N].
inline double element_axial_force(const Element& el, double l, double l_rate) {
  return element_tension(el, l, l_rate) + element_stop_force(el, l, l_rate);
}

/// True while the element is taut or on its compression stop (l below l_s).
inline bool element_axially_loaded(const Element& el, double l) {
  return is_elastic(el) && (element_strain(el, l) > 0 || l < kStopFraction * el.length);
}

/// Local axial stiffness d(axial force)/dl of an element at length l [N/m]:
/// EA / L while taut or on the compression stop, 0 when slack or
/// inextensible. The stiff part of the elastic element's force, for an
/// implicit integrator's local linearisation (with element_axial_damping_rate).
inline double element_axial_stiffness(const Element& el, double l) {
  return element_axially_loaded(el, l) ? el.axial_stiffness / el.length : 0.0;
}

/// Local axial damping d(axial force)/dl' of an element at length l [N s/m]:
/// c_a / L while taut or on the stop, else 0.
inline double element_axial_damping_rate(const Element& el, double l) {
  return element_axially_loaded(el, l) ? el.axial_damping / el.length : 0.0;
}

/// Speed of the axial (tension) wave along an elastic element,
/// c = sqrt(EA / m') with m' = m / L its mass per unit length [m/s]
/// (no added mass: the water does not follow an axial motion).
double axial_wave_speed(const Element& el);

/// The largest fixed RK4 step that is stable for the axial mode of a chain
/// of these elements: 0.8 L / c (consistent-mass rod: highest axial
/// frequency 2 sqrt(3) c / L; RK4 is stable up to 2 sqrt(2) / omega on the
/// imaginary axis); with axial damping overdamping that mode, 2.7 / |fast
/// real root| when smaller [s]. Infinity for an inextensible element.
double rk4_axial_step_limit(const Element& el);

/// Articulated quantities of one elastic element (docs/theory.md §5.4):
/// with a the acceleration of its top joint, d'' = Ainv (r - G a).
struct ElasticWork {
  Mat3 Ainv = Mat3::Zero();  // (Mt/3 + K_k)^-1 [1/kg]
  Mat3 G = Mat3::Zero();     // Mt/2 + K_k [kg]
  Vec3 r = Vec3::Zero();     // F/2 + (M x e)/l - T e - b_k [N]
  double T = 0;              // tension T [N] (set with the loads; zeroed for impulses)
};

/// Backward step of elastic element `el` with axis e, length l: from the
/// articulated (Kk, bk) of what hangs at its bottom joint, its Mt, its loads
/// F (at the centre, [N]) and M (moment about the centre, [N m]) and
/// tension ew.T, fill ew and give (K, b) at its top joint: f = K a + b.
void elastic_backward(const Vec3& e, double l, const Mat3& Mt, const Vec3& F, const Vec3& M, const Mat3& Kk,
                      const Vec3& bk, ElasticWork& ew, Mat3& K, Vec3& b);

/// Forward step: from the acceleration a of the top joint, d'' = Ainv (r - G a);
/// gives the element's angular acceleration alpha [rad/s^2] and l'' [m/s^2]
/// (e, w, l, l_rate: the element's state) and returns d'' [m/s^2].
Vec3 elastic_forward(const ElasticWork& ew, const Vec3& e, const Vec3& w, double l, double l_rate, const Vec3& a,
                     Vec3& alpha, double& l_acc);

/// The same for the winch's top element, whose top is the material at the
/// sheave (acceleration a) rather than the joint P_0: `shift` = a - a_0
/// enters the decomposition d_1'' = (a + d'') - a_0 into l'' and alpha.
Vec3 elastic_forward(const ElasticWork& ew, const Vec3& e, const Vec3& w, double l, double l_rate, const Vec3& a,
                     const Vec3& shift, Vec3& alpha, double& l_acc);

}  // namespace towsim
