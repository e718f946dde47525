// Bending springs at the joints: loads and local stiffness (bending.hpp).
#include "towsim/dynamics/bending.hpp"

#include "towsim/dynamics/elastic.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace towsim {

bool has_bending(const Model& model) {
  return std::any_of(model.cable.elements.begin(), model.cable.elements.end(),
                     [](const Element& el) { return el.bending_stiffness > 0; });
}

double joint_bending_stiffness(const Element& upper, const Element& lower) {
  if (!(upper.bending_stiffness > 0) || !(lower.bending_stiffness > 0)) return 0.0;
  // Each half-element's flexibility L / (2 EI), in series.
  return 2.0 / (upper.length / upper.bending_stiffness + lower.length / lower.bending_stiffness);
}

Vec3 bending_angle(const Vec3& a, const Vec3& b) {
  const Vec3 axis = a.cross(b);
  const double s = axis.norm(), c = a.dot(b);
  if (s > 0) return std::atan2(s, c) / s * axis;
  // Parallel: no bend; opposite: pi about a direction normal to a.
  return c >= 0 ? Vec3::Zero().eval() : Vec3(std::numbers::pi * tangent_basis(a).col(0));
}

namespace {

/// The spring's stiffness at joint k (1..n-1) of the current chain, 0 at a body.
double joint_stiffness(const Model& model, const Workspace& ws, std::size_t k) {
  if (k == 0 || k >= model.cable.elements.size() || ws.body_at[k] >= 0) return 0.0;
  return joint_bending_stiffness(current_element(model, ws, k - 1), current_element(model, ws, k));
}

}  // namespace

void bending_loads(const Model& model, const PhysicalState& s, Workspace& ws) {
  if (!ws.bending) return;
  const std::size_t n = model.cable.elements.size();
  // Each interior joint's couple, +M on the element above, -M below.
  for (std::size_t k = 1; k < n; ++k) {
    const double kappa = joint_stiffness(model, ws, k);
    ws.bend[k] = kappa > 0 ? Vec3(kappa * bending_angle(s.e[k - 1], s.e[k])) : Vec3::Zero().eval();
    ws.Mom[k - 1] += ws.bend[k];
    ws.Mom[k] -= ws.bend[k];
  }
}

double element_bending_stiffness(const Model& model, const Workspace& ws, std::size_t k) {
  return joint_stiffness(model, ws, k) + joint_stiffness(model, ws, k + 1);
}

void bending_local_stiffness(const Model& model, const Workspace& ws, std::vector<double>& element_stiffness) {
  if (!ws.bending) return;
  const std::size_t n = model.cable.elements.size();
  // The spring at joint k resists the rotation of both its elements.
  for (std::size_t k = 1; k < n; ++k) {
    const double kappa = joint_stiffness(model, ws, k);
    element_stiffness[k - 1] += kappa;
    element_stiffness[k] += kappa;
  }
}

void bending_stage_couplings(const Model& model, const Workspace& ws, std::vector<double>& kappa) {
  const auto& els = model.cable.elements;
  kappa.assign(els.size() + 1, 0.0);
  if (!ws.bending) return;
  for (std::size_t k = 1; k < els.size(); ++k)
    if (!is_elastic(els[k - 1]) && !is_elastic(els[k])) kappa[k] = joint_stiffness(model, ws, k);
}

}  // namespace towsim
