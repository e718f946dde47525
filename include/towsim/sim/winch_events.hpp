// The winch's events: the top element splits as it grows and is removed as
// it shrinks (docs/theory.md "Winch"). The Model is immutable: each event
// derives a model with one element more or less in the top section, and
// maps the state into it.
#pragma once

#include "towsim/dynamics/state.hpp"

namespace towsim {

/// What the winch needs after a step.
enum class WinchEvent {
  None,
  Split,   // l_1 > split_at * L_e: split the top element
  Remove,  // l_1 < remove_at * L_e: remove it
};

/// The event due for state s of `model` (None without a winch, or when the
/// top section has a single element left: it is never removed).
WinchEvent winch_event(const Model& model, const PhysicalState& s);

/// `model` with one more element of nominal length L_e below the top one,
/// in the top section; joints of bodies and attachments move down by one.
Model split_model(const Model& model);

/// The state of `model` mapped onto split_model(model): the top element of
/// length l_1 becomes an element of l_1 - L_e (still the winch's) over one of
/// L_e, both with the old e_1 and omega_1. Positions, velocities and
/// momentum are unchanged.
PhysicalState split_state(const Model& model, const PhysicalState& s);

/// split_state over an elastic top element (unstretched L_1, stretched
/// l_1): the upper element keeps L_1 - L_e of the material, the new one L_e,
/// both at the old strain (l_1 splits in proportion, unstretched length is
/// conserved exactly); the new joint keeps its material velocity.
PhysicalState split_elastic_state(const Model& model, const PhysicalState& s);

/// Result of removing the top element.
struct Removal {
  Model model;                       // the model with one element less
  PhysicalState state;               // the state mapped into it, after the impulse
  double energy_lost = 0;            // kinetic energy before - after (the removed element's included) [J]
  double removed_energy = 0;         // kinetic energy the removed element had (its material joins the next one) [J]
  double energy_before_impulse = 0;  // kinetic energy of the mapped state before the impulse [J]
  double impulse_work = 0;           // work of the impulse at the sheave, lambda . (v_before + v_after) / 2 [J]
  Vec3 impulse = Vec3::Zero();       // impulse of the sheave on the cable [N s, R_g]
  PhysicalState before_impulse;      // the mapped state before the impulse (pay-out speed r*)
  Vec3 jump = Vec3::Zero();          // the sheave's velocity jump the impulse makes, (rate - r*) e [m/s, R_g]
};

/// Remove the top element (length l_1 small) of state s at t: the next
/// element becomes the winch's, from the sheave P_0 to its own bottom joint
/// (every joint below keeps its position and velocity), with e, omega and a
/// provisional pay-out speed that match its bottom joint's velocity; the
/// pay-out speed is then brought back to `rate` (the schedule's, or the
/// old one) by an impulse through the chain (tow_velocity_jump).
Removal remove_top(const Model& model, const PhysicalState& s, double t, double rate);

/// remove_top over an elastic top element: the next element takes in its
/// material (L_1 + L_2, unstretched length conserved exactly) and spans P_0
/// to P_2 (l_1 = |P_2 - P_0|: the strain becomes the two elements' average
/// when collinear); every joint below keeps its position and velocity and
/// the pay-out speed its value `rate`: no impulse (l_1' is free).
Removal remove_elastic_top(const Model& model, const PhysicalState& s, double rate);

}  // namespace towsim
