// Fluid and gravity loads on cable elements and on the towed body (docs/theory.md §3-4).
#pragma once

#include <utility>

#include "towsim/dynamics/state.hpp"
#include "towsim/model/seabed_segment.hpp"

namespace towsim {

/// Smoothed sign: x / sqrt(x^2 + v_s^2) [-]; continuous, odd, -> sgn(x) for |x| >> v_s.
double smooth_sign(double x, double v_s);

/// Loads on cable element `el` applied at its centre G: weight and buoyancy,
/// normal pressure drag, tangential friction and the velocity terms of the
/// ideal-fluid added mass (incl. the Munk moment). The acceleration terms of
/// the added mass are NOT included: they belong to the mass matrix Mt, Ia.
/// e: unit axis, edot = de/dt, vG: velocity of G, xG: position of G [m, R_g],
/// t: time [s]. Outputs: F [N, R_g] and moment about G, M [N m, R_g]; with
/// `water`, the water's velocity at G the loads took (+0 in still water) [m/s, R_g].
void element_loads(const Model& model, const Element& el, const Vec3& e, const Vec3& edot, const Vec3& vG,
                   const Vec3& xG, double t, Vec3& F, Vec3& M, Vec3* water = nullptr);

/// Translational inertia of an element at G: m I + ma (I - ee^T) [kg].
/// Inline, coefficient by coefficient (called per element per evaluation;
/// the same operations, and bits, as the matrix expression).
inline Mat3 element_mass(const Element& el, const Vec3& e) {
  Mat3 M;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const double d = i == j ? 1.0 : 0.0;  // I_ij
      M(i, j) = el.mass * d + el.added_mass * (d - e[i] * e[j]);
    }
  return M;
}

/// Rotational inertia of an element about G, perpendicular to e: I + Ia [kg m^2].
inline double element_rot_inertia(const Element& el) { return el.inertia + el.added_inertia; }

/// Body inertia in R_g about O_t and the velocity-dependent inertial terms:
/// d(momentum, moment of momentum about O_t)/dt = Mw [a_O; alpha] + hw.
/// Rigid part with absolute velocities, added mass with velocities relative to
/// the water (Kirchhoff's equations). Needs ws's kinematics (compute_kinematics).
/// t: time [s] (the water's velocity may depend on it; steady flows ignore it).
void body_inertia(const Fluid& fluid, const Body& body, BodyWork& ws, double t = 0);

/// External loads on the body except the link force: gravity, buoyancy,
/// sphere, cylinder and lifting-surface loads, damping. Force ws.Fb [N] and
/// moment about O_t ws.Mb [N m], both R_g.
void body_loads(const Fluid& fluid, const Body& body, double t, BodyWork& ws);

/// Loads of the attachments lumped at each joint: ws.Ma (mass + added mass)
/// and ws.Fa (apparent weight, drag on the velocity relative to the water).
/// Needs the joints' kinematics (compute_kinematics).
void attachment_loads(const Model& model, double t, Workspace& ws);

/// Seabed contact (model.seabed; nothing without one; docs/theory.md §3.2).
/// At the joints (the default): each joint P_k below the bottom gets the
/// contact force of the cable it represents (half of each adjacent element),
/// added to ws.Fa[k] (at the end body's joint: to its Fb, Mb at the link
/// point Q; at an in-line body: the half-element above acts at Q on the
/// body, the one below at Q2 = P_k). Along elements (Seabed::along_elements):
/// each element's segment below the bottom gets the law integrated along its
/// length in contact (element_seabed_contact), added to its loads ws.F (at
/// G) and ws.Mom (the couple about G); ws.Fs, ws.ls (and Fs_q, ls_q at an
/// in-line body's Q) then hold the end shares of that load and of the length
/// in contact, for the outputs and the stage solve's local Jacobian, not
/// added to the loads a second time. Each body's hull points (the lowest
/// point of each sphere, of each cylinder's end discs; a body with neither:
/// its CG) add theirs to Fb, Mb. Fills ws.Fs, ws.ls, ws.seabed_normal,
/// ws.seabed_friction and each BodyWork's Fs_q, ls_q. Call after the element
/// loads, attachment_loads and body_loads.
void seabed_loads(const Model& model, Workspace& ws);

