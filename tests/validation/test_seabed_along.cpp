// The seabed's contact along elements (MODEL.md 10 "Contact along elements",
// docs/theory.md §3.2, docs/validation.md): the integrated law of one
// segment against its closed forms and a fine quadrature of the point law; a
// cable laid onto a flat bottom from a stationary tow point (top tension
// against the closed forms of the discrete equilibrium, w h + w L/2 at the
// joints and w h + w L/(2 sqrt 3) along elements: first order in L; the
// touchdown joint of a steady tow meets MODEL.md 10's 0.1 %, test_touchdown.cpp); a cable dragged
// with friction (lying tension gradient mu w, top tension w h + mu w l_lying,
// with its measured order in the element length); statics and the settled
// dynamics agreeing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/model/seabed_segment.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

constexpr double kRho = 1025, kG = 9.81;  // the test models' water [kg/m^3] and gravity [m/s^2]

/// Apparent weight per metre of a test cable, from its own data [N/m].
double apparent_weight(const testing::CableSpec& c) {
  return (c.mass_per_length - kRho * std::numbers::pi / 4 * c.diameter * c.diameter) * kG;
}

// ---------------------------------------------------------------------------
// One segment (segment_contact) against closed forms.
// ---------------------------------------------------------------------------
// Lying flat, sunk by d: k d L on it, half at each end; no moment.
TEST(SeabedSegment, LyingSegmentCarriesKDeltaL) {
  const Seabed sb = Seabed::flat(50, 1e5, 1e3, 0.5);
  const double d = 1e-3, L = 4;
  const Vec3 a(0, 0, -50 - d), b(L, 0, -50 - d);
  const SegmentContact c = segment_contact(sb, a, Vec3::Zero(), b, Vec3::Zero());
  // 1e-11: the quadrature is exact here; the rest is the round-off of the
  // gap (z - z_b ~ 50 m, eps 50 / d ~ 1e-11 relative to d = 1 mm).
  EXPECT_NEAR(c.total().z(), 1e5 * d * L, 1e-11 * 1e5 * d * L);
  EXPECT_NEAR(c.at_a.z(), 0.5 * 1e5 * d * L, 1e-11 * 1e5 * d * L);
  EXPECT_NEAR(c.length, L, 1e-15 * L);
  EXPECT_NEAR(c.length_a, 0.5 * L, 1e-15 * L);
  EXPECT_NEAR(c.moment(a, b, 0.5 * (a + b)).norm(), 0, 1e-12 * 1e5 * d * L * L);
  EXPECT_EQ(c.first, 0.0);
}

// Crossing the bottom: a gap H_a above at a, H_b below at b. The penetration
// grows linearly from the crossing u* = H_a / (H_a + H_b) to b, so the force
// is k (H_a + H_b) L (1 - u*)^2 / 2 and its share at b
// k (H_a + H_b) L (1 - u*)^2 (2 + u*) / 6 (integral of (u - u*) u).
TEST(SeabedSegment, CrossingSegmentHasTheTriangleLoad) {
  const Seabed sb = Seabed::flat(50, 1e5, 1e3, 0.0);
  const double Ha = 0.3, Hb = 0.1, L = 5;
  const Vec3 a(0, 0, -50 + Ha), b(std::sqrt(L * L - (Ha + Hb) * (Ha + Hb)), 0, -50 - Hb);
  const SegmentContact c = segment_contact(sb, a, Vec3::Zero(), b, Vec3::Zero());
  const double us = Ha / (Ha + Hb), k = 1e5;
  const double F = k * (Ha + Hb) * L * (1 - us) * (1 - us) / 2;
  const double Fb = k * (Ha + Hb) * L * (1 - us) * (1 - us) * (2 + us) / 6;
  // Exact quadrature; 1e-11: the round-off of the gaps (50 m against 0.1 m).
  EXPECT_NEAR(c.total().z(), F, 1e-11 * F);
  EXPECT_NEAR(c.at_b.z(), Fb, 1e-11 * F);
  EXPECT_NEAR(c.length, (1 - us) * L, 1e-11 * L);
  EXPECT_NEAR(c.first, us, 1e-11);
}

