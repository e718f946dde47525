// Part: the winch's paid-out top element (docs/theory.md "Winch"). It is a
// rigid or elastic element (rigid_element.hpp, elastic_element.hpp) whose
// material leaves the sheave: its properties scale with the paid-out length
// (Workspace::top), and its top is the material at the sheave rather than
// the tow point. This file holds what that adds to the forward dynamics:
// the top material's acceleration and the drum's equation.
#pragma once

#include <algorithm>

#include "towsim/dynamics/state.hpp"

namespace towsim::parts {

struct PaidOutElement {
  /// The winch's deployed length: the paid-out top element plus the fixed
  /// elements below it and the cable drawn in by removals (unstretched over
  /// an elastic top; as the integrator's stops at min_length/max_length see
  /// it) [m].
  static double deployed_length(const Model& model, const PhysicalState& s) {
    double L = model.winch.length_offset + paid_out_length(model, s);
    const auto& els = model.cable.elements;
    for (std::size_t k = 1; k < els.size(); ++k) L += els[k].length;
    return L;
  }

  /// Tension-controlled winch: the pay-out acceleration l'' from the drum's
  /// equation M_d l'' = T - T_set - c l', where the tension at the sheave
  /// T = -e_1 . f_0 is affine in l'': f_0 = K_0 (a + l'' e_1) + b_0 = f + l''
  /// K_0 e_1 (f the force at l'' = 0). Clamped to the acceleration limit, and
  /// to zero where the speed limit is reached and l'' would pass it, and where
  /// the drum is stopped at min_length or max_length (deployed length L [m])
  /// and l'' would take it out: there the drum holds, so the forces are those
  /// of a fixed length (not of a drum accelerating against its stop).
  static double drum_acceleration(const Winch& w, const Vec3& e1, double rate, double L, const Mat3& K0,
                                  const Vec3& f) {
    const double T0 = -e1.dot(f);      // tension at l'' = 0 [N]
    const double k = e1.dot(K0 * e1);  // dT/dl'' = -k [kg]
    double acc = (T0 - w.tension - w.damping * rate) / (w.drum_inertia + k);
    acc = std::clamp(acc, -w.max_acceleration, w.max_acceleration);
    if ((rate >= w.max_speed && acc > 0) || (rate <= -w.max_speed && acc < 0)) acc = 0;
    // The stop's round-off: the projection puts L back on the limit [m].
    const double eps = 1e-9 * std::max(1.0, L);
    if ((L <= w.min_length + eps && rate <= 0 && acc < 0) || (L >= w.max_length - eps && rate >= 0 && acc > 0)) acc = 0;
    return acc;
  }

  /// The top material's acceleration less a_0 and the pay-out's l'' term
  /// (the Coriolis terms), and the stretch lam multiplying L_1'' [-]: rigid,
  /// a_0 + l'' e_1 + 2 l' (omega_1 x e_1); elastic, a_0 + lam L_1'' e_1 +
  /// 2 lam L_1' (omega_1 x e_1) + 2 (L_1'/L_1)(l_1' - lam L_1') e_1, lam =
  /// l_1/L_1 (its velocity v_0 + lam L_1' e_1 seen in the material).
  struct Top {
    Vec3 a_extra = Vec3::Zero();  // [m/s^2, R_g]
    double lam = 1;               // [-]
    double pay_rate = 0;          // the winch's rate: l_1' (rigid) or L_1' (elastic) [m/s]
  };
  static Top top(const Model& model, const PhysicalState& s, const Workspace& ws, bool elastic) {
    Top top;
    const Vec3 e1 = s.e[0];
    if (elastic) {
      const double l = s.length_of(model, 0), Lu = s.top_unstretched;
      top.pay_rate = s.top_unstretched_rate;
      top.lam = l / Lu;
      top.a_extra = 2 * top.lam * top.pay_rate * ws.edot[0] +
                    2 * top.pay_rate / Lu * (s.length_rate_of(0) - top.lam * top.pay_rate) * e1;
    } else {
      top.pay_rate = element_length_rate(s, 0);
      top.a_extra = 2 * top.pay_rate * ws.edot[0];
    }
    return top;
  }
};

}  // namespace towsim::parts
