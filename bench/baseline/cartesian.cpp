// The earlier formulation (Cartesian joints, multipliers, central differences):
// see cartesian.hpp. Benchmark baseline only.
#include "cartesian.hpp"

#include <cmath>
#include <numbers>

#include "towsim/hydro/loads.hpp"

namespace towsim::baseline {

Chain cable_chain(const Model& m) {
  Chain c;
  c.model = m;
  for (const Element& el : m.cable.elements) {
    Link l;
    l.length = el.length;
    l.is_element = true;
    l.element = el;
    c.links.push_back(l);
  }
  c.point.assign(c.links.size() + 1, PointMass{});
  return c;
}

void add_dumbbell(Chain& c, double ms, double r, double cd, double ca, double spacing) {
  const Fluid& f = c.model.fluid;
  const double V = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  PointMass s;
  s.mass = ms;
  s.added_mass = ca * f.rho * V;
  s.drag = 0.5 * f.rho * cd * std::numbers::pi * r * r;
  s.weight = (ms - f.rho * V) * f.g;
  c.point.back() = s;  // leading sphere at the cable's last joint
  Link rod;
  rod.length = spacing;
  rod.J = 2 * 0.4 * ms * r * r;  // the spheres' own rotational inertia
  c.links.push_back(rod);
  c.point.push_back(s);  // second sphere
}

CentralDifference::CentralDifference(const Chain& chain, double h, VelocityEstimate ve)
    : c_(chain), h_(h), ve_(ve), N_(static_cast<int>(chain.links.size())) {
  const std::size_t J = N_ + 1;
  x_.resize(J), xm1_.resize(J), xm2_.resize(J), v_.resize(J), Q_.resize(J), a_.resize(J), xnew_.resize(J);
  e_.resize(J), g_.resize(J), lam_.resize(J);
  Md_.resize(J), Mo_.resize(J);
  Dinv_.resize(J), U_.resize(J), y_.resize(J);
}

void CentralDifference::start(const std::vector<Vec3>& x) {
  x_ = x;
  xm1_ = x;
  xm2_ = x;
  x_[0] = tow_kinematics(c_.model.tow, 0).pos;
  xm1_[0] = tow_kinematics(c_.model.tow, -h_).pos;
  xm2_[0] = tow_kinematics(c_.model.tow, -2 * h_).pos;
  t_ = 0;
  steps_ = 0;
}

double CentralDifference::length_error() const {
  double err = 0;
  for (int k = 1; k <= N_; ++k) err = std::max(err, std::abs((x_[k] - x_[k - 1]).norm() / c_.links[k - 1].length - 1));
  return err;
}

void CentralDifference::velocities() {
  v_[0] = tow_kinematics(c_.model.tow, t_).vel;
  for (int k = 1; k <= N_; ++k) {
    if (ve_ == VelocityEstimate::Backward || steps_ == 0)
      v_[k] = (x_[k] - xm1_[k]) / h_;
    else
      v_[k] = (3 * x_[k] - 4 * xm1_[k] + xm2_[k]) / (2 * h_);
  }
}

void CentralDifference::assemble_and_solve() {
  const Model& m = c_.model;
  const double h2 = h_ * h_;
  for (int k = 0; k <= N_; ++k) {
    Md_[k].setZero();
    Mo_[k].setZero();
    Q_[k].setZero();
  }
  // Links: geometry, consistent mass, loads at the centre (half to each end).
  for (int k = 1; k <= N_; ++k) {
    const Link& l = c_.links[k - 1];
    const Vec3 d = x_[k] - x_[k - 1];
    const double len = d.norm();
    const Vec3 e = d / len;
    e_[k] = e;
    g_[k] = len - l.length;
    const Mat3 Nn = Mat3::Identity() - e * e.transpose();
    if (l.is_element) {
      const Element& el = l.element;
      const Mat3 Mk = el.mass * Mat3::Identity() + el.added_mass * Nn;
      Md_[k - 1] += Mk / 3;
      Md_[k] += Mk / 3;
      Mo_[k] += Mk / 6;
      const Vec3 vG = 0.5 * (v_[k - 1] + v_[k]);
      const Vec3 edot = (v_[k] - v_[k - 1]) / l.length;
      const Vec3 xG = 0.5 * (x_[k - 1] + x_[k]);
      Vec3 F, Mom;
      element_loads(m, el, e, edot, vG, xG, t_, F, Mom);
      const Vec3 Mx = Mom.cross(e) / l.length;  // a moment about G as a couple on the ends
      Q_[k - 1] += 0.5 * F - Mx;
      Q_[k] += 0.5 * F + Mx;
    }
    if (l.J > 0) {
      const Mat3 Jn = l.J / (l.length * l.length) * Nn;
      Md_[k - 1] += Jn;
      Md_[k] += Jn;
      Mo_[k] -= Jn;
    }
  }
  // Point masses.
  for (int k = 1; k <= N_; ++k) {
    const PointMass& p = c_.point[k];
    if (p.mass == 0 && p.added_mass == 0) continue;
    Md_[k] += (p.mass + p.added_mass) * Mat3::Identity();
    const Vec3 u = v_[k] - m.fluid.current(x_[k].z());
    Q_[k] += Vec3(0, 0, -p.weight) - p.drag * u.norm() * u;
  }
  // Imposed tow point: its second difference.
  const Vec3 x0new = tow_kinematics(m.tow, t_ + h_).pos;
  a_[0] = (x0new - 2 * x_[0] + xm1_[0]) / h2;
  xnew_[0] = x0new;

  // Block-tridiagonal saddle-point system in z_k = [a_k; lambda_k], k = 1..N:
  //   Mo_k a_{k-1} + Md_k a_k + Mo_{k+1} a_{k+1} - lambda_k e_k + lambda_{k+1} e_{k+1} = Q_k
  //   e_k . (a_k - a_{k-1}) = r_k = -(g_k + e_k . (dx_k - dx_{k-1})) / h^2,  dx = x_n - x_{n-1}
  // Block Thomas elimination (forward), then back substitution.
  Eigen::Matrix4d Dp, Lk;
  for (int k = 1; k <= N_; ++k) {
    const Vec3& e = e_[k];
    Eigen::Matrix4d D;
    D.topLeftCorner<3, 3>() = Md_[k];
    D.topRightCorner<3, 1>() = -e;
    D.bottomLeftCorner<1, 3>() = e.transpose();
    D(3, 3) = 0;
    Eigen::Vector4d b;
    b.head<3>() = Q_[k];
    b(3) = -(g_[k] + e.dot((x_[k] - xm1_[k]) - (x_[k - 1] - xm1_[k - 1]))) / h2;
    if (k == 1) {
      b.head<3>() -= Mo_[1] * a_[0];
      b(3) += e.dot(a_[0]);
    } else {
      Lk.setZero();
      Lk.topLeftCorner<3, 3>() = Mo_[k];
      Lk.bottomLeftCorner<1, 3>() = -e.transpose();
      const Eigen::Matrix4d W = Lk * Dinv_[k - 1];
      D -= W * U_[k - 1];
      b -= W * y_[k - 1];
    }
    Dinv_[k] = D.partialPivLu().inverse();
    y_[k] = b;
    U_[k].setZero();
    if (k < N_) {
      U_[k].topLeftCorner<3, 3>() = Mo_[k + 1];
      U_[k].topRightCorner<3, 1>() = e_[k + 1];  // geometry of every link is computed above
    }
  }
  Eigen::Vector4d z = Dinv_[N_] * y_[N_];
  a_[N_] = z.head<3>();
  lam_[N_] = z(3);
  for (int k = N_ - 1; k >= 1; --k) {
    z = Dinv_[k] * (y_[k] - U_[k] * z);
    a_[k] = z.head<3>();
    lam_[k] = z(3);
  }
  // Tow force: P_0's own equation, Md_0 a_0 + Mo_1 a_1 = Q_0 + F_R - lambda_1 e_1.
  FR_ = Md_[0] * a_[0] + Mo_[1] * a_[1] - Q_[0] + lam_[1] * e_[1];
}

bool CentralDifference::step() {
  velocities();
  assemble_and_solve();
  const double h2 = h_ * h_;
  for (int k = 1; k <= N_; ++k) xnew_[k] = 2 * x_[k] - xm1_[k] + h2 * a_[k];
  std::swap(xm2_, xm1_);
  std::swap(xm1_, x_);
  std::swap(x_, xnew_);
  t_ += h_;
  ++steps_;
  for (int k = 1; k <= N_; ++k)
    if (!x_[k].allFinite()) return false;
  return true;
}

}  // namespace towsim::baseline
