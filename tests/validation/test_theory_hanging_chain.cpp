// Small oscillations of a chain hanging in vacuum: the linearised chain's
// eigenfrequencies (mass and stiffness matrices built by hand in
// tests/support/pode.hpp) against frequencies measured in simulations started
// in an eigenmode, and the linearised chain against the continuous hanging
// chain (Bessel J0) as n grows. Derivations: tests/support/pode.hpp and
// docs/validation.md section 2.
#include <gtest/gtest.h>

#include <iomanip>
#include <iostream>
#include <sstream>

#include "../support/models.hpp"
#include "../support/pode.hpp"
#include "towsim/integrators/system.hpp"

namespace towsim {
namespace {

using testing::CableSpec;
constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;
constexpr double kLength = 10.0;        // total chain length [m]
constexpr double kMassPerLength = 1.0;  // [kg/m]

struct ModeCase {
  int n;     // links
  int mode;  // 1 = slowest
  Formulation formulation;
};
void PrintTo(const ModeCase& c, std::ostream* os) { *os << "n=" << c.n << " mode " << c.mode; }

class TheoryHangingChain : public ::testing::TestWithParam<ModeCase> {};

// ---------------------------------------------------------------------------
// Start in the mode shape (link angles th_k = eps v_k, at rest), run with
// fixed-step RK4 and the formulation's projection after each step, read the
// period from the zero crossings of the modal coordinate q = v^T M th.
// ---------------------------------------------------------------------------
TEST_P(TheoryHangingChain, SimulatedFrequencyMatchesLinearisedChain) {
  const ModeCase c = GetParam();
  const double l = kLength / c.n, ml = kMassPerLength * l;
  const validation::ChainModes modes = validation::hanging_chain_modes(c.n, l, ml, kG);
  const double w_lin = modes.omega[c.mode - 1];
  Eigen::VectorXd v = modes.shapes.col(c.mode - 1);
  const double eps = 2e-4;  // largest link angle [rad]: frequency shift O(eps^2) ~ 4e-8
  v *= eps / v.cwiseAbs().maxCoeff();
  // M v for the modal coordinate (the same M as in hanging_chain_modes).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(c.n, c.n);
  for (int k = 0; k < c.n; ++k) {
    for (int j = 0; j < k; ++j) A(k, j) = 1.0;
    A(k, k) = 0.5;
  }
  const Eigen::VectorXd Mv = ml * l * l * (A.transpose() * A + Eigen::MatrixXd::Identity(c.n, c.n) / 12.0) * v;

  CableSpec spec;
  spec.n = c.n;
  spec.length = kLength;
  spec.mass_per_length = kMassPerLength;
  Model m = testing::cable_model(spec, /*rho=*/0.0, kG);  // vacuum: no fluid load, no added mass
  m.sim.formulation = c.formulation;
  PhysicalState s = PhysicalState::hanging(m);
  for (int k = 0; k < c.n; ++k) s.e[k] = Vec3(std::sin(v[k]), 0, -std::cos(v[k]));
  auto sys = make_system(m);
  StateVector y = sys->initial(s, 0.0);

  const double T_lin = 2 * kPi / w_lin;
  const double h = 0.005;  // RK4 phase error (w h)^4/120 < 1e-9 for every case here
  const long steps = static_cast<long>(std::ceil(5.3 * T_lin / h));
  std::vector<double> t{0.0}, q, qd;
  auto modal = [&](const StateVector& yy) {
    const PhysicalState ps = sys->physical(yy);
    double a = 0, ad = 0;
    for (int k = 0; k < c.n; ++k) {
      const Vec3& e = ps.e[k];
      const double th = std::atan2(e.x(), -e.z());
      const Vec3 edot = ps.w[k].cross(e);
      a += Mv[k] * th;
      ad += Mv[k] * edot.dot(Vec3(std::cos(th), 0, std::sin(th)));
    }
    q.push_back(a);
    qd.push_back(ad);
  };
  modal(y);
  boost::numeric::odeint::runge_kutta4<StateVector> rk;
  for (long i = 0; i < steps; ++i) {
    rk.do_step(sys->in_window({}), y, t.back(), h);
    t.push_back((i + 1) * h);
    sys->project(y, t.back());
    modal(y);
  }
  const auto cr = validation::hermite_zero_crossings(t, q, qd);
  ASSERT_GE(cr.size(), 10u);
  const double T_sim = 2 * (cr.back() - cr.front()) / static_cast<double>(cr.size() - 1);
  const double err = std::abs(T_sim - T_lin) / T_lin;
  std::ostringstream os;
  os << std::setprecision(10) << "[measured] hanging chain n=" << c.n << " mode " << c.mode << " "
     << (c.formulation == Formulation::Paper ? "paper" : "default") << ": w_lin=" << w_lin << " rad/s, T_lin=" << T_lin
     << " s, T_sim=" << T_sim << " s, rel err " << std::setprecision(3) << err << "\n";
  std::cout << os.str();
  // 1e-7 relative: the amplitude's (nonlinear) frequency shift is
  // O(eps^2) = 4e-8 (measured: the error scales as eps^2, 8.6e-7 at eps =
  // 1e-3 and 3.5e-8 at 2e-4 for the worst case, n = 2 mode 2); RK4's phase
  // error (w h)^4/120 < 1e-9 and the crossings' Hermite interpolation error
  // ~(w h)^4/384 < 1e-9.
  EXPECT_LT(err, 1e-7);
}

std::vector<ModeCase> mode_cases() {
  std::vector<ModeCase> out;
  for (Formulation f : {Formulation::Default, Formulation::Paper})
    for (int n : {1, 2, 5, 10})
      for (int k = 1; k <= std::min(n, 3); ++k) out.push_back({n, k, f});
  for (int k = 1; k <= 3; ++k) out.push_back({40, k, Formulation::Default});
  return out;
}

INSTANTIATE_TEST_SUITE_P(TheoryVacuum, TheoryHangingChain, ::testing::ValuesIn(mode_cases()), [](const auto& info) {
  return std::string(info.param.formulation == Formulation::Paper ? "Paper" : "Default") + "_n" +
         std::to_string(info.param.n) + "_mode" + std::to_string(info.param.mode);
});

// ---------------------------------------------------------------------------
// Linearised chain -> continuous chain: w_k -> (j_{0,k}/2) sqrt(g / L) as n
// grows, at second order in 1/n.
// ---------------------------------------------------------------------------
TEST(TheoryHangingChainLimit, LinearisedChainConvergesToBesselFrequencies) {
  const std::vector<int> ns = {5, 10, 20, 40, 80, 160, 320};
  std::vector<std::array<double, 3>> err;
  auto out = validation::data_file("validation_chain_modes.dat");
  if (out) *out << "# n rel_err_mode1 rel_err_mode2 rel_err_mode3 (linearised chain vs continuous, Bessel J0)\n";
  std::ostringstream os;
  os << std::setprecision(6) << "[measured] hanging chain vs continuous: w_k = (j0k/2) sqrt(g/L) = "
     << validation::continuous_chain_omega(1, kLength, kG) << ", " << validation::continuous_chain_omega(2, kLength, kG)
     << ", " << validation::continuous_chain_omega(3, kLength, kG) << " rad/s\n"
     << "   n    w1          err1        p     w2          err2        p     w3          err3        p\n";
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const int n = ns[i];
    const auto modes = validation::hanging_chain_modes(n, kLength / n, kMassPerLength * kLength / n, kG);
    std::array<double, 3> e{};
    os << std::setw(4) << n;
    for (int k = 1; k <= 3; ++k) {
      const double wc = validation::continuous_chain_omega(k, kLength, kG);
      e[k - 1] = std::abs(modes.omega[k - 1] - wc) / wc;
      os << "  " << std::fixed << std::setprecision(6) << modes.omega[k - 1] << "  " << std::scientific
         << std::setprecision(3) << e[k - 1] << "  " << std::fixed << std::setprecision(2);
      if (i > 0) {
        os << std::setw(4) << validation::observed_order(err.back()[k - 1], e[k - 1]);
      } else {
        os << "    ";
      }
    }
    os << "\n";
    if (out) *out << n << " " << e[0] << " " << e[1] << " " << e[2] << "\n";
    err.push_back(e);
  }
  std::cout << os.str();
  for (int k = 0; k < 3; ++k) {
    for (std::size_t i = 1; i < err.size(); ++i) EXPECT_LT(err[i][k], err[i - 1][k]) << "mode " << k + 1;
    // Second order in 1/n over the last three doublings (2 +- 0.1).
    for (std::size_t i = err.size() - 3; i < err.size(); ++i)
      EXPECT_NEAR(validation::observed_order(err[i - 1][k], err[i][k]), 2.0, 0.1) << "mode " << k + 1;
  }
  // n = 320: within 1e-4 of the continuous chain for the three lowest modes
  // (measured 3.0e-7, 1.0e-5, 4.4e-5: the error grows with the mode number,
  // as the element length compares with the mode's wavelength).
  for (int k = 0; k < 3; ++k) EXPECT_LT(err.back()[k], 1e-4);
}

}  // namespace
}  // namespace towsim
