// The stage solve's W of a tree of lines (docs/theory.md §6.3, "The
// Jacobian approximation") against a finite-difference Jacobian J of the
// network's dynamics, on a body's rotation: a line hanging from one of a
// body's points pulls it, and turning the body about its link point Q moves
// the point against that pull (body_line_stiffness). At rest that is all of
// the body's rotational stiffness besides its own weight and buoyancy, so W
// equals J on it up to the differences' error.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include "../support/models.hpp"
#include "../support/networks.hpp"
#include "../support/rosenbrock.hpp"
#include "towsim/integrators/network_system.hpp"

namespace towsim {
namespace {

constexpr double kRho = 1025, kG = 9.81;  // the test models' water [kg/m^3] and gravity [m/s^2]

/// 20 m of the test cable (10 elements, 1.5 kg/m, 19 mm) from a stationary
/// tow point to a 200 kg sphere (r = 0.3 m, link point on top), and a tail
/// of the same cable from the sphere's point `p` [m, body axes] to a 3 kg
/// sphere. The body's centre of gravity is moved along x_b so that the
/// tail's pull and the body's weight balance about Q: hanging straight
/// down, the state is at rest in equilibrium.
Network sphere_with_tail(const Vec3& p, bool line_pull = true) {
  testing::CableSpec cs;
  cs.n = 10;
  cs.length = 20;
  Model top = testing::cable_model(cs), tail = testing::cable_model(cs);
  testing::add_sphere_body(top, 200, 0.3);
  testing::add_sphere_body(tail);
  const double w = (cs.mass_per_length - kRho * std::numbers::pi / 4 * cs.diameter * cs.diameter) * kG;  // [N/m]
  const Body& end = tail.bodies.front();
  const double pull = w * cs.length + (end.mass - kRho * end.displaced_volume) * kG;  // the tail's [N]
  Body& b = top.bodies.front();
  b.cg = Vec3(-pull * p.x() / (b.mass * kG), 0, 0);  // m g x_cg + pull p_x = 0 about Q (buoyancy at O)
  finalize_body(b, top.fluid);
  top.sim.line_pull_stiffness = tail.sim.line_pull_stiffness = line_pull;
  return testing::network_of({top, tail}, {LineTop{}, LineTop{0, 0, p}});
}

/// ||(W - J) X|| / ||J X|| on the body's angular-velocity rows for its three
/// rotations X at rest (W from the stage solve at hg = 0.01 s, J by central
/// differences of step 1e-7 rad).
double rotation_mismatch(const Network& net) {
  NetworkSystem sys(net);
  const StateVector y = sys.initial_tree(network_initial_state(net));
  const std::size_t N = y.size(), n = net.tree.lines[0].cable.elements.size();
  const std::size_t ob = 6 + 6 * n;  // line 0's body rows: quaternion, then angular velocity
  StateVector f;
  sys.derivative(y, f, 0.0, StepWindow{});
  sys.prepare_stage_solve(0.0, StepWindow{});
  const auto at = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  // W on the rows the stage solve moves: the tail's top rows are its node's (held).
  std::vector<std::size_t> held;
  for (std::size_t i = sys.offset(1); i < sys.offset(1) + 6; ++i) held.push_back(i);
  const Eigen::MatrixXd W = testing::stage_W(sys, N, 0.01, held);
  const Quat q(y[ob], y[ob + 1], y[ob + 2], y[ob + 3]);
  double num = 0, den = 0;
  const double eps = 1e-7;
  for (int j = 0; j < 3; ++j) {
    // Rotation by a about the body: dq = 1/2 (0, a) q.
    const Quat dq = Quat(0, Vec3::Unit(j).x(), Vec3::Unit(j).y(), Vec3::Unit(j).z()) * q;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(at(N));
    x.segment<4>(at(ob)) << 0.5 * dq.w(), 0.5 * dq.x(), 0.5 * dq.y(), 0.5 * dq.z();
    StateVector yp = y, ym = y, fp, fm;
    for (std::size_t i = 0; i < N; ++i) yp[i] += eps * x[at(i)], ym[i] -= eps * x[at(i)];
    sys.derivative(yp, fp, 0.0, StepWindow{});
    sys.derivative(ym, fm, 0.0, StepWindow{});
    const Eigen::VectorXd Wx = W * x;
    for (std::size_t row = ob + 4; row < ob + 7; ++row) {
      const double jx = (fp[row] - fm[row]) / (2 * eps);
      num += (Wx[at(row)] - jx) * (Wx[at(row)] - jx);
      den += jx * jx;
    }
  }
  return std::sqrt(num / den);
}

// The tail from the sphere's bottom (its pull along the arm from Q: a
// pendulum stiffness |f| |r| across it) and from a point off the axis (the
// pull across the arm as well: (f.r) I - f r^T in full). Measured 5.1e-14
// and 1.7e-11 (the differences' error, eps_mach |f| / 1e-7 against
// |J X|): bound 1e-6. Without the lines' term (line_pull_stiffness off) W
// misses the tail's 261 N at 0.6 m against the body's own 825 N in water
// at 0.3 m: 157 / (157 + 247) = 0.39 of its rotational stiffness;
// measured 0.39 and 0.35, checked above 0.3.
TEST(RosenbrockTreeJacobian, LineHangingFromABodyPointIsInItsRotationalStiffness) {
  const struct {
    const char* name;
    Vec3 point;
  } cases[] = {{"tail from the bottom", Vec3(0, 0, -0.3)}, {"tail from a point off the axis", Vec3(0.2, 0, -0.2)}};
  for (const auto& c : cases) {
    const double e = rotation_mismatch(sphere_with_tail(c.point));
    const double without = rotation_mismatch(sphere_with_tail(c.point, false));
    std::cout << "[measured] " << c.name << ": ||(W - J) X|| / ||J X|| on the body's rotation = " << e
              << " (without the lines' pull " << without << ")\n";
    EXPECT_LT(e, 1e-6) << c.name;
    EXPECT_GT(without, 0.3) << c.name;
  }
}

}  // namespace
}  // namespace towsim
