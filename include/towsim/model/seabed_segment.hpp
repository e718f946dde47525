// The seabed's contact along a straight segment of cable (MODEL.md 10
// "Contact along elements", docs/theory.md §3.2): the point law of
// towsim/model/seabed.hpp per metre, integrated along the segment.
//
// Along a segment a -> b, p(u) = a + u (b - a), u in [0, 1], moving at
// v(u) = v_a + u (v_b - v_a) (exact for a rigid or uniformly stretching
// element), over a piece of bottom with one normal n (the segment is cut at
// the depth table's rows), the gap h(u) and the normal load per metre
// g(u) = -k h(u) - c v(u).n are linear in u. The normal force per metre is
// max(0, g) n where h < 0, the friction per metre -mu g u_t / sqrt(|u_t|^2 + v_s^2).
// Integrated on the sub-interval where both h < 0 and g > 0 by 3-point
// Gauss-Legendre (exact for the normal force, linear times linear shape
// functions; the friction's smooth ratio to within its quadrature error).
#pragma once

#include <limits>

#include "towsim/model/seabed.hpp"

namespace towsim {

/// The seabed's contact on one straight segment, as end forces: the two
/// forces at a and b have the distributed load's resultant and its moment
/// about any point of the segment (the weights 1 - u and u); the component
/// of the moment along the segment is zero (a force on its axis).
struct SegmentContact {
  Vec3 at_a = Vec3::Zero();      // share of the load at a: integral of (1 - u) f ds [N, R_g]
  Vec3 at_b = Vec3::Zero();      // share at b: integral of u f ds [N, R_g]
  double length = 0;             // length in contact (h < 0) [m]
  double length_a = 0;           // its share at a, integral of (1 - u) ds over the contact [m]
  double length_b = 0;           // its share at b, integral of u ds over the contact [m]
  double normal = 0;             // magnitude of the normal force, summed over the bottom's pieces [N]
  Vec3 friction = Vec3::Zero();  // resultant of the friction [N, R_g]
  double first = std::numeric_limits<double>::quiet_NaN();  // u of the contact nearest a (NaN: none) [-]

  /// Resultant force on the segment [N, R_g].
  Vec3 total() const { return at_a + at_b; }
  /// Its moment about a point c [N m, R_g].
  Vec3 moment(const Vec3& a, const Vec3& b, const Vec3& c) const { return (a - c).cross(at_a) + (b - c).cross(at_b); }
};

/// The contact of the segment a -> b [m, R_g] whose ends move at va, vb
/// [m/s, R_g] with the bottom `sb`; zero above it. `rest_sink` [m, >= 0]
/// moves the level the gap is measured from up by that much along the
/// vertical: h(u) is the gap minus rest_sink n_z (Seabed::rest_sink: a cable lying at rest then has
/// its axis on the bottom's level).
SegmentContact segment_contact(const Seabed& sb, const Vec3& a, const Vec3& va, const Vec3& b, const Vec3& vb,
                               double rest_sink = 0);

}  // namespace towsim
