// Wave loads on cable elements and the body (docs/theory.md 8 "Wave loads"):
// a neutrally buoyant element or sphere moving with the water is accelerated
// exactly like it (Froude-Krylov + added mass = its own inertia times the
// water's acceleration), and drag acts on the velocity relative to the waves.
#include <gtest/gtest.h>

#include <memory>
#include <numbers>

#include "../support/models.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/waves/waves.hpp"

namespace {

using namespace towsim;

std::shared_ptr<const WaveField> sea() {
  return std::make_shared<const WaveField>(
      make_irregular_sea(3.0, 9.0, 3.3, 50, 5, Vec3(0.6, 0.8, 0), std::numeric_limits<double>::infinity(), 9.81));
}

// Neutral element (m = rho pi D^2/4 L) at rest relative to the water, for both
// added-mass models: F = Mt a_w, i.e. a_G = a_w, to round-off (1e-12 relative:
// a handful of operations on terms of size |Mt a_w|).
TEST(WaveLoads, NeutralElementFollowsTheWater) {
  for (AddedMassModel am : {AddedMassModel::Morison, AddedMassModel::IdealFluid}) {
    towsim::testing::CableSpec c;
    c.n = 1, c.length = 5, c.diameter = 0.05, c.am = am;
    c.mass_per_length = 1025 * std::numbers::pi / 4 * c.diameter * c.diameter;  // neutral
    Model m = towsim::testing::cable_model(c);
    m.fluid.waves = sea();
    const Element& el = m.cable.elements[0];
    const Vec3 e = Vec3(0.3, -0.2, -1).normalized();
    for (const Vec3& xG : {Vec3(1, 2, -3), Vec3(-10, 4, -12)})
      for (double t : {0.0, 7.1, 55.5}) {
        const Vec3 uw = m.fluid.velocity(xG, t), aw = m.fluid.acceleration(xG, t);
        Vec3 F, M;
        element_loads(m, el, e, Vec3::Zero(), uw, xG, t, F, M);
        const Vec3 expect = element_mass(el, e) * aw;
        EXPECT_LE((F - expect).norm(), 1e-12 * expect.norm() + 1e-12) << "t = " << t;
        EXPECT_LE(M.norm(), 1e-12);
        EXPECT_GT(aw.norm(), 1e-3);  // the check is not vacuous
      }
  }
}

// Drag on the relative velocity: an element moving with the water feels no
// drag, one at rest in the waves feels the drag of -u_w (checked against the
// closed form -k |u_n| u_n with no other load: Morison, Ca = 0, f = 0, at a
// depth and time where a_w is included separately).
TEST(WaveLoads, DragActsOnTheVelocityRelativeToTheWaves) {
  towsim::testing::CableSpec c;
  c.n = 1, c.length = 5, c.ca = 0, c.am = AddedMassModel::Morison;
  Model m = towsim::testing::cable_model(c);
  m.fluid.waves = sea();
  const Element& el = m.cable.elements[0];
  const Vec3 e = Vec3::UnitX(), xG(0, 0, -2);
  const double t = 3.3;
  const Vec3 uw = m.fluid.velocity(xG, t), aw = m.fluid.acceleration(xG, t);
  const double rhoV = 1025 * std::numbers::pi / 4 * el.diameter * el.diameter * el.length;
  Vec3 F, M;
  element_loads(m, el, e, Vec3::Zero(), Vec3::Zero(), xG, t, F, M);
  const Vec3 un = -(uw - uw.dot(e) * e);
  const Vec3 expect = Vec3(0, 0, -el.weight) - el.drag_factor * un.norm() * un + rhoV * aw;
  EXPECT_LE((F - expect).norm(), 1e-12 * expect.norm());
}

// A neutrally buoyant sphere body (mass = rho V, CG and buoyancy at its centre)
// moving with the water: Mw [a; alpha] + hw = F gives a = a_w and alpha = 0
// (Froude-Krylov rho V a_w plus the added-mass Ca rho V a_w), to 1e-10.
TEST(WaveLoads, NeutralSphereFollowsTheOrbitalMotion) {
  towsim::testing::CableSpec c;
  Model m = towsim::testing::cable_model(c);
  const double r = 0.5, V = 4.0 / 3 * std::numbers::pi * r * r * r;
  towsim::testing::add_sphere_body(m, 1025 * V, r, 0.5, 0.5);
  m.fluid.waves = sea();
  for (const Vec3& O : {Vec3(0, 0, -2), Vec3(30, -7, -15)})
    for (double t : {1.0, 44.4}) {
      BodyWork bw;
      bw.R = Mat3::Identity();
      bw.O = O;
      bw.vO = m.fluid.velocity(O, t);
      bw.w.setZero();
      body_inertia(m.fluid, m.bodies[0], bw, t);
      body_loads(m.fluid, m.bodies[0], t, bw);
      Vec6 rhs;
      rhs << bw.Fb, bw.Mb;
      const Vec6 acc = bw.Mw.ldlt().solve(rhs - bw.hw);
      const Vec3 aw = m.fluid.acceleration(O, t);
      EXPECT_LE((acc.head<3>() - aw).norm(), 1e-10 * aw.norm()) << "t = " << t;
      EXPECT_LE(acc.tail<3>().norm(), 1e-10);
    }
}

}  // namespace

