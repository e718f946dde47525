// Elastic cable elements: the element's step of the O(n) recursion
// (docs/theory.md §5.4 "Elastic elements").
#include "towsim/dynamics/elastic.hpp"

#include <cmath>
#include <limits>

namespace towsim {

double axial_wave_speed(const Element& el) { return std::sqrt(el.axial_stiffness * el.length / el.mass); }

double rk4_axial_step_limit(const Element& el) {
  if (!is_elastic(el)) return std::numeric_limits<double>::infinity();
  const double undamped = 0.8 * el.length / axial_wave_speed(el);
  // Axial damping c_a shares the stiffness's mode shapes (damping force
  // c_a l'/L beside EA (l - L)/L): ratio zeta = (c_a / EA) omega / 2 at the
  // highest mode omega = 2 sqrt(3) c / L. Overdamped (zeta > 1), its fast
  // root -omega (zeta + sqrt(zeta^2 - 1)) is real: RK4 needs |h lambda| <= 2.785
  // there (2.7 kept, as 0.8 L / c keeps 2.77 of 2.83 on the imaginary axis).
  const double omega = 2 * std::sqrt(3.0) * axial_wave_speed(el) / el.length;
  const double zeta = el.axial_damping / el.axial_stiffness * omega / 2;
  if (zeta <= 1) return undamped;
  return std::min(undamped, 2.7 / (omega * (zeta + std::sqrt(zeta * zeta - 1))));
}

void elastic_backward(const Vec3& e, double l, const Mat3& Mt, const Vec3& F, const Vec3& M, const Mat3& Kk,
                      const Vec3& bk, ElasticWork& ew, Mat3& K, Vec3& b) {
  // d-equation (Lagrange on d with the rod's kinetic energy):
  // (Mt/3 + Kk) d'' = F/2 + (M x e)/l - T e - bk - (Mt/2 + Kk) a.
  ew.G = 0.5 * Mt + Kk;
  ew.Ainv = (Mt / 3 + Kk).inverse();
  ew.r = 0.5 * F + M.cross(e) / l - ew.T * e - bk;
  // Force through the top joint: f = Mt (a + d''/2) - F + f_k, f_k = Kk (a + d'') + bk,
  // i.e. K = Mt + Kk - G A^-1 G, b = G A^-1 r + bk - F. With G = A + Mt/6
  // these are K = Mt/3 - (Mt/6) A^-1 (Mt/6), b = (M x e)/l - F/2 - T e +
  // (Mt/6) A^-1 r: no difference of large terms when Kk >> Mt (a heavy body
  // below), and K stays bounded (the spring isolates the inertia below).
  const Mat3 M6 = Mt / 6;
  const Mat3 H = M6 * ew.Ainv;
  K = Mt / 3 - H * M6;
  K = 0.5 * (K + K.transpose()).eval();  // symmetric in exact arithmetic
  b = M.cross(e) / l - 0.5 * F - ew.T * e + H * ew.r;
}

Vec3 elastic_forward(const ElasticWork& ew, const Vec3& e, const Vec3& w, double l, double l_rate, const Vec3& a,
                     Vec3& alpha, double& l_acc) {
  Vec3 dd = ew.Ainv * (ew.r - ew.G * a);
  // d'' = l'' e + 2 l' (w x e) + l (alpha x e) - l |w|^2 e.
  const double along = e.dot(dd);
  l_acc = along + l * w.squaredNorm();
  const Vec3 beta = (dd - along * e - 2 * l_rate * w.cross(e)) / l;  // alpha x e
  alpha = e.cross(beta);
  return dd;
}

Vec3 elastic_forward(const ElasticWork& ew, const Vec3& e, const Vec3& w, double l, double l_rate, const Vec3& a,
                     const Vec3& shift, Vec3& alpha, double& l_acc) {
  Vec3 dd = ew.Ainv * (ew.r - ew.G * a);
  // d_1'' = dd + shift = l'' e + 2 l' (w x e) + l (alpha x e) - l |w|^2 e.
  const Vec3 d1 = dd + shift;
  const double along = e.dot(d1);
  l_acc = along + l * w.squaredNorm();
  const Vec3 beta = (d1 - along * e - 2 * l_rate * w.cross(e)) / l;  // alpha x e
  alpha = e.cross(beta);
  return dd;
}

}  // namespace towsim
