// The body's analytic load derivatives (body_load_derivatives, the damping D
// and the stiffness about O_t, KO, of the Rosenbrock-W stage matrix,
// docs/theory.md §6.3) against central finite differences of body_loads, as
// body_local_jacobian computed them before: every load model (gravity,
// buoyancy, a thruster, sphere and cylinder drag, a lifting surface below and
// past stall and in reverse flow, linear and quadratic damping), in still
// water, a sheared current and waves.
//
// Tolerance kRel = 1e-6 relative to |D| (|KO|): the differences' own error is
// truncation h^2/6 |g'''| ~ 1e-12 relative (steps h = 1e-6 of the speeds'
// scale, 1e-6 rad) plus round-off ~ eps |g| / h, |g| <= ~5e2 N (the body's
// weight dominates) against |D|, |KO| >= ~1: ~1e-7 relative at worst. The
// analytic values themselves carry ~1e-15 relative; in waves their water
// gradients are central differences too (same size). 1e-6 leaves a margin
// of 10 over the worst round-off and still catches any wrong term (each is
// >= 1e-3 of the total here).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include "../support/models.hpp"
#include "towsim/dynamics/implicit.hpp"
#include "towsim/hydro/loads.hpp"
#include "towsim/waves/waves.hpp"

namespace {

using namespace towsim;

constexpr double kRel = 1e-6;

/// -d(F; M)/d(v_O; omega) and -dM/dtheta by central differences of body_loads.
void finite_differences(const Fluid& fluid, const Body& body, const BodyWork& bw, double t, Mat6& D, Mat3& KO) {
  BodyWork p = bw;
  auto loads = [&] {
    body_loads(fluid, body, t, p);
    Vec6 g;
    g << p.Fb, p.Mb;
    return g;
  };
  const double dv = 1e-6 * std::max(1.0, bw.vO.norm()), dw = 1e-6 * std::max(1.0, bw.w.norm());
  for (int j = 0; j < 6; ++j) {
    const double d = j < 3 ? dv : dw;
    Vec3& x = j < 3 ? p.vO : p.w;
    x[j % 3] += d;
    const Vec6 gp = loads();
    x[j % 3] -= 2 * d;
    const Vec6 gm = loads();
    x[j % 3] += d;
    D.col(j) = -(gp - gm) / (2 * d);
  }
  const double da = 1e-6;
  for (int j = 0; j < 3; ++j) {
    p.R = Eigen::AngleAxisd(da, Vec3::Unit(j)).toRotationMatrix() * bw.R;
    const Vec6 gp = loads();
    p.R = Eigen::AngleAxisd(-da, Vec3::Unit(j)).toRotationMatrix() * bw.R;
    const Vec6 gm = loads();
    KO.col(j) = -(gp.tail<3>() - gm.tail<3>()) / (2 * da);
  }
  p.R = bw.R;
}

Model rich_model(int flow) {
  Model m;
  if (flow >= 1) {  // sheared current, rows away from the body's depth (~20 m)
    m.fluid.current_depth = {0.0, 10.0, 50.0};
    m.fluid.current_velocity = {Vec3(0.8, 0.3, 0), Vec3(0.5, 0.1, 0), Vec3(0.1, -0.2, 0)};
  }
  if (flow == 2)
    m.fluid.waves = std::make_shared<const WaveField>(
        make_irregular_sea(3.0, 9.0, 3.3, 50, 5, Vec3(0.6, 0.8, 0), std::numeric_limits<double>::infinity(), 9.81));
  towsim::testing::add_rich_body(m);
  m.bodies.back().thrusters.push_back({Vec3(-0.8, 0.05, 0.02), Vec3(1, 0.1, 0).normalized(), {0.0}, {25.0}});
  return m;
}

TEST(BodyJacobian, AnalyticDerivativesMatchFiniteDifferencesOfTheLoads) {
  std::mt19937 rng(7);
  std::normal_distribution<double> N(0.0, 1.0);
  auto rnd = [&] { return Vec3(N(rng), N(rng), N(rng)); };
  const char* flows[] = {"still water", "sheared current", "waves"};
  double worst = 0;
  for (int flow = 0; flow < 3; ++flow) {
    const Model m = rich_model(flow);
    const Body& body = m.bodies.back();
    // Speeds: slow and fast, ahead (fin below stall), sideways (past stall),
    // astern (reverse flow).
    for (const Vec3& v0 : {Vec3(2.0, 0.1, -0.05), Vec3(0.3, 0.4, 0.2), Vec3(-1.5, 0.05, 0.1), Vec3(0.2, -0.1, 1.0)})
      for (int trial = 0; trial < 3; ++trial) {
        BodyWork bw;
        bw.R = Eigen::AngleAxisd(0.3 * N(rng), rnd().normalized()).toRotationMatrix();
        bw.O = Vec3(0, 0, -20) + rnd();
        bw.vO = v0 + 0.05 * rnd();
        bw.w = 0.3 * rnd();
        const double t = 3.0 + trial;
        Mat6 D, Dfd;
        Mat3 KO, KOfd;
        body_load_derivatives(m.fluid, body, bw, t, D, KO);
        finite_differences(m.fluid, body, bw, t, Dfd, KOfd);
        const double eD = (D - Dfd).norm() / Dfd.norm(), eK = (KO - KOfd).norm() / KOfd.norm();
        EXPECT_LE(eD, kRel) << flows[flow] << ", v " << v0.transpose() << "\n" << D << "\n\n" << Dfd;
        EXPECT_LE(eK, kRel) << flows[flow] << ", v " << v0.transpose() << "\n" << KO << "\n\n" << KOfd;
        worst = std::max({worst, eD, eK});
      }
  }
  std::printf("[measured] body D, KO vs central differences: max rel err %.3e (tol %.0e)\n", worst, kRel);
}

}  // namespace