// On a sloped table, crossing two of its rows, moving (damping and
// friction): the integral against the point law summed over 2e5 midpoint
// pieces (its error ~ (1/2e5)^2 relative where smooth, and O(ds) at the
// contact's ends, where the integrand vanishes linearly: (ds)^2 again);
// 1e-6 relative leaves room for both.
TEST(SeabedSegment, SlopedBottomMatchesTheFineQuadratureOfThePointLaw) {
  Seabed sb;
  sb.x = {0, 10, 20};
  sb.depth = {50, 51, 49};
  sb.stiffness = 1e5, sb.damping = 1e3, sb.friction = 0.5;
  const Vec3 a(-2, 0.3, -50.02), b(23, -0.2, -49.03), va(0.2, 0.1, -0.01), vb(0.05, -0.1, 0.004);
  const SegmentContact c = segment_contact(sb, a, va, b, vb);
  const int N = 200000;
  const double L = (b - a).norm();
  Vec3 Fa = Vec3::Zero(), Fb = Vec3::Zero(), Ft = Vec3::Zero();
  double len = 0;
  for (int i = 0; i < N; ++i) {
    const double u = (i + 0.5) / N;
    const SeabedForce f = sb.contact(a + u * (b - a), va + u * (vb - va), L / N);
    Fa += (1 - u) * f.total();
    Fb += u * f.total();
    Ft += f.friction;
    len += f.length;
  }
  std::printf("sloped segment: |F_a - quadrature| / |F| = %.2e, |F_b - quadrature| / |F| = %.2e, length %.6f m\n",
              (c.at_a - Fa).norm() / (Fa + Fb).norm(), (c.at_b - Fb).norm() / (Fa + Fb).norm(), c.length);
  ASSERT_GT(Fb.norm(), 0);
  EXPECT_LT((c.at_a - Fa).norm(), 1e-6 * (Fa + Fb).norm());
  EXPECT_LT((c.at_b - Fb).norm(), 1e-6 * (Fa + Fb).norm());
  EXPECT_LT((c.friction - Ft).norm(), 1e-6 * (Fa + Fb).norm());
  EXPECT_NEAR(c.length, len, 2 * L / N);  // the midpoint pieces' resolution L / N ~ 1.3e-4 m at each end
}

// ---------------------------------------------------------------------------
// 90 m of cable (1.5 kg/m, 19 mm) laid from a stationary tow point onto a
// flat frictionless bottom 60 m down, 15 to 180 elements (every count puts
// a joint exactly on the bottom level). At rest the suspended part hangs
// straight down to that joint, the corner C, which cannot sink (the column
// is 60 m long and rigid). T = w h + S_0, S_0 the shear the corner carries:
// - at the joints, the lying part rests sunk by delta = w / k, the corner is
//   off the bottom and carries half of the first lying element:
//   S_0 = w L / 2 (docs/theory.md), first order in L;
// - along elements, the contact level is raised by the rest sink
//   (Seabed::rest_sink), so the lying part rests with its axis on the
//   bottom's level, where the column ends: each lying element carries its
//   own weight, no lying joint carries a shear, S_0 = 0 and T = w h at every
//   element count (MODEL.md 10's 0.1 %, here to the statics' residual).
// Checked to 1e-6 w L (the statics' residual) plus 2 w delta (a sink's
// tilt), with the touchdown at 60 m of arc and 30 m lying (within 1 mm).
// ---------------------------------------------------------------------------
Model laydown_model(int n, testing::CableSpec& cs, double mu, bool along) {
  cs.n = n;
  cs.length = 90;
  Model m = testing::cable_model(cs);
  m.seabed = Seabed::flat(60, 1e5, 1e3, mu);
  m.seabed->along_elements = along;
  m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point stays at the origin
  return m;
}

TEST(SeabedAlong, LaidCableTopTensionHasTheCornersClosedForm) {
  for (bool along : {false, true}) {
    for (int n : {15, 30, 45, 90, 180}) {
      testing::CableSpec cs;
      const Model m = laydown_model(n, cs, 0.0, along);
      const double w = apparent_weight(cs), L = cs.length / n, h = 60;
      const StaticsResult r_s = solve_statics(m, Vec3::Zero());
      ASSERT_TRUE(r_s.converged) << n << ": " << r_s.message;
      const double T = r_s.tow_force.norm(), S0 = along ? 0.0 : 0.5 * w * L;
      // The lying joints' shear against S_0, and their axial force.
      const auto corner = static_cast<std::size_t>(std::lround(h / L));
      double worst_shear = 0, worst_axial = 0;
      for (std::size_t j = corner + 1; j + 1 < r_s.sample.node_pos.size(); ++j) {
        worst_shear = std::max(worst_shear, std::abs(r_s.sample.tension[j] - S0));
        worst_axial = std::max(worst_axial, std::abs(r_s.sample.axial[j]));
      }
      std::printf(
          "laid, %s, n = %3d: (T - w h) / (w L) = %.5f (closed form %.5f), (T - w h) / (w h) = %.2e; touchdown %.5f m "
          "(x %.4f), lying %.5f m; lying joints: max |tension - S_0| %.1e N, max |axial| %.1e N\n",
          along ? "along elements" : "at joints", n, (T - w * h) / (w * L), S0 / (w * L), (T - w * h) / (w * h),
          r_s.sample.touchdown_arc_length, r_s.sample.touchdown.x(), r_s.sample.lying_length, worst_shear, worst_axial);
      EXPECT_NEAR(T, w * h + S0, 1e-6 * w * L + w * 2 * w / 1e5) << n;  // + w delta-level: the sinks' tilt
      if (along) {
        EXPECT_LT(worst_shear, 1e-6 * w * L) << n;
      }
      // Axial force: the shear S times the sinks' tilt (<= delta / L): below w delta.
      EXPECT_LT(worst_axial, w * w / 1e5) << n;
      EXPECT_NEAR(r_s.sample.touchdown_arc_length, h, 1e-3) << n;
      EXPECT_NEAR(r_s.sample.lying_length, cs.length - h, 1e-3) << n;
      EXPECT_NEAR(r_s.sample.touchdown.z(), -h, 1e-3) << n;
    }
  }
}