/// The seabed's contact along element k (0-based), from its top joint P_k to
/// its bottom end (an in-line body's upper link Q, else P_{k+1}), for the
/// kinematics in ws (segment_contact). Needs model.seabed.
SegmentContact element_seabed_contact(const Model& model, const Workspace& ws, std::size_t k);

/// Length of hull a body with no sphere or cylinder represents at its CG [m].
inline constexpr double kBareBodyLength = 1.0;

/// A body's hull contact points (docs/theory.md §3.2), the one rule for
/// where the seabed touches a body (the contact loads, the implicit
/// integrator's local Jacobian, the statics' lay-down and the start check):
/// visit(p, length) for each sphere's lowest point towards the bottom
/// (length: its diameter), each cylinder's end discs' lowest points (half its
/// length each, as a cable element), else the CG (kBareBodyLength); for the
/// body origin O [m, R_g] and attitude R (body axes to R_g); p [m, R_g],
/// length [m].
template <class Visit>
void hull_points(const Seabed& sb, const Body& body, const Vec3& O, const Mat3& R, Visit&& visit) {
  for (const SphereLoad& sp : body.spheres) {
    const Vec3 c = O + R * sp.center;
    visit(Vec3(c - sp.radius * sb.normal(c.x())), 2 * sp.radius);
  }
  for (const CylinderLoad& cy : body.cylinders) {
    const Vec3 a = R * cy.axis;
    for (double side : {-0.5, 0.5}) {
      const Vec3 ce = O + R * cy.center + side * cy.length * a;
      const Vec3 nrm = sb.normal(ce.x());
      const Vec3 d = nrm - nrm.dot(a) * a;  // towards the bottom in the disc's plane: -d
      visit(d.norm() > 1e-12 ? Vec3(ce - 0.5 * cy.diameter * d.normalized()) : ce, 0.5 * cy.length);
    }
  }
  if (body.spheres.empty() && body.cylinders.empty()) visit(Vec3(O + R * body.cg), kBareBodyLength);
}

/// The same at the body's pose in an evaluation (bw.O, bw.R).
template <class Visit>
void hull_points(const Seabed& sb, const Body& body, const BodyWork& bw, Visit&& visit) {
  hull_points(sb, body, bw.O, bw.R, std::forward<Visit>(visit));
}

/// Normal stiffness of the seabed contact at joint k (0..n) for the current
/// kinematics: d|F_n|/d(penetration) = stiffness * length in contact the
/// joint stands for (its share along elements) [N/m] (at an in-line body's
/// joint: of the element below, at Q2); 0 off the
/// bottom or without a seabed. For implicit integrators (a joint's local stiffness).
double seabed_normal_stiffness(const Model& model, const Workspace& ws, int k);

/// The flow a lifting surface sees (body kinematics in ws, deflection d [rad]).
struct SurfaceFlow {
  double alpha = 0;          // angle of attack [rad] (0 without flow)
  double speed = 0;          // relative speed in the surface's plane [m/s]
  Vec3 up = Vec3::Zero();    // body velocity relative to the water, in the surface's plane [m/s, R_g]
  Vec3 span = Vec3::Zero();  // span axis, chord x normal [-, R_g]
};
SurfaceFlow surface_flow(const Fluid& fluid, const LiftingSurface& ls, double d, double t, const BodyWork& ws);

/// Deflection of surface j of body b as the dynamics use it: the depth
/// controller's state (ws.deflection) or the table at t [rad].
double current_deflection(const Body& b, std::size_t j, const BodyWork& ws, double t);

/// Lift coefficient of a lifting surface at angle of attack alpha [rad]:
/// linear up to stall, then falling smoothly to zero at 90 degrees.
double lift_coefficient(const LiftingSurface& ls, double alpha);

/// Deflection of a lifting surface at time t [rad].
double surface_deflection(const LiftingSurface& ls, double t);

}  // namespace towsim
