// Statics for every tow heading and current direction (issue 15): 36 headings
// x 3 current directions, with and without a body, and a two-part tow. The
// independent truth is rotational symmetry: a uniform current and a tow
// heading rotated together by the same angle about the vertical see the same
// relative flow, so the equilibrium must be the same one rotated (the solver
// knows nothing of this). Each body must also fly nose first (its x axis
// along the relative flow), the stable equilibrium a run settles to.
// docs/validation.md section 5.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>

#include "../support/steady.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kCurrent = 0.5;  // current speed [m/s], a quarter of the 4-knot tow

struct HeadingCase {
  std::string example;
  bool body;     // keep the example's bodies
  int headings;  // tow headings spread over 360 degrees
};
void PrintTo(const HeadingCase& c, std::ostream* os) { *os << c.example << (c.body ? " with body" : " cable only"); }

/// Rotation by angle a about the vertical [rad].
Mat3 Rz(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

class StaticsHeadings : public ::testing::TestWithParam<HeadingCase> {};

TEST_P(StaticsHeadings, ConvergeForEveryHeadingAndCurrent) {
  const HeadingCase c = GetParam();
  Model m = validation::example_model(c.example);
  if (!c.body) m.bodies.clear();
  const double speed = final_tow_velocity(m.tow).norm();
  ASSERT_GT(speed, 1.0);
  // Reference solution per relative angle (current direction - heading), to compare rotated copies.
  struct Ref {
    double heading;
    StaticsResult r;
  };
  std::map<int, Ref> refs;
  double worst_residual = 0, worst_force = 0, worst_shape = 0, worst_attitude = 0;
  int max_iterations = 0;
  for (int ic = 0; ic < 3; ++ic) {
    const double cur = 120.0 * ic * kDeg;  // current towards 0, 120, 240 degrees
    m.fluid.current_depth = {0};
    m.fluid.current_velocity = {kCurrent * Vec3(std::cos(cur), std::sin(cur), 0)};
    for (int ih = 0; ih < c.headings; ++ih) {
      const double h = 360.0 / c.headings * ih * kDeg;
      const Vec3 V = speed * Vec3(std::cos(h), std::sin(h), 0);
      const StaticsResult r = solve_statics(m, V);
      ASSERT_TRUE(r.converged) << "heading " << h / kDeg << " deg, current towards " << cur / kDeg
                               << " deg: " << r.message;
      worst_residual = std::max(worst_residual, r.residual);
      max_iterations = std::max(max_iterations, r.iterations);
      // Every body flies nose first: body x along the flow relative to it.
      const Vec3 flow = V - m.fluid.current_velocity[0];
      for (const BodyState& b : r.state.bodies)
        EXPECT_GT((b.q * Vec3::UnitX()).dot(flow.normalized()), 0.5)
            << "heading " << h / kDeg << " deg, current towards " << cur / kDeg << " deg: body flies backwards";
      const int rel = static_cast<int>(std::lround(std::remainder(cur - h, 2 * M_PI) / kDeg + 360)) % 360;
      auto it = refs.find(rel);
      if (it == refs.end()) {
        refs.emplace(rel, Ref{h, r});
        continue;
      }
      // The same relative flow: the reference equilibrium rotated by the heading change.
      const Mat3 R = Rz(h - it->second.heading);
      const StaticsResult& ref = it->second.r;
      worst_force = std::max(worst_force, (r.tow_force - R * ref.tow_force).norm() / ref.tow_force.norm());
      for (std::size_t k = 0; k < r.state.e.size(); ++k)
        worst_shape = std::max(worst_shape, (r.state.e[k] - R * ref.state.e[k]).norm());
      for (std::size_t b = 0; b < r.state.bodies.size(); ++b) {
        const Mat3 Rb = r.state.bodies[b].q.toRotationMatrix(), Rr = R * ref.state.bodies[b].q.toRotationMatrix();
        worst_attitude = std::max(worst_attitude, (Rb - Rr).norm());
      }
    }
  }
  std::cout << std::setprecision(3) << "[measured] statics headings " << c.example << (c.body ? " + body" : "") << ": "
            << 3 * c.headings << " cases converged, worst residual " << worst_residual << " rad/s^2, at most "
            << max_iterations << " iterations; rotated copies: |dF_R|/|F_R| " << worst_force << ", |de| " << worst_shape
            << ", |dR_body| " << worst_attitude << "\n";
  // 1e-7: the equilibria are converged to angular accelerations < 1e-9 rad/s^2
  // (the statics' criterion); the angles they leave undetermined scale as
  // alpha I / (stiffness of the equilibrium) ~ 1e-9 * (m L^2) / (T L) with
  // tensions T ~ 1e3-1e4 N on 20-50 m elements: < 1e-8. Round-off of the
  // rotation itself is 1e-15.
  constexpr double kRotated = 1e-7;
  EXPECT_LT(worst_force, kRotated);
  EXPECT_LT(worst_shape, kRotated);
  EXPECT_LT(worst_attitude, kRotated);
}

INSTANTIATE_TEST_SUITE_P(StaticsAnyHeading, StaticsHeadings,
                         ::testing::Values(HeadingCase{"sea-state-tow", false, 36},
                                           HeadingCase{"sea-state-tow", true, 36},
                                           HeadingCase{"two-part-tow", true, 12}),
                         [](const auto& info) {
                           std::string s = info.param.example + (info.param.body ? "_body" : "_cable");
                           for (char& ch : s)
                             if (ch == '-') ch = '_';
                           return s;
                         });

// A set stop flag (SIGINT/SIGTERM in the CLI) ends the steady solve at once,
// and a run starting `initial: steady` ends "interrupted" before t = 0.
TEST(StaticsStop, StopFlagInterruptsSolveAndSteadyStart) {
  Model m = validation::example_model("sea-state-tow");
  const volatile int stop = 1;
  const StaticsResult r = solve_statics(m, final_tow_velocity(m.tow), &stop);
  EXPECT_TRUE(r.interrupted);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("interrupted"), std::string::npos) << r.message;
  m.initial.kind = Initial::Kind::Steady;
  MemorySink sink;
  const RunStats rs = simulate(m, sink, {}, &stop);
  EXPECT_EQ(rs.status, "interrupted") << rs.message;
  EXPECT_TRUE(sink.samples.empty());
}

// A steady start that cannot converge fails the run with the statics'
// message (what to try), before t = 0, instead of an internal error.
TEST(StaticsStop, UnconvergedSteadyStartFailsWithTheMessage) {
  Model m = validation::example_model("sea-state-tow");
  m.initial.kind = Initial::Kind::Steady;
  // No equilibrium exists for a tow speed that is not a number (the compiler
  // refuses it in a scenario; the library must still fail cleanly).
  m.tow.pieces.clear();
  m.tow.pieces.push_back(Ramp{Vec3::UnitX(), std::nan(""), 0});
  MemorySink sink;
  const RunStats rs = simulate(m, sink);
  EXPECT_EQ(rs.status, "failed");
  EXPECT_NE(rs.message.find("initial: steady: statics did not converge"), std::string::npos) << rs.message;
}

}  // namespace
}  // namespace towsim
