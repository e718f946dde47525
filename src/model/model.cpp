// Derived quantities of the compiled model (docs/theory.md §2-4).
#include "towsim/model/model.hpp"
#include "towsim/model/table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace towsim {

namespace {
/// Skew-symmetric matrix [a]x such that [a]x b = a x b.
Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

/// 6x6 inertia about O_t of a load with translational inertia A at point c and
/// rotational inertia B (body axes): T^T diag(A) T + diag(0, B), T = [I, -[c]x].
Mat6 point_inertia_6(const Mat3& A, const Mat3& B, const Vec3& c) {
  const Mat3 C = skew(c);
  Mat6 m;
  m.topLeftCorner<3, 3>() = A;
  m.topRightCorner<3, 3>() = -A * C;
  m.bottomLeftCorner<3, 3>() = C * A;
  m.bottomRightCorner<3, 3>() = B - C * A * C;
  return m;
}

}  // namespace

double Cable::total_length() const {
  double s = 0;
  for (const auto& e : elements) s += e.length;
  return s;
}

Element make_element(double length, double mass_per_length, double diameter, double cd, double tangential_coef,
                     TangentialLaw law, double ca, const Fluid& fluid) {
  const double area = std::numbers::pi * diameter * diameter / 4;  // A_i [m^2]
  Element e{};
  e.length = length;
  e.mass = mass_per_length * length;
  e.diameter = diameter;
  e.inertia = e.mass * length * length / 12;
  e.added_mass = ca * fluid.rho * area * length;
  e.added_inertia = e.added_mass * length * length / 12;
  e.weight = (e.mass - fluid.rho * area * length) * fluid.g;
  e.drag_factor = 0.5 * fluid.rho * cd * diameter * length;
  e.friction_factor = law == TangentialLaw::Pode
                          ? 0.5 * fluid.rho * cd * tangential_coef * diameter * length
                          : 0.5 * fluid.rho * std::numbers::pi * diameter * length * tangential_coef;
  return e;
}

Element scaled_element(const Element& el, double length) {
  const double r = length / el.length;  // [-]
  Element e = el;
  e.length = length;
  for (double* x : {&e.mass, &e.added_mass, &e.weight, &e.drag_factor, &e.friction_factor}) *x *= r;
  e.inertia *= r * r * r;
  e.added_inertia *= r * r * r;
  return e;
}

void finalize_body(Body& body, const Fluid& fluid) {
  const double rho = fluid.rho;
  // Rigid-body mass matrix about O_t: inertia about O_t = I_G - m [r_G]x [r_G]x.
  body.rigid_mass = point_inertia_6(body.mass * Mat3::Identity(), body.inertia_cg, body.cg);

  // Fluid (added) mass: user matrix plus each load model's share, and displaced volume.
  body.fluid_mass = body.added_mass;
  double volume = body.volume;
  Vec3 moment = body.volume * body.cb;  // first moment of displaced volume [m^4]
  for (const auto& s : body.spheres) {
    const double v = 4.0 / 3.0 * std::numbers::pi * std::pow(s.radius, 3);
    body.fluid_mass += point_inertia_6(s.added_mass * rho * v * Mat3::Identity(), Mat3::Zero(), s.center);
    volume += v;
    moment += v * s.center;
  }
  for (const auto& c : body.cylinders) {
    const double v = std::numbers::pi * c.diameter * c.diameter / 4 * c.length;
    const double ma = c.added_mass * rho * v;
    const Mat3 normal = Mat3::Identity() - c.axis * c.axis.transpose();
    body.fluid_mass += point_inertia_6(ma * normal, ma * c.length * c.length / 12 * normal, c.center);
    volume += v;
    moment += v * c.center;
  }
  body.displaced_volume = volume;
  body.buoyancy_center = volume > 0 ? Vec3(moment / volume) : body.cg;
  // Once here rather than at each evaluation (body_inertia, body_loads).
  body.total_mass = body.rigid_mass + body.fluid_mass;
  body.damped = !body.linear_damping.isZero() || !body.quadratic_damping.isZero();
}

int control_count(const Body& body) {
  return static_cast<int>(std::count_if(body.surfaces.begin(), body.surfaces.end(),
                                        [](const LiftingSurface& ls) { return ls.depth_control.has_value(); }));
}

const Body* end_body(const Model& model) {
  if (model.bodies.empty() || model.bodies.back().inline_body) return nullptr;
  return &model.bodies.back();
}

int body_joint(const Model& model, const Body& body) { return body.joint < 0 ? model.cable.n() : body.joint; }

}  // namespace towsim
