// The seabed's shape and contact law (include/towsim/model/seabed.hpp).
#include "towsim/model/seabed.hpp"

#include <algorithm>
#include <cmath>

#include "towsim/model/table.hpp"

namespace towsim {

Seabed Seabed::flat(double d, double stiffness, double damping, double friction) {
  Seabed s;
  s.x = {0.0};
  s.depth = {d};
  s.stiffness = stiffness;
  s.damping = damping;
  s.friction = friction;
  return s;
}

double Seabed::depth_at(double x_g) const { return interpolate(x, depth, x_g); }

Vec3 Seabed::normal(double x_g) const {
  if (depth.size() < 2 || !(x_g >= x.front() && x_g < x.back())) return Vec3::UnitZ();  // NaN too
  const auto i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), x_g) - x.begin()) - 1;
  // z_b = -depth(x): the surface z - z_b(x) = 0 has gradient (depth'(x), 0, 1).
  const double slope = (depth[i + 1] - depth[i]) / (x[i + 1] - x[i]);
  return Vec3(slope, 0, 1).normalized();
}

double Seabed::gap(const Vec3& p) const { return (p.z() - bottom_z(p.x())) * normal(p.x()).z(); }

SeabedForce Seabed::contact(const Vec3& p, const Vec3& v, double length) const {
  SeabedForce f;
  const double h = gap(p);
  if (!(h < 0) || length <= 0) return f;
  f.length = length;
  const Vec3 n = normal(p.x());
  // Spring-damper along the normal, never pulling the point down (the
  // velocity relative to the bottom's).
  const Vec3 vr = v - velocity;
  const double vn = vr.dot(n);
  const double Fn = length * std::max(0.0, -stiffness * h - damping * vn);
  f.normal = Fn * n;
  // Smoothed Coulomb friction against the slip velocity along the bottom.
  const Vec3 ut = vr - vn * n;
  f.friction = -friction * Fn / std::sqrt(ut.squaredNorm() + slip_speed * slip_speed) * ut;
  return f;
}

void Seabed::contact_slopes(const Vec3& p, const Vec3& v, double length, const Vec3& f, Mat3& C, Mat3& K) const {
  if (length <= 0) return;
  const Vec3 nrm = normal(p.x());
  const Mat3 nn = nrm * nrm.transpose();
  K += stiffness * length * nn;
  C += damping * length * nn;
  // Friction mu |F_n| u_t / q, q = sqrt(|u_t|^2 + v_s^2): its slope on u_t,
  // mu |F_n| (P - u_t u_t^T / q^2) / q (P: projector onto the bottom's plane).
  const double fn = std::max(0.0, f.dot(nrm));
  if (friction <= 0 || fn <= 0) return;
  const Mat3 P = Mat3::Identity() - nn;
  const Vec3 ut = P * (v - velocity);
  const double q2 = ut.squaredNorm() + slip_speed * slip_speed;
  C += friction * fn / std::sqrt(q2) * (P - ut * ut.transpose() / q2);
}

}  // namespace towsim