// ---------------------------------------------------------------------------
// Statics and the dynamics agree: the same 90 m laid in 30 elements along
// elements (mu 0.5, which the smoothed law turns off at rest), 20 s of the
// dynamics (rosenbrock, tolerance 1e-8) from the statics' result stay there:
// top tension within 1e-6 relative, touchdown and lying length within
// 1e-6 m, joint speeds below 1e-5 m/s (the integration error of a 1e-8
// tolerance on a state at rest, far below these; a contact law differing
// between the two would move the lying part by its sink, 1.2e-4 m, and the
// tension by up to w L / 2). (A fall from a straight start does not settle in
// minutes here: the smoothed friction's creep holds a horizontal tension.)
// ---------------------------------------------------------------------------
TEST(SeabedAlong, DynamicsStayAtTheStatics) {
  testing::CableSpec cs;
  Model m = laydown_model(30, cs, 0.5, true);
  const StaticsResult r = solve_statics(m, Vec3::Zero());
  ASSERT_TRUE(r.converged) << r.message;
  m.initial.kind = Initial::Kind::Steady;
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-8;
  m.sim.time_step = 0.01;
  m.sim.duration = 20;
  m.sim.output_interval = 5;
  const auto samples = testing::run(m);
  ASSERT_FALSE(samples.empty());
  const Sample& last = samples.back();
  double vmax = 0;
  for (const Sample& smp : samples)
    for (const Vec3& v : smp.node_vel) vmax = std::max(vmax, v.norm());
  const double T = last.tow_force.norm(), Ts = r.tow_force.norm();
  std::printf(
      "dynamics from the statics (along elements), 20 s: T %.6f N vs %.6f N (%+.2e), touchdown %.7f m vs %.7f m, "
      "lying %.7f m vs %.7f m, max joint speed %.2e m/s\n",
      T, Ts, (T - Ts) / Ts, last.touchdown_arc_length, r.sample.touchdown_arc_length, last.lying_length,
      r.sample.lying_length, vmax);
  EXPECT_NEAR(T, Ts, 1e-6 * Ts);
  EXPECT_NEAR(last.touchdown_arc_length, r.sample.touchdown_arc_length, 1e-6);
  EXPECT_NEAR(last.lying_length, r.sample.lying_length, 1e-6);
  EXPECT_LT(vmax, 1e-5);
}

// ---------------------------------------------------------------------------
// The same 90 m in 45 elements falling from straight (along (1, 0, -0.5))
// onto the frictionless bottom comes to rest (the scenario's defaults:
// rosenbrock, tolerance 1e-5) with the statics' top tension w h. Only drag
// stops the lying part sliding to and fro along the frictionless bottom
// (quadratic drag: a slow decay), so after 2400 s it still moves by
// millimetres: measured (T - w h) / (w h) = 2.1e-5 and the end 2.8 mm from
// its rest 30 m out. Checked to 1e-4 relative (a tenth of MODEL.md 10's
// 0.1 %, five times the sliding's share) and 1 cm.
// ---------------------------------------------------------------------------
TEST(SeabedAlong, FallOntoAFrictionlessBottomComesToRestAtTheTopTensionWh) {
  testing::CableSpec cs;
  Model m = laydown_model(45, cs, 0.0, true);
  m.initial.kind = Initial::Kind::Direction;
  m.initial.direction = Vec3(1, 0, -0.5).normalized();
  m.sim.integrator = Integrator::Rosenbrock;
  m.sim.tolerance = 1e-5;
  m.sim.duration = 2400;
  m.sim.output_interval = 100;
  const auto samples = testing::run(m);
  ASSERT_FALSE(samples.empty());
  const Sample& last = samples.back();
  ASSERT_NEAR(last.t, 2400, 1e-9);
  const double w = apparent_weight(cs), T = last.tow_force.norm();
  std::printf("fall onto a frictionless bottom, 45 elements, 2400 s: (T - w h) / (w h) = %.2e, end x %.6f m\n",
              (T - 60 * w) / (60 * w), last.node_pos.back().x());
  EXPECT_NEAR(T, 60 * w, 1e-4 * 60 * w);
  EXPECT_NEAR(last.node_pos.back().x(), 30, 1e-2);
}

