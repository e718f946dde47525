// The default O(n) recursion against the paper's dense Lagrange formulation:
// two independent computations of the same equations must agree to round-off.
#include <gtest/gtest.h>

#include <cstdio>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/paper.hpp"

namespace towsim {
namespace {

using testing::CableSpec;

struct AgreementCase {
  int n;
  bool body;
  Tow::Mode mode;
  bool current;
  AddedMassModel am;
};

class FormulationAgreement : public ::testing::TestWithParam<AgreementCase> {};

/// Relative difference of two vectors, scaled by the larger norm (floor 1).
double rel(const Vec3& a, const Vec3& b, double scale) { return (a - b).norm() / std::max(scale, 1.0); }

TEST_P(FormulationAgreement, SameAccelerationsAndForces) {
  const AgreementCase c = GetParam();
  CableSpec spec;
  spec.n = c.n;
  spec.length = 10.0 * c.n;
  spec.tangential = 0.02;
  spec.am = c.am;
  Model m = testing::cable_model(spec);
  if (c.body) testing::add_rich_body(m);
  if (c.current) {
    m.fluid.current_depth = {0, 50, 400};
    m.fluid.current_velocity = {Vec3(1.0, 0.3, 0), Vec3(0.5, 0.1, 0.0), Vec3(0.1, 0, 0)};
  }
  m.tow.mode = c.mode;
  m.tow.pieces.push_back(testing::ramp_piece(Vec3(1, 0.2, 0), 2.0, 15.0));
  m.tow.force_value = {Vec3(300, -50, 120)};
  std::mt19937 rng(1234 + c.n);
  Workspace ws(m);
  PaperWorkspace pw(m);
  for (int trial = 0; trial < 3; ++trial) {
    PhysicalState s = testing::random_state(m, rng);
    const double t = 3.7;
    if (c.mode == Tow::Mode::Motion) {
      const auto k = tow_kinematics(m.tow, t);
      s.r0 = k.pos, s.v0 = k.vel;
    }
    forward_dynamics(m, s, t, ws);
    // The paper's coordinates, with the paper's own pole z_g where possible.
    const PaperState p = to_paper(m, s);
    paper_dynamics(m, p, t, pw);
    // Tolerance 1e-9 relative (docs/contract.md §P8): both are exact solutions of the same
    // equations, so only round-off separates them. Errors are relative to the
    // system's own scale: the largest angular acceleration for rotations, the
    // largest joint acceleration for a0, the largest joint force for forces
    // (a tow force that results from cancelling element loads would make a
    // purely pointwise relative error meaningless). Random 2 km chains at
    // n = 200 reach a few 1e-10 on this scale.
    double amax = 1.0, fmax = 1.0;
    for (int k = 0; k < m.cable.n(); ++k) amax = std::max(amax, ws.acc.alpha[k].norm());
    for (const Vec3& f : ws.acc.joint_force) fmax = std::max(fmax, f.norm());
    const double a0max = std::max(ws.acc.a0.norm(), amax * m.cable.elements[0].length);
    double worst = 0;
    for (int k = 0; k < m.cable.n(); ++k) {
      worst = std::max(worst, rel(ws.acc.alpha[k], pw.acc.alpha[k], amax));
      EXPECT_LT(rel(ws.acc.alpha[k], pw.acc.alpha[k], amax), 1e-9) << "element " << k + 1;
    }
    worst = std::max(worst, rel(ws.acc.tow_force, pw.acc.tow_force, fmax));
    if (trial == 0) std::printf("    largest relative difference (alpha, F_R): %.2e\n", worst);
    EXPECT_LT(rel(ws.acc.a0, pw.acc.a0, a0max), 1e-9);
    EXPECT_LT(rel(ws.acc.tow_force, pw.acc.tow_force, fmax), 1e-9);
    if (c.body) {
      EXPECT_LT(rel(ws.acc.alpha_b[0], pw.acc.alpha_b[0], std::max(amax, ws.acc.alpha_b[0].norm())), 1e-9);
      EXPECT_LT(rel(ws.acc.link_force[0], pw.acc.link_force[0], fmax), 1e-9);
    }
  }
}

std::vector<AgreementCase> agreement_cases() {
  std::vector<AgreementCase> out;
  for (int n : {1, 2, 7, 40, 200})
    for (bool body : {false, true})
      for (auto mode : {Tow::Mode::Motion, Tow::Mode::Force})
        for (bool current : {false, true})
          out.push_back({n, body, mode, current, n % 2 ? AddedMassModel::IdealFluid : AddedMassModel::Morison});
  return out;
}

INSTANTIATE_TEST_SUITE_P(RandomStates, FormulationAgreement, ::testing::ValuesIn(agreement_cases()),
                         [](const auto& info) {
                           const AgreementCase& c = info.param;
                           return "n" + std::to_string(c.n) + (c.body ? "_body" : "_cable") +
                                  (c.mode == Tow::Mode::Motion ? "_motion" : "_force") +
                                  (c.current ? "_current" : "_still");
                         });

}  // namespace
}  // namespace towsim
