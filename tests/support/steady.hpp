// Steady-tow helpers for the statics validation tests (docs/validation.md §5): the paper's
// example models, and the fluid and gravity loads of a steady configuration
// written out from docs/theory.md §3-4 with the cable's primary coefficients (never
// read back from the compiled loads).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "towsim/dynamics/state.hpp"
#include "towsim/model/model.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::validation {

/// A built-in example scenario compiled to a Model (the test fails if it does not compile).
inline Model example_model(const std::string& name) {
  const scenario::Example* e = scenario::find_example(name);
  EXPECT_NE(e, nullptr) << name;
  if (!e) return Model{};
  auto s = scenario::load_scenario_text(e->yaml, name + ".yaml", name, "");
  EXPECT_TRUE(s.ok()) << s.diags.str();
  return s.ok() ? *s.model : Model{};
}

/// Replace the tow law by a straight tow at speed V along +x, at speed from
/// t = 0 (ramp_time 0), or hold the tow point fixed when V == 0.
inline void straight_tow(Model& m, double V) {
  m.tow.mode = Tow::Mode::Motion;
  m.tow.pieces.clear();
  if (V != 0) {
    m.tow.pieces.push_back(Ramp{Vec3::UnitX(), V, 0});
  }
  towsim::finalize_tow(m.tow);  // the example's course plan no longer holds
}

/// The cable's primary coefficients (docs/theory.md §3), as a scenario gives them.
struct CableCoefficients {
  double mass_per_length;  // [kg/m]
  double diameter;         // [m]
  double cd;               // normal drag [-]
  double tangential;       // Pode f or skin Ct [-]
  double ca = 1.0;         // normal added mass [-]
};

/// My own current profile: linear in depth between the table's rows, held
/// beyond its ends (docs/theory.md §1 / scenario `current`).
inline Vec3 current_at(const Fluid& fl, double z) {
  const auto& d = fl.current_depth;
  const auto& U = fl.current_velocity;
  if (U.empty()) return Vec3::Zero();
  const double depth = -z;
  if (U.size() == 1 || depth <= d.front()) return U.front();
  if (depth >= d.back()) return U.back();
  std::size_t i = 0;
  while (depth > d[i + 1]) ++i;
  const double s = (depth - d[i]) / (d[i + 1] - d[i]);
  return (1 - s) * U[i] + s * U[i + 1];
}

/// Sum of the loads of a steady configuration (every point moving at V):
/// force, and moment about the tow point P_0 (Munk moments included for the
/// ideal-fluid form), plus the scale: the sum of the magnitudes of every
/// load, for relative errors.
struct LoadSum {
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();  // about P_0
  double force_scale = 0;      // sum of |individual forces| [N]
  double moment_scale = 0;     // sum of |individual moments about P_0| [N m]
  void add(const Vec3& F, const Vec3& arm) {
    force += F;
    moment += arm.cross(F);
    force_scale += F.norm();
    moment_scale += arm.cross(F).norm();
  }
  void add_couple(const Vec3& M) {
    moment += M;
    moment_scale += M.norm();
  }
};

/// Loads on cable and body in steady motion at V, from the configuration
/// (tow point, element axes, body attitude) and the primary data:
///  - element: apparent weight -(m' - rho A) g L z; normal drag
///    -1/2 rho Cd D L |u_n| u_n; tangential friction: Pode
///    -1/2 rho Cd f D L |u|^2 sgn_s(u.e) e or skin -1/2 rho pi D L Ct |u.e| (u.e) e;
///    ideal fluid: Munk moment ma (e.u)(u x e), ma = Ca rho A L (the
///    velocity terms of -dP/dt vanish with de/dt = 0);
///  - body: weight m_B g at the CG, buoyancy rho g (volume + spheres) at the
///    centre of the displaced volume, sphere drag -1/2 rho Cd pi r^2 |u| u at
///    each centre (spheres have no Munk moment).
/// u = V - U(z) at the point of application.
inline LoadSum steady_loads(const Model& m, const CableCoefficients& cc, const PhysicalState& s, const Vec3& V) {
  const double rho = m.fluid.rho, g = m.fluid.g, pi = std::numbers::pi;
  const double A = pi * cc.diameter * cc.diameter / 4;
  LoadSum out;
  Vec3 P = s.r0;
  for (int k = 0; k < m.cable.n(); ++k) {
    const double L = m.cable.elements[k].length;
    const Vec3 e = s.e[k];
    const Vec3 G = P + 0.5 * L * e;
    P += L * e;
    const Vec3 u = V - current_at(m.fluid, G.z());
    const double ue = u.dot(e);
    const Vec3 un = u - ue * e;
    out.add(Vec3(0, 0, -(cc.mass_per_length - rho * A) * g * L), G - s.r0);
    out.add(-0.5 * rho * cc.cd * cc.diameter * L * un.norm() * un, G - s.r0);
    if (m.cable.tangential_law == TangentialLaw::Pode) {
      const double vs = m.cable.sign_smoothing_speed;
      out.add(-0.5 * rho * cc.cd * cc.tangential * cc.diameter * L * u.squaredNorm() *
                  (ue / std::sqrt(ue * ue + vs * vs)) * e,
              G - s.r0);
    } else {
      out.add(-0.5 * rho * pi * cc.diameter * L * cc.tangential * std::abs(ue) * ue * e, G - s.r0);
    }
    if (m.cable.added_mass_model == AddedMassModel::IdealFluid) out.add_couple(cc.ca * rho * A * L * ue * u.cross(e));
  }
  if (!m.bodies.empty()) {
    const Body& b = m.bodies[0];
    const Mat3 R = s.bodies[0].q.toRotationMatrix();
    const Vec3 O = P - R * b.link_point;  // P = P_n = Q
    double vol = b.volume;
    Vec3 vol_moment = b.volume * b.cb;
    out.add(Vec3(0, 0, -b.mass * g), O + R * b.cg - s.r0);
    for (const SphereLoad& sp : b.spheres) {
      const double Vs = 4.0 / 3.0 * pi * std::pow(sp.radius, 3);
      vol += Vs;
      vol_moment += Vs * sp.center;
      const Vec3 C = O + R * sp.center;
      const Vec3 u = V - current_at(m.fluid, C.z());
      out.add(-0.5 * rho * sp.drag * pi * sp.radius * sp.radius * u.norm() * u, C - s.r0);
    }
    if (vol > 0) out.add(Vec3(0, 0, rho * g * vol), O + R * (vol_moment / vol) - s.r0);
  }
  return out;
}

/// Joints P_0..P_n of a state.
inline std::vector<Vec3> joints(const Model& m, const PhysicalState& s) {
  std::vector<Vec3> P{s.r0};
  for (int k = 0; k < m.cable.n(); ++k) P.push_back(P.back() + m.cable.elements[k].length * s.e[k]);
  return P;
}

/// The paper examples' cable coefficients (scenarios/paper-*.yaml).
inline CableCoefficients paper51_cable() { return {1.5, 0.019, 1.8, 0.0, 1.0}; }
inline CableCoefficients paper52_cable() { return {0.14, 0.010, 1.9, 0.0, 1.0}; }

}  // namespace towsim::validation