namespace {

// A neutrally buoyant attachment (mass = rho V) moving with the water: its
// lumped load is its inertia times the water's acceleration, Fa = Ma a_w
// (Froude-Krylov + added mass; no drag at zero relative velocity), 1e-12.
TEST(WaveLoads, NeutralAttachmentFollowsTheWater) {
  towsim::testing::CableSpec c;
  Model m = towsim::testing::cable_model(c);
  m.fluid.waves = sea();
  Attachment a;
  a.joint = 2, a.volume = 0.05, a.mass = 1025 * 0.05, a.drag_area = 0.3, a.added_mass = 20;
  m.cable.attachments.push_back(a);
  Workspace ws(m);
  const Vec3 P(3, -1, -4);
  const double t = 12.5;
  ws.P[2] = P;
  ws.vP[2] = m.fluid.velocity(P, t);
  attachment_loads(m, t, ws);
  const Vec3 aw = m.fluid.acceleration(P, t);
  EXPECT_LE((ws.Fa[2] - ws.Ma[2] * aw).norm(), 1e-12 * (ws.Ma[2] * aw).norm());
  EXPECT_GT(aw.norm(), 1e-3);
}

// The water's velocity an element's loads took (element_loads' `water`) is
// the fluid's velocity at G, bit for bit (one wave sum gives the velocity
// whether or not the acceleration is asked too), and the Jacobian's drag
// damping from it equals the one that sums the waves again: exactly, in
// waves, in a current with waves, in a current alone and in still water.
TEST(WaveLoads, JacobianTakesTheWaterVelocityTheLoadsTook) {
  towsim::testing::CableSpec c;
  c.n = 1, c.length = 5;
  for (int kind = 0; kind < 4; ++kind) {
    Model m = towsim::testing::cable_model(c);
    if (kind <= 1) m.fluid.waves = sea();
    if (kind >= 1 && kind <= 2) {
      m.fluid.current_depth = {0, 50, 200};
      m.fluid.current_velocity = {Vec3(0.5, 0.1, 0), Vec3(0.3, 0.2, 0), Vec3(0.1, 0, 0)};
    }
    const Element& el = m.cable.elements[0];
    const Vec3 e = Vec3(0.3, -0.2, -1).normalized(), vG(1.9, 0.3, -0.2), fb(10, -5, -800);
    for (const Vec3& xG : {Vec3(1, 2, -3), Vec3(-10, 4, -60)})
      for (double t : {7.1, 55.5}) {
        Vec3 F, M, water;
        element_loads(m, el, e, Vec3(0.01, 0.02, 0), vG, xG, t, F, M, &water);
        const Vec3 expect = kind == 3 ? Vec3::Zero() : m.fluid.velocity(xG, t);
        for (int i = 0; i < 3; ++i) EXPECT_EQ(water[i], expect[i]) << "kind " << kind << ", t = " << t;
        Mat3 C0, C1;
        double K0, K1;
        element_local_jacobian(m, el, e, vG, xG, t, F, fb, C0, K0);
        element_local_jacobian(m, el, e, vG, xG, t, F, fb, C1, K1, &water);
        EXPECT_TRUE(C0 == C1) << "kind " << kind << ", t = " << t;
        EXPECT_EQ(K0, K1);
        EXPECT_GT(C0.norm(), 0);
      }
  }
}

}  // namespace
