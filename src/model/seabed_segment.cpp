// The seabed's contact along a straight segment (include/towsim/model/seabed_segment.hpp).
#include "towsim/model/seabed_segment.hpp"

#include <algorithm>
#include <cmath>

namespace towsim {

namespace {

/// The sub-interval [c0, c1] of [u0, u1] where a linear function with values
/// f0 at u0 and f1 at u1 is negative; false when it is empty.
bool negative_part(double f0, double f1, double u0, double u1, double& c0, double& c1) {
  const bool n0 = f0 < 0, n1 = f1 < 0;
  if (!n0 && !n1) return false;
  c0 = u0, c1 = u1;
  if (n0 != n1) {
    const double us = u0 + (u1 - u0) * f0 / (f0 - f1);  // the root
    (n0 ? c1 : c0) = std::clamp(us, u0, u1);
  }
  return c1 > c0;
}

/// 3-point Gauss-Legendre on [-1, 1]: abscissae and weights.
constexpr double kGaussX = 0.7745966692414834;  // sqrt(3/5)
constexpr double kGaussX3[3] = {-kGaussX, 0.0, kGaussX};
constexpr double kGaussW3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

}  // namespace

SegmentContact segment_contact(const Seabed& sb, const Vec3& a, const Vec3& va_g, const Vec3& b, const Vec3& vb_g,
                               double rest_sink) {
  SegmentContact out;
  // The ends' velocities relative to the bottom's.
  const Vec3 va = va_g - sb.velocity, vb = vb_g - sb.velocity;
  const Vec3 d = b - a, dv = vb - va;
  const double L = d.norm();  // [m]
  if (!(L > 0)) return out;
  // One piece [u0, u1] of the segment over one plane of the bottom.
  auto piece = [&](double u0, double u1) {
    if (!(u1 > u0)) return;
    const Vec3 n = sb.normal(a.x() + 0.5 * (u0 + u1) * d.x());
    const Vec3 p0 = a + u0 * d, p1 = a + u1 * d;
    const double h0 = (p0.z() - sb.bottom_z(p0.x())) * n.z() - rest_sink * n.z();  // gaps above the contact level [m]
    const double h1 = (p1.z() - sb.bottom_z(p1.x())) * n.z() - rest_sink * n.z();
    double c0 = 0, c1 = 0;
    if (!negative_part(h0, h1, u0, u1, c0, c1)) return;
    // Length in contact and its shares at the ends.
    const double dc = c1 - c0, dc2 = 0.5 * (c1 * c1 - c0 * c0);
    out.length += L * dc;
    out.length_a += L * (dc - dc2);
    out.length_b += L * dc2;
    out.first = std::isnan(out.first) ? c0 : std::min(out.first, c0);
    // Normal load per metre g(u) = -k h - c v.n [N/m], linear in u.
    auto g = [&](double u) {
      const double h = h0 + (h1 - h0) * (u - u0) / (u1 - u0);
      return -sb.stiffness * h - sb.damping * (va + u * dv).dot(n);
    };
    double f0 = 0, f1 = 0;
    if (!negative_part(-g(c0), -g(c1), c0, c1, f0, f1)) return;  // the damping never pulls
    const double gf0 = g(f0), gf1 = g(f1), mid = 0.5 * (f0 + f1), half = 0.5 * (f1 - f0);
    for (int q = 0; q < 3; ++q) {
      const double u = mid + half * kGaussX3[q], wq = kGaussW3[q] * half * L;  // [-], [m]
      const double gq = 0.5 * (gf0 + gf1) + 0.5 * (gf1 - gf0) * kGaussX3[q];   // g(u) [N/m]
      Vec3 f = gq * n;
      if (sb.friction > 0) {
        const Vec3 v = va + u * dv;
        const Vec3 ut = v - v.dot(n) * n;  // slip along the bottom [m/s]
        const Vec3 ft = -sb.friction * gq / std::sqrt(ut.squaredNorm() + sb.slip_speed * sb.slip_speed) * ut;
        out.friction += wq * ft;
        f += ft;
      }
      out.at_a += (wq * (1 - u)) * f;
      out.at_b += (wq * u) * f;
      out.normal += wq * gq;
    }
  };
  // Cut at the depth table's rows between the ends (in the order along u).
  const double xa = a.x(), xb = b.x();
  double u_prev = 0;
  const std::size_t m = sb.depth.size() < 2 ? 0 : sb.x.size();
  for (std::size_t j = 0; j < m; ++j) {
    const double xi = xb >= xa ? sb.x[j] : sb.x[m - 1 - j];
    if (!((xi - xa) * (xb - xi) > 0)) continue;  // strictly between the ends
    const double u = (xi - xa) / (xb - xa);
    piece(u_prev, u);
    u_prev = u;
  }
  piece(u_prev, 1.0);
  return out;
}

}  // namespace towsim
