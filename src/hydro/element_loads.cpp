// Loads on a cable element (docs/theory.md §3; paper 2.3-2.43).
#include <cmath>
#include <numbers>

#include "drag_laws.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim {

double smooth_sign(double x, double v_s) { return x / std::sqrt(x * x + v_s * v_s); }

void element_loads(const Model& model, const Element& el, const Vec3& e, const Vec3& edot, const Vec3& vG,
                   const Vec3& xG, double t, Vec3& F, Vec3& M, Vec3* water) {
  const Fluid& fluid = model.fluid;
  // Weight and buoyancy (apparent weight), along -z.
  F = Vec3(0, 0, -el.weight);
  M.setZero();
  if (water) water->setZero();
  if (fluid.rho == 0) return;

  // Velocity relative to the water, split along and across the element (in
  // still water, no current nor waves, the water's velocity is +0: u = vG).
  // With waves, the water's velocity and accelerations from one sum over the harmonics.
  Vec3 uw = Vec3::Zero(), rate = Vec3::Zero(), aw = Vec3::Zero();
  if (fluid.waves)
    fluid.flow(xG, vG, t, uw, rate, aw);
  else if (fluid.has_current())
    uw = fluid.velocity(xG, t);
  const Vec3 u = fluid.waves || fluid.has_current() ? Vec3(vG - uw) : vG;
  if (water) *water = uw;
  const double ue = u.dot(e);
  const Vec3 un = u - ue * e;

  // A faired section's loading tables replace the default laws below.
  const auto sec = static_cast<std::size_t>(el.section);
  const Section* faired = sec < model.cable.sections.size() ? &model.cable.sections[sec] : nullptr;
  const double v_s = model.cable.sign_smoothing_speed;

  // Normal pressure drag (paper 2.41), or the table f_n(phi).
  if (faired != nullptr && !faired->normal_loading.empty())
    F += faired->normal_loading.normal_force(el.drag_factor, un, ue, v_s);
  else
    F -= drag_laws::normal_drag(el.drag_factor, un);

  // Tangential friction: the table f_t(phi), Pode/Landweber (paper 2.43) or
  // skin friction. Without friction (friction_factor 0) the default laws
  // would subtract a signed zero, which leaves F as it is but for the sign of
  // an exactly zero component: skipped (a square root and a division).
  if (faired != nullptr && !faired->tangential_loading.empty()) {
    F += faired->tangential_loading.tangential_force(el.drag_factor, un, ue, e, v_s);
  } else if (el.friction_factor != 0) {
    F -= drag_laws::tangential_friction(model.cable.tangential_law, el.friction_factor, u, ue, e, v_s);
  }

  // Added mass: the relative velocity also changes as G moves through a
  // non-uniform flow, du/dt = a_G - rate seen by G; that rate is known here.
  if (!fluid.uniform()) {
    const Vec3 dU = fluid.waves ? rate : fluid.rate_seen(xG, vG, t);
    F += el.added_mass * (dU - dU.dot(e) * e);
  }
  // Waves: Froude-Krylov rho V a_w (the added mass's part is in rate_seen).
  if (fluid.waves) F += fluid.rho * std::numbers::pi / 4 * el.diameter * el.diameter * el.length * aw;
  // Ideal fluid: -dP/dt velocity terms and the Munk moment (paper 2.42).
  if (model.cable.added_mass_model == AddedMassModel::IdealFluid) {
    F += el.added_mass * (edot * ue + e * edot.dot(u));
    M += el.added_mass * ue * u.cross(e);
  }
}

}  // namespace towsim

namespace towsim {

void attachment_loads(const Model& model, double t, Workspace& ws) {
  const Fluid& fluid = model.fluid;
  for (std::size_t k = 0; k < ws.Ma.size(); ++k) ws.Ma[k].setZero(), ws.Fa[k].setZero();
  for (const Attachment& a : model.cable.attachments) {
    const auto k = static_cast<std::size_t>(a.joint);
    // Inertia: own mass plus isotropic added mass, moving with the joint.
    ws.Ma[k].diagonal().array() += a.mass + a.added_mass;
    // Apparent weight, then drag on the velocity relative to the water.
    ws.Fa[k].z() -= (a.mass - fluid.rho * a.volume) * fluid.g;
    if (fluid.rho == 0) continue;
    const Vec3 u = ws.vP[k] - fluid.velocity(ws.P[k], t);
    ws.Fa[k] -= drag_laws::point_drag(0.5 * fluid.rho * a.drag_area, u);
    // Added mass in a non-uniform flow: the water's velocity seen by the
    // moving joint changes at a known rate (as for the elements).
    if (!fluid.uniform()) ws.Fa[k] += a.added_mass * fluid.rate_seen(ws.P[k], ws.vP[k], t);
    // Waves: Froude-Krylov rho V a_w.
    if (fluid.waves) ws.Fa[k] += fluid.rho * a.volume * fluid.acceleration(ws.P[k], t);
  }
}

}  // namespace towsim
