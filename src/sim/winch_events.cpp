// The winch's events: split and removal of the top element (docs/theory.md "Winch").
#include "towsim/sim/winch_events.hpp"

#include <cmath>

#include "towsim/dynamics/dynamics.hpp"

namespace towsim {

namespace {

/// Move the joints of bodies and attachments below the top element by `by`.
void shift_joints(Model& m, int by) {
  for (Attachment& a : m.cable.attachments)
    if (a.joint >= 1) a.joint += by;
  for (Body& b : m.bodies)
    if (b.joint >= 1) b.joint += by;
  for (std::size_t i = 1; i < m.cable.sections.size(); ++i) m.cable.sections[i].first_element += by;
}

/// Kinetic energy of state s of model m (fills ws) [J].
double energy(const Model& m, const PhysicalState& s, Workspace& ws) {
  compute_kinematics(m, s, ws);
  compute_loads(m, s, 0.0, ws);
  return kinetic_energy(m, s, ws);
}

/// Model without element 2 (the top section's first below the winch's).
Model without_second(const Model& model) {
  Model m = model;
  m.cable.elements.erase(m.cable.elements.begin() + 1);
  if (!m.cable.sections.empty()) {
    m.cable.sections[0].elements -= 1;
    m.cable.sections[0].length -= model.winch.nominal_length;
  }
  shift_joints(m, -1);
  return m;
}

/// The start of a removal: the old chain's energy [J], the removed top
/// element's kinetic energy [J], and the chord P_0 -> P_2 the next element
/// will span (length [m], direction [-], P_2's velocity relative to the
/// sheave [m/s], R_g).
struct TopRemoval {
  double E_old = 0, removed_energy = 0, L = 0;
  Vec3 e = Vec3::UnitZ(), dv2 = Vec3::Zero();
};
TopRemoval top_removal(const Model& model, const PhysicalState& s) {
  TopRemoval t;
  Workspace ws(model);
  t.E_old = energy(model, s, ws);
  const Element& el = ws.top;
  t.removed_energy = 0.5 * ws.vG[0].dot(ws.Mt[0] * ws.vG[0]) +
                     0.5 * (el.inertia + el.added_inertia) * s.w[0].squaredNorm();
  const Vec3 d = ws.P[2] - ws.P[0];
  t.L = d.norm();
  t.e = d / t.L;
  t.dv2 = ws.vP[2] - s.v0;
  return t;
}

}  // namespace

PhysicalState split_elastic_state(const Model& model, const PhysicalState& s) {
  PhysicalState out = s;
  const double Le = model.winch.nominal_length;
  const double Lu = s.top_unstretched, Lr = s.top_unstretched_rate;  // L_1 [m], L_1' [m/s]
  const double l = element_length(model, s, 0), lr = element_length_rate(s, 0);
  out.length.assign(s.e.size(), 0.0);
  out.length_rate.assign(s.e.size(), 0.0);
  for (std::size_t k = 0; k < s.e.size(); ++k)
    out.length[k] = element_length(model, s, k), out.length_rate[k] = element_length_rate(s, k);
  // The new joint is the material point at fraction f = (L_1 - L_e)/L_1 of
  // the top element: the upper part keeps L_1 - L_e of the material, the
  // lower one L_e, both at the old strain; the new joint keeps its material
  // velocity v_T + f (v_{P_1} - v_T), v_T = v_0 + (l/L_1) L_1' e_1.
  const double f = (Lu - Le) / Lu;
  const double l_up = f * l;
  const double lr_up = l / Lu * Lr * (1 - f) + f * lr;
  out.e.insert(out.e.begin() + 1, s.e[0]);
  out.w.insert(out.w.begin() + 1, s.w[0]);
  out.length[0] = l_up;
  out.length_rate[0] = lr_up;
  out.length.insert(out.length.begin() + 1, l - l_up);
  out.length_rate.insert(out.length_rate.begin() + 1, lr - lr_up);
  out.top_unstretched = Lu - Le;
  return out;
}

WinchEvent winch_event(const Model& model, const PhysicalState& s) {
  const Winch& w = model.winch;
  if (!w.active() || model.cable.elements.empty()) return WinchEvent::None;
  // The paid-out material decides: l_1, or L_1 over an elastic top element.
  const double l = paid_out_length(model, s);
  if (l > w.split_at * w.nominal_length) return WinchEvent::Split;
  const bool more = !model.cable.sections.empty() ? model.cable.sections[0].elements > 1 : model.cable.n() > 1;
  if (l < w.remove_at * w.nominal_length && more) return WinchEvent::Remove;
  return WinchEvent::None;
}

Model split_model(const Model& model) {
  Model m = model;
  auto& els = m.cable.elements;
  // The top element is the section's template (nominal length): copy it.
  const Element nominal = scaled_element(els.front(), m.winch.nominal_length);
  els.insert(els.begin() + 1, nominal);
  if (!m.cable.sections.empty()) {
    m.cable.sections[0].elements += 1;
    m.cable.sections[0].length += m.winch.nominal_length;
  }
  shift_joints(m, 1);
  return m;
}

PhysicalState split_state(const Model& model, const PhysicalState& s) {
  if (elastic_winch(model)) return split_elastic_state(model, s);
  PhysicalState out = s;
  const double Le = model.winch.nominal_length;
  const double l = element_length(model, s, 0);
  out.length.assign(s.e.size(), 0.0);
  out.length_rate.assign(s.e.size(), 0.0);
  for (std::size_t k = 0; k < s.e.size(); ++k) out.length[k] = element_length(model, s, k);
  out.length_rate[0] = element_length_rate(s, 0);
  // Two collinear elements, same rotation: the material keeps its velocity.
  out.e.insert(out.e.begin() + 1, s.e[0]);
  out.w.insert(out.w.begin() + 1, s.w[0]);
  out.length[0] = l - Le;
  out.length.insert(out.length.begin() + 1, Le);
  out.length_rate.insert(out.length_rate.begin() + 1, 0.0);
  return out;
}

Removal remove_top(const Model& model, const PhysicalState& s, double t, double rate) {
  (void)t;
  if (elastic_winch(model)) return remove_elastic_top(model, s, rate);
  Removal r;
  const TopRemoval top = top_removal(model, s);
  const double E_old = top.E_old;
  r.removed_energy = top.removed_energy;
  const double l = element_length(model, s, 0);
  // The next element now spans the sheave P_0 to its own bottom joint P_2.
  const double L = top.L;  // [m]
  const Vec3& e = top.e;
  const Vec3& dv2 = top.dv2;         // P_2's velocity relative to the sheave [m/s]
  const double r_star = dv2.dot(e);  // provisional pay-out speed [m/s]
  const Vec3 w = e.cross(dv2 - r_star * e) / L;

  r.model = without_second(model);
  // Cable drawn in by straightening the kink at P_1 (zero when collinear).
  r.model.winch.length_offset += l + model.winch.nominal_length - L;

  PhysicalState& n = r.state;
  n = s;
  n.e.erase(n.e.begin());
  n.w.erase(n.w.begin());
  n.length.assign(n.e.size(), 0.0);
  n.length_rate.assign(n.e.size(), 0.0);
  for (std::size_t k = 1; k < n.e.size(); ++k) n.length[k] = element_length(model, s, k + 1);
  n.e[0] = e;
  n.w[0] = w;
  n.length[0] = L;
  n.length_rate[0] = r_star;
  // The pay-out speed jumps from r* to `rate`: the chain's impulsive response.
  Workspace ws(r.model);
  r.energy_before_impulse = energy(r.model, n, ws);
  const Vec3 jump = (rate - r_star) * e;
  r.before_impulse = n, r.jump = jump;
  tow_velocity_jump(r.model, n, jump, ws);
  r.impulse = ws.acc.tow_force;
  for (std::size_t k = 0; k < n.w.size(); ++k) n.w[k] += ws.acc.alpha[k];
  for (std::size_t b = 0; b < n.bodies.size(); ++b) n.bodies[b].w += ws.acc.alpha_b[b];
  n.length_rate[0] = rate;
  const Vec3 v_before = s.v0 + r_star * e, v_after = s.v0 + rate * e;
  r.impulse_work = r.impulse.dot(0.5 * (v_before + v_after));
  r.energy_lost = E_old - energy(r.model, n, ws);
  return r;
}

Removal remove_elastic_top(const Model& model, const PhysicalState& s, double rate) {
  Removal r;
  const TopRemoval top = top_removal(model, s);
  r.removed_energy = top.removed_energy;
  // The next element takes in the top one's material (L_1 + L_2) and spans
  // the sheave P_0 to its own bottom joint P_2, which keeps its position and
  // velocity; l and l' are free coordinates here: no impulse.
  const double l = top.L;  // [m]
  const Vec3& e = top.e;
  const Vec3& dv2 = top.dv2;  // P_2's velocity relative to the sheave [m/s]
  const double lr = dv2.dot(e);
  r.model = without_second(model);
  PhysicalState& n = r.state;
  n = s;
  n.e.erase(n.e.begin());
  n.w.erase(n.w.begin());
  n.length.erase(n.length.begin());
  n.length_rate.erase(n.length_rate.begin());
  n.e[0] = e;
  n.w[0] = e.cross(dv2 - lr * e) / l;
  n.length[0] = l;
  n.length_rate[0] = lr;
  n.top_unstretched = s.top_unstretched + model.cable.elements[1].length;
  n.top_unstretched_rate = rate;
  Workspace ws(r.model);
  r.energy_before_impulse = energy(r.model, n, ws);
  r.energy_lost = top.E_old - r.energy_before_impulse;
  r.before_impulse = n;
  return r;
}

}  // namespace towsim
