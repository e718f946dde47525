// Models built in code for the tests (no YAML), with the paper's numbers.
#pragma once

#include <numbers>
#include <random>
#include <vector>

#include "towsim/dynamics/state.hpp"
#include "towsim/model/model.hpp"
#include "towsim/model/winch.hpp"

namespace towsim::testing {

/// Cable parameters of a test model.
struct CableSpec {
  int n = 5;                     // elements
  double length = 100;           // total [m]
  double mass_per_length = 1.5;  // [kg/m]
  double diameter = 0.019;       // [m]
  double cd = 1.8;               // normal drag [-]
  double tangential = 0.0;       // f (pode) or ct (skin) [-]
  TangentialLaw law = TangentialLaw::Pode;
  double ca = 1.0;  // normal added mass [-]
  AddedMassModel am = AddedMassModel::IdealFluid;
};

/// A model of a cable only, towed by `tow`, in a fluid of density rho.
inline Model cable_model(const CableSpec& c, double rho = 1025, double g = 9.81) {
  Model m;
  m.fluid.rho = rho;
  m.fluid.g = g;
  m.cable.tangential_law = c.law;
  m.cable.added_mass_model = c.am;
  for (int i = 0; i < c.n; ++i)
    m.cable.elements.push_back(
        make_element(c.length / c.n, c.mass_per_length, c.diameter, c.cd, c.tangential, c.law, c.ca, m.fluid));
  m.tow.mode = Tow::Mode::Motion;
  return m;
}

/// The paper 5.2 sphere (3 kg, r = 0.05 m, link on its surface) attached to m.
inline void add_sphere_body(Model& m, double mass = 3.0, double radius = 0.05, double cd = 0.5, double ca = 0.5) {
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = mass;
  b.inertia_cg = 0.4 * mass * radius * radius * Mat3::Identity();
  b.cg = Vec3::Zero();
  b.link_point = Vec3(0, 0, radius);
  b.spheres.push_back({Vec3::Zero(), radius, cd, ca});
  finalize_body(b, m.fluid);
}

/// The whole cable of m (n elements, `length` [m]) on an imposed winch:
/// one section, the element length as nominal and minimum top length, the
/// pay-out rates [m/s] from `times` [s] (piecewise constant).
inline void impose_winch(Model& m, int n, double length, const std::vector<double>& times,
                         const std::vector<double>& rates) {
  const double Le = length / n;
  m.cable.sections.push_back({"cable", 0, n, length, 0});
  m.winch.mode = Winch::Mode::Imposed;
  m.winch.nominal_length = Le;
  m.winch.min_length = Le;
  m.winch.schedule = schedule_from_rate(times, rates, length, m.winch.min_length, m.winch.max_length);
}

/// The paper 5.2 cable (0.14 kg/m, 10 mm, Cd 1.9; Pode f = tangential) in
/// n elements over `length` [m].
inline CableSpec paper52_cable(int n, double length, double tangential = 0.0) {
  CableSpec spec;
  spec.n = n;
  spec.length = length;
  spec.mass_per_length = 0.14;
  spec.diameter = 0.010;
  spec.cd = 1.9;
  spec.tangential = tangential;
  return spec;
}

/// The paper 5.2 tow (scenarios/paper-3d-turn.yaml, bench/scenarios/km-*):
/// paper52_cable(n, length), a sphere at its end (the paper's 3 kg,
/// r = 0.05 m unless given), and the tow law: the tow point reaches 1.57 m/s
/// along x in 15 s, then turns to port on a 7.5 m circle.
inline Model paper52_turn(int n, double length, double body_mass = 3.0, double body_radius = 0.05) {
  Model m = cable_model(paper52_cable(n, length));
  add_sphere_body(m, body_mass, body_radius);
  m.tow.pieces.push_back(Ramp{Vec3::UnitX(), 1.57, 15});
  m.tow.pieces.push_back(Turn{7.5, 15, true});
  return m;
}

/// A body with every load model and off-diagonal terms, for agreement tests.
inline void add_rich_body(Model& m) {
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 40;
  b.inertia_cg << 2.0, 0.1, -0.05, 0.1, 5.0, 0.2, -0.05, 0.2, 5.5;
  b.cg = Vec3(-0.1, 0.02, -0.05);
  b.link_point = Vec3(0.4, 0.0, 0.15);
  b.volume = 0.02;
  b.cb = Vec3(-0.05, 0, 0.03);
  b.added_mass.diagonal() << 3, 20, 22, 0.5, 2, 2.1;
  b.added_mass(1, 5) = b.added_mass(5, 1) = 0.7;
  b.linear_damping.diagonal() << 5, 10, 10, 1, 2, 2;
  b.quadratic_damping.diagonal() << 10, 60, 60, 1, 5, 5;
  b.spheres.push_back({Vec3(0.3, 0, 0), 0.1, 0.5, 0.5});
  b.cylinders.push_back({Vec3(-0.2, 0, 0), Vec3::UnitX(), 1.2, 0.15, 1.2, 0.01, 1.0});
  LiftingSurface fin{Vec3(-0.7, 0, 0.1), Vec3::UnitX(), Vec3::UnitZ(), 0.1, 2 * std::numbers::pi, 0.26, 0.01, 0.05,
                     {0.0, 10.0},        {0.0, 0.1}};
  b.surfaces.push_back(fin);
  finalize_body(b, m.fluid);
}

/// A chain of every kind of part: a heavy section of `n_top` elements, an
/// in-line body (the rich body, jointed at link_point and lower_link_point),
/// a lighter section of `n_low` elements with different properties, an end
/// sphere, and attachments at joints 1 and n_top + 1 (when not at a body).
inline Model two_part_model(int n_top = 3, int n_low = 4) {
  CableSpec top;
  top.n = n_top;
  top.length = 15.0 * n_top;
  top.mass_per_length = 4.0;
  top.diameter = 0.03;
  top.tangential = 0.02;
  Model m = cable_model(top);
  add_rich_body(m);
  m.bodies.back().inline_body = true;
  m.bodies.back().joint = n_top;
  m.bodies.back().name = "depressor";
  m.bodies.back().lower_link_point = Vec3(-0.5, 0.1, -0.2);
  for (int i = 0; i < n_low; ++i)
    m.cable.elements.push_back(make_element(6.0, 0.8, 0.012, 1.2, 0.02, m.cable.tangential_law, 0.9, m.fluid));
  add_sphere_body(m);
  if (n_top >= 2) m.cable.attachments.push_back({1, 15.0, 20.0, 0.004, 0.05, 3.0});
  if (n_low >= 2) m.cable.attachments.push_back({n_top + 1, 15.0 * n_top + 6.0, 5.0, 0.01, 0.02, 8.0});
  return m;
}

/// A random physical state: unit vectors anywhere (poles included), angular
/// velocities normal to them, random body attitude and rates.
inline PhysicalState random_state(const Model& m, std::mt19937& rng, double rate = 0.5) {
  std::normal_distribution<double> N(0.0, 1.0);
  auto rnd = [&] { return Vec3(N(rng), N(rng), N(rng)); };
  PhysicalState s = PhysicalState::hanging(m);
  s.r0 = rnd();
  s.v0 = rnd();
  for (int k = 0; k < m.cable.n(); ++k) {
    s.e[k] = rnd().normalized();
    const Vec3 w = rate * rnd();
    s.w[k] = w - w.dot(s.e[k]) * s.e[k];
  }
  // Drawn even without a body, so that every model sees the same sequence.
  const Quat q = Quat(N(rng), N(rng), N(rng), N(rng)).normalized();
  const Vec3 wb = rate * rnd();
  for (auto& b : s.bodies) b.q = q, b.w = wb;
  return s;
}

}  // namespace towsim::testing