// ---------------------------------------------------------------------------
// A cable dragged along a flat bottom with friction mu at U = 0.5 m/s (no
// tangential drag: normal drag leaves the tension's magnitude alone, so the
// continuous cable has T_top = T_td + w h and T_td = mu s w l_lying,
// s = U / sqrt(U^2 + v_s^2) the law's smoothing). On the lying part the
// horizontal force grows by mu s w per metre (each lying element's contact
// carries its weight exactly, its axis on the bottom's level: the rest sink). The top tension's Richardson differences
// over halved element lengths converge at second order in L, and it stays
// within 0.5 % of w L of the closed form on the discrete lying length
// (measured; docs/validation.md).
// ---------------------------------------------------------------------------
TEST(SeabedAlong, DraggedCableClosedFormsConvergeAtSecondOrder) {
  const double U = 0.5, mu = 0.5, h = 110;
  std::vector<double> Ts, errs, Ls;
  for (int n : {15, 30, 60, 120}) {
    testing::CableSpec cs;
    cs.n = n;
    cs.length = 300;
    cs.tangential = 0;
    Model m = testing::cable_model(cs);
    m.seabed = Seabed::flat(h, 1e5, 1e3, mu);
    m.seabed->along_elements = true;
    m.tow.mode = Tow::Mode::Motion;
    m.tow.pieces = {testing::ramp_piece(Vec3::UnitX(), U, 0.0)};
    const double w = apparent_weight(cs), L = cs.length / n;
    const double s = U / std::hypot(U, kSeabedSlipSpeed);
    const StaticsResult r = solve_statics(m, Vec3(U, 0, 0));
    ASSERT_TRUE(r.converged) << n << ": " << r.message;
    // The lying part's tension gradient: at a lying joint j, 3 elements past
    // the touchdown, the horizontal force is the friction on the length l_j
    // beyond it, mu s w l_j, up to the touchdown's disturbance of the
    // contact there.
    const double td = r.sample.touchdown_arc_length;
    const auto j = static_cast<std::size_t>(std::ceil(td / L - 1e-9)) + 3;
    ASSERT_LT(j, r.sample.node_pos.size()) << n;
    const double lj = cs.length - static_cast<double>(j) * L;
    const double grad_err = (r.joint_force[j].x() - mu * s * w * lj) / (mu * s * w * lj);
    const double T = r.tow_force.norm(), Tc = w * h + mu * s * w * r.sample.lying_length;
    std::printf(
        "dragged, n = %3d (L = %5.2f m): f_x / (mu s w l) - 1 = %+.2e at %zu; T = %.4f N, closed form "
        "%.4f N, (T - Tc) / (w L) = %+.3e, lying %.4f m\n",
        n, L, grad_err, j, T, Tc, (T - Tc) / (w * L), r.sample.lying_length);
    EXPECT_LT(std::abs(grad_err), 0.02) << n;
    Ts.push_back(T);
    errs.push_back(std::abs(T - Tc));
    Ls.push_back(L);
  }
  // Orders: log2 of successive ratios, of the closed-form error and of the
  // Richardson differences T(L) - T(L/2), printed.
  for (std::size_t i = 0; i + 1 < errs.size(); ++i) {
    const double p = std::log2(errs[i] / errs[i + 1]);
    std::printf("dragged: order of |T - Tc| between L = %.2f and %.2f m: %.3f\n", Ls[i], Ls[i + 1], p);
  }
  for (std::size_t i = 0; i + 2 < Ts.size(); ++i) {
    const double p = std::log2(std::abs(Ts[i] - Ts[i + 1]) / std::abs(Ts[i + 1] - Ts[i + 2]));
    std::printf("dragged: Richardson order of T over L = %.2f, %.2f, %.2f m: %.3f\n", Ls[i], Ls[i + 1], Ls[i + 2], p);
  }
  // T converges at second order (the last Richardson triple, 10, 5, 2.5 m:
  // 2.000 measured; 0.3 for the pre-asymptotic spread). The closed form on the
  // discrete lying length stays within 0.5 % of w L from L = 10 m on
  // (measured -3.2e-3, -2.8e-3, -4.2e-3 w L: the touchdown element's share).
  const double p_rich = std::log2(std::abs(Ts[1] - Ts[2]) / std::abs(Ts[2] - Ts[3]));
  EXPECT_NEAR(p_rich, 2.0, 0.3);
  for (std::size_t i = 1; i < errs.size(); ++i)
    EXPECT_LT(errs[i], 5e-3 * apparent_weight(testing::CableSpec{}) * Ls[i]) << Ls[i];
}

}  // namespace
}  // namespace towsim
