// Flutter of a free cable end made of short elements (docs/validation.md §6,
// finding 4): the steady tow of a free end at the critical angle is a linearly
// unstable equilibrium of the discrete chain when its elements are short. The
// linearisation of towsim's dynamics against an independent planar chain
// (tests/support/planar_chain.hpp), and the growth of a run started in the
// unstable mode (both formulations, two RK4 steps) against the eigenvalue.
#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <complex>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "../support/models.hpp"
#include "../support/planar_chain.hpp"
#include "towsim/dynamics/dynamics.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/tow/ramp.hpp"

namespace towsim {
namespace {

constexpr double kV = 2.0;  // tow speed [m/s]

/// The paper 5.1 cable (1.5 kg/m, D 0.019 m, C_d 1.8, C_a 1, Morison, f = 0)
/// in n elements of length l, free end, towed at kV from t = 0, started steady.
Model tail_model(int n, double l, Formulation f = Formulation::Default) {
  testing::CableSpec c;
  c.n = n;
  c.length = n * l;
  c.am = AddedMassModel::Morison;
  Model m = testing::cable_model(c);
  m.tow.pieces.push_back(Ramp{Vec3::UnitX(), kV, 0});
  m.initial.kind = Initial::Kind::Steady;
  m.sim.formulation = f;
  return m;
}

/// The same chain written independently in the x-z plane.
validation::PlanarChain planar_reference(int n, double l) {
  const double rho = 1025, g = 9.81, mu = 1.5, D = 0.019, A = std::numbers::pi * D * D / 4;
  return {n, l, mu * l, rho * A * l, (mu - rho * A) * g * l, 0.5 * rho * 1.8 * D, kV};
}

/// towsim's dynamics linearised about the steady state s0, in tangent
/// coordinates x = (a_1..a_n, b_1..b_n): e_k = normalise(e0_k + T_k a_k),
/// omega_k = T_k b_k, T_k = [t1 t2] normal to e0_k, t1 = e0 x y in the tow
/// plane. Central differences of forward_dynamics.
struct Linearised {
  std::vector<Eigen::Matrix<double, 3, 2>> T;
  Eigen::MatrixXd J;
  double residual = 0;  // max |alpha_k| at s0 [rad/s^2]
};
Linearised linearise(const Model& m, const PhysicalState& s0) {
  const int n = static_cast<int>(s0.e.size()), N = 4 * n;
  Linearised lin;
  Workspace ws(m);
  const double t = 1.0;  // any time on the constant-speed tow
  forward_dynamics(m, s0, t, ws);
  for (const Vec3& a : ws.acc.alpha) lin.residual = std::max(lin.residual, a.norm());
  lin.T.reserve(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const Vec3 t1 = s0.e[k].cross(Vec3::UnitY()).normalized();
    Eigen::Matrix<double, 3, 2> Tk;
    Tk << t1, s0.e[k].cross(t1);
    lin.T.push_back(Tk);
  }
  auto rhs = [&](const Eigen::VectorXd& x) {
    PhysicalState s = s0;
    for (int k = 0; k < n; ++k) {
      s.e[k] = (s0.e[k] + lin.T[k] * x.segment<2>(2 * k)).normalized();
      s.w[k] = lin.T[k] * x.segment<2>(2 * n + 2 * k);
      s.w[k] -= s.w[k].dot(s.e[k]) * s.e[k];
    }
    forward_dynamics(m, s, t, ws);
    Eigen::VectorXd d(N);
    for (int k = 0; k < n; ++k) {
      d.segment<2>(2 * k) = lin.T[k].transpose() * s.w[k].cross(s.e[k]);
      d.segment<2>(2 * n + 2 * k) = lin.T[k].transpose() * ws.acc.alpha[k];
    }
    return d;
  };
  lin.J.resize(N, N);
  const double h = 1e-6;  // central differences: truncation O(h^2) ~ 1e-12, round-off ~1e-16/h ~ 1e-10 relative
  for (int j = 0; j < N; ++j) {
    Eigen::VectorXd xp = Eigen::VectorXd::Zero(N), xm = xp;
    xp[j] = h, xm[j] = -h;
    lin.J.col(j) = (rhs(xp) - rhs(xm)) / (2 * h);
  }
  return lin;
}

/// Tangent coordinates of a physical state (the inverse of the chart above).
Eigen::VectorXd tangent_coordinates(const Linearised& lin, const PhysicalState& s0, const PhysicalState& s) {
  const auto n = static_cast<int>(s0.e.size());
  Eigen::VectorXd x(4 * n);
  for (int k = 0; k < n; ++k) {
    x.segment<2>(2 * k) = lin.T[k].transpose() * s.e[k] / s0.e[k].dot(s.e[k]);
    x.segment<2>(2 * n + 2 * k) = lin.T[k].transpose() * s.w[k];
  }
  return x;
}

/// The eigenvalue of largest real part of the in-plane block (a along t1, b along t2).
std::complex<double> top_in_plane(const Eigen::MatrixXd& J, int n) {
  std::vector<int> sel(static_cast<std::size_t>(2 * n));
  for (int k = 0; k < n; ++k) {
    sel[static_cast<std::size_t>(k)] = 2 * k;
    sel[static_cast<std::size_t>(n + k)] = 2 * n + 2 * k + 1;
  }
  Eigen::MatrixXd B(2 * n, 2 * n);
  for (int i = 0; i < 2 * n; ++i)
    for (int j = 0; j < 2 * n; ++j) B(i, j) = J(sel[i], sel[j]);
  const Eigen::VectorXcd ev = Eigen::EigenSolver<Eigen::MatrixXd>(B, false).eigenvalues();
  std::complex<double> top = ev[0];
  for (int i = 0; i < ev.size(); ++i)
    if (ev[i].real() > top.real() || (ev[i].real() == top.real() && ev[i].imag() > top.imag())) top = ev[i];
  return {top.real(), std::abs(top.imag())};
}

std::complex<double> top_of(const Eigen::VectorXcd& ev) {
  std::complex<double> top = ev[0];
  for (int i = 0; i < ev.size(); ++i)
    if (ev[i].real() > top.real()) top = ev[i];
  return {top.real(), std::abs(top.imag())};
}

// ---------------------------------------------------------------------------
// The steady state is an equilibrium of the discrete dynamics (residual
// accelerations), and its linearisation in towsim equals the independent
// planar chain's: unstable for short elements, stable for long ones.
// ---------------------------------------------------------------------------
struct LengthCase {
  double l;       // element length [m]
  bool unstable;  // expected sign of the growth rate
};
class FreeEndFlutterLinear : public ::testing::TestWithParam<LengthCase> {};

TEST_P(FreeEndFlutterLinear, TowsimLinearisationEqualsIndependentChain) {
  const LengthCase c = GetParam();
  const int n = 40;  // the unstable mode lives in the last ~10 elements: 40 give the eigenvalue of 200 to 1e-6
  const Model m = tail_model(n, c.l);
  const PhysicalState s0 = initial_state(m);
  const Linearised lin = linearise(m, s0);
  const std::complex<double> ts = top_in_plane(lin.J, n);
  const std::complex<double> ref = top_of(planar_reference(n, c.l).eigenvalues());
  const std::complex<double> all = top_of(Eigen::EigenSolver<Eigen::MatrixXd>(lin.J, false).eigenvalues());
  std::ostringstream os;
  os << std::setprecision(8) << "[measured] free end, " << n << " x " << c.l << " m at " << kV
     << " m/s: residual |alpha| " << std::setprecision(2) << lin.residual << " rad/s^2; in-plane top eigenvalue "
     << std::setprecision(8) << ts.real() << " +- " << ts.imag() << "i /s (planar reference " << ref.real() << " +- "
     << ref.imag() << "i, |diff| " << std::setprecision(2) << std::abs(ts - ref)
     << "); any plane: " << std::setprecision(8) << all.real() << " +- " << all.imag() << "i\n";
  std::cout << os.str();
  // The statics leave residuals at the solver's tolerance (measured <= 5e-10 rad/s^2
  // for 200 elements); 1e-8 rad/s^2 is far below the growth scales here.
  EXPECT_LT(lin.residual, 1e-8);
  // 1e-7 of |lambda|: both Jacobians are central differences with h = 1e-6
  // (truncation ~h^2, round-off ~1e-16/h of the accelerations' scale, ~1e-10
  // relative) of well-separated eigenvalues; measured <= 8e-9 relative.
  EXPECT_LT(std::abs(ts - ref), 1e-7 * std::abs(ref));
  EXPECT_EQ(ts.real() > 0, c.unstable);
  // Unstable: the fastest-growing mode is the in-plane one (out of the plane
  // the tail grows more slowly); stable: stable in both planes.
  if (c.unstable)
    EXPECT_NEAR(all.real(), ts.real(), 1e-6);
  else
    EXPECT_LT(all.real(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(PaperCable, FreeEndFlutterLinear,
                         ::testing::Values(LengthCase{0.01, true}, LengthCase{0.02, true}, LengthCase{0.05, true},
                                           LengthCase{0.1, true}, LengthCase{0.5, true}, LengthCase{1.0, false},
                                           LengthCase{2.0, false}),
                         [](const auto& info) {
                           return "l" + std::to_string(static_cast<int>(info.param.l * 100)) + "cm";
                         });

// ---------------------------------------------------------------------------
// A run started in the unstable mode (steady state + eps Re v) grows at the
// eigenvalue's rate and turns at its frequency: modal coordinate z = u^T x (u
// the left eigenvector), |z(t)| = |z(0)| exp(sigma t). Default and paper
// formulations, fixed-step RK4 at two steps.
// ---------------------------------------------------------------------------
struct RunCase {
  Formulation formulation;
  double h;  // RK4 step [s]
};
class FreeEndFlutterRun : public ::testing::TestWithParam<RunCase> {};

TEST_P(FreeEndFlutterRun, SeededModeGrowsAtTheLinearisedRate) {
  const RunCase c = GetParam();
  const int n = 40;
  const double l = 0.01;
  const Model m = tail_model(n, l, c.formulation);
  const PhysicalState s0 = initial_state(m);
  const Linearised lin = linearise(tail_model(n, l), s0);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(lin.J);
  int top = 0;
  for (int i = 0; i < es.eigenvalues().size(); ++i)
    if (es.eigenvalues()[i].real() > es.eigenvalues()[top].real() ||
        (es.eigenvalues()[i].real() == es.eigenvalues()[top].real() && es.eigenvalues()[i].imag() > 0))
      top = i;
  const std::complex<double> lambda = es.eigenvalues()[top];
  const Eigen::VectorXcd u = es.eigenvectors().inverse().row(top).transpose();  // left eigenvector: u^T J = lambda u^T
  Eigen::VectorXd v = es.eigenvectors().col(top).real();
  const double eps = 1e-9;  // largest seeded angle [rad]: after 0.5 s ~5e-5, nonlinear terms ~1e-5 relative
  v *= eps / v.cwiseAbs().maxCoeff();

  PhysicalState s = s0;
  for (int k = 0; k < n; ++k) {
    s.e[k] = (s0.e[k] + lin.T[k] * v.segment<2>(2 * k)).normalized();
    s.w[k] = lin.T[k] * v.segment<2>(2 * n + 2 * k);
    s.w[k] -= s.w[k].dot(s.e[k]) * s.e[k];
  }
  auto sys = make_system(m);
  StateVector y = sys->initial(s, 0.0);
  boost::numeric::odeint::runge_kutta4<StateVector> rk;
  const double t0 = 0.1, t1 = 0.5;  // window: the seed's other-mode content (round-off) is gone by t0
  const auto steps = static_cast<long>(std::lround(t1 / c.h));
  std::complex<double> z0, z1;
  double phase = 0, arg_prev = 0;
  bool started = false;
  for (long i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) * c.h;
    const Eigen::VectorXd x = tangent_coordinates(lin, s0, sys->physical(y));
    const std::complex<double> z = (u.array() * x.array().cast<std::complex<double>>()).sum();  // z = u^T x
    if (std::abs(t - t0) < c.h / 2) z0 = z, started = true, arg_prev = std::arg(z);
    if (started) {
      double d = std::arg(z) - arg_prev;
      d -= 2 * std::numbers::pi * std::round(d / (2 * std::numbers::pi));
      phase += d, arg_prev = std::arg(z);
    }
    if (i == steps) z1 = z;
    if (i == steps) break;
    rk.do_step(sys->in_window({t, t + c.h}), y, t, c.h);
    sys->project(y, t + c.h);
  }
  const double sigma = std::log(std::abs(z1) / std::abs(z0)) / (t1 - t0);
  const double omega = std::abs(phase) / (t1 - t0);
  std::ostringstream os;
  os << std::setprecision(8) << "[measured] free end 40 x 1 cm, "
     << (c.formulation == Formulation::Paper ? "paper" : "default") << " RK4 h=" << c.h << ": growth " << sigma
     << " /s, frequency " << omega << " rad/s; eigenvalue " << lambda.real() << " +- " << std::abs(lambda.imag())
     << "i; rel err " << std::setprecision(2) << std::abs(sigma / lambda.real() - 1) << ", "
     << std::abs(omega / std::abs(lambda.imag()) - 1) << "\n";
  std::cout << os.str();
  // 1e-4 relative: the amplitude's nonlinear terms (~the amplitude, <= 5e-5
  // relative at the window's end) and RK4's error per step (|lambda| h)^4/120
  // < 1e-10; measured well below (see the output line).
  EXPECT_NEAR(sigma / lambda.real(), 1.0, 1e-4);
  EXPECT_NEAR(omega / std::abs(lambda.imag()), 1.0, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Tail1cm, FreeEndFlutterRun,
                         ::testing::Values(RunCase{Formulation::Default, 1e-4}, RunCase{Formulation::Default, 5e-5},
                                           RunCase{Formulation::Paper, 1e-4}),
                         [](const auto& info) {
                           return std::string(info.param.formulation == Formulation::Paper ? "paper" : "default") +
                                  (info.param.h < 1e-4 ? "_h50us" : "_h100us");
                         });

}  // namespace
}  // namespace towsim
