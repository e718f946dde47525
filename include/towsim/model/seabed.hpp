// The seabed: its shape (flat, or a depth table along x_g) and the contact
// load model of a point on it (MODEL.md 9 "Seabed", docs/theory.md §3.2).
//
// Contact law of a point p moving at v that represents a length l of cable
// (or of a body's hull), with n the bottom's upward unit normal below p:
//   penetration  delta = -(p_z - z_b(p_x)) n_z            [m]  (> 0: in contact)
//   normal force F_n = l max(0, k delta - c v.n) n         [N]  (the damping never pulls)
//   friction     F_t = -mu |F_n| u_t / sqrt(|u_t|^2 + v_s^2), u_t = v - (v.n) n   [N]
// k: stiffness per metre in contact, c: damping per metre, mu: Coulomb
// coefficient, v_s: the friction's smoothing speed (tends to Coulomb as v_s -> 0).
#pragma once

#include <vector>

#include "towsim/model/types.hpp"

namespace towsim {

/// The force of the seabed on one contact point.
struct SeabedForce {
  Vec3 normal = Vec3::Zero();    // F_n, along the bottom's normal [N, R_g]
  Vec3 friction = Vec3::Zero();  // F_t, along the bottom [N, R_g]
  double length = 0;             // length represented by the point when in contact, else 0 [m]
  Vec3 total() const { return normal + friction; }
};

/// Default friction smoothing speed v_s [m/s]: friction at a slip speed u is
/// mu N u / sqrt(u^2 + v_s^2), within 0.5 % of mu N above 10 v_s = 0.1 m/s,
/// and the smoothing's viscous slope mu N / v_s stays moderate (no `environment`
/// key: MODEL.md fixes the seabed keys; models built in code may change it).
inline constexpr double kSeabedSlipSpeed = 0.01;

/// A sea bottom at z = -depth(x) [m, R_g], depth linear in x_g between the
/// table's rows and constant beyond its ends (one row: flat).
struct Seabed {
  std::vector<double> x;                 // table abscissae x_g, strictly increasing [m]
  std::vector<double> depth;             // depth below the still water level at x, > 0 [m]
  double stiffness = 1e5;                // k: normal stiffness per metre in contact [N/m per m]
  double damping = 1e3;                  // c: normal damping per metre in contact [N s/m per m]
  double friction = 0.5;                 // mu: Coulomb coefficient [-]
  double slip_speed = kSeabedSlipSpeed;  // v_s of the smoothed friction [m/s]
  // Where the cable feels the law: false, at its joints (each standing for
  // half of each adjacent element); true, along each element's straight
  // segment (segment_contact, MODEL.md 10) [-]. Scenario key
  // environment.seabed.contact: joints | elements.
  bool along_elements = true;
  // The bottom's own velocity [m/s, R_g]: zero, except where the dynamics
  // run in a frame that moves over a flat bottom (a network's steady tow,
  // relaxed in the tow's frame); the contact's damping and friction act on
  // the velocity relative to it.
  Vec3 velocity = Vec3::Zero();

  /// A flat bottom at depth d [m].
  static Seabed flat(double d, double stiffness = 1e5, double damping = 1e3, double friction = 0.5);

  /// Depth of the bottom below x (only x_g matters) [m].
  double depth_at(double x_g) const;
  /// Height z_b of the bottom below x [m, R_g] (= -depth_at).
  double bottom_z(double x_g) const { return -depth_at(x_g); }
  /// Upward unit normal of the bottom at x_g [-, R_g] (on a table's row: the
  /// slope of the segment to its right).
  Vec3 normal(double x_g) const;
  /// Distance of p above the bottom, along the normal (< 0: below) [m].
  double gap(const Vec3& p) const;
  /// The contact force on a point p [m, R_g] moving at v [m/s, R_g] that
  /// represents `length` [m] of cable or hull; zero above the bottom.
  SeabedForce contact(const Vec3& p, const Vec3& v, double length) const;
  /// The slopes of that force for the stage solve's local Jacobian, given the
  /// force f [N, R_g] it bears: C += c l n n^T + the friction's slope
  /// mu |F_n| d(u_t/q)/du_t [N s/m], K += k l n n^T [N/m] (n: the bottom's
  /// normal; the friction's dependence on the penetration is left out).
  void contact_slopes(const Vec3& p, const Vec3& v, double length, const Vec3& f, Mat3& C, Mat3& K) const;
  /// d|F_n|/d(penetration) of such a point [N/m]: k * length in contact, 0 above.
  double normal_stiffness(const Vec3& p, double length) const { return gap(p) < 0 ? stiffness * length : 0.0; }
  /// The sink delta = w / k [m] of a cable of apparent weight w [N/m] lying
  /// at rest on a flat bottom under this law (0 for a buoyant cable). Along
  /// elements the contact level is raised by it (times n_z on a slope), so
  /// that a lying cable rests with its axis on the bottom's level, as on the
  /// rigid bottom the penalty stands for: the hanging part then ends where
  /// the lying part begins.
  double rest_sink(double weight_per_metre) const { return weight_per_metre > 0 ? weight_per_metre / stiffness : 0.0; }
};

}  // namespace towsim
