// The Rosenbrock-W method's time column (docs/theory.md §6.3, "The explicit
// time dependence"): the tow law drives the top of the cable through time
// only, so W's column for time, f_t, enters the stages as gamma_i h^2 f_t.
// On the paper 5.2 chain (300 m in 10 elements, the 3 kg sphere), ramp and
// turn, at fixed steps against RK4 at 1 ms: the tow force with f_t is more
// accurate than without (W's time column zero, as before) and still of
// order 3 (W's time column may be anything: it is part of W).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"

namespace towsim {
namespace {

/// paper-3d-turn (scenarios/paper-3d-turn.yaml) as a Model: 300 m of cable
/// in 10 elements, 0.14 kg/m, 10 mm, Cd 1.9, the 3 kg sphere; the tow point
/// reaches 1.57 m/s in 15 s, then turns on a 7.5 m circle.
Model paper_turn() {
  testing::CableSpec spec;
  spec.n = 10;
  spec.length = 300;
  spec.mass_per_length = 0.14;
  spec.diameter = 0.010;
  spec.cd = 1.9;
  Model m = testing::cable_model(spec);
  testing::add_sphere_body(m);
  m.tow.pieces.push_back(testing::ramp_piece(Vec3::UnitX(), 1.57, 15));
  m.tow.pieces.push_back(testing::turn_piece(7.5, 15));
  m.sim.integrator = Integrator::Rosenbrock;
  return m;
}

constexpr double kEnd = 30;      // ramp and half a turn [s]
constexpr double kBreak = 15;    // the tow law's breakpoint: steps land on it [s]
constexpr double kSample = 0.1;  // tow force compared every 0.1 s [s]

/// |F_R| every kSample from 0 to kEnd: Rosenbrock-W at fixed steps h (a
/// divisor of kSample), with or without f_t, or RK4 at h (rk4 = true).
std::vector<double> tow_force(double h, RosenbrockW::TimeDerivative td, bool rk4 = false) {
  const Model m = paper_turn();
  auto sys = make_system(m);
  StateVector y = sys->initial(initial_state(m), 0.0), k1, k2, k3, k4, yt;
  const std::size_t N = y.size();
  RosenbrockW ros(*sys, 1e10, 1.0, RosenbrockW::ForceEstimate::Embedded, td);  // error control off
  std::vector<double> out;
  const int per_sample = static_cast<int>(std::lround(kSample / h));
  const int steps = static_cast<int>(std::lround(kEnd / h));
  for (int s = 0; s <= steps; ++s) {
    const double t = s * h;
    if (s % per_sample == 0) {
      sys->set_window(t, t);
      sys->derivative(y, k1, t);
      out.push_back(sys->last_accelerations()->tow_force.norm());
    }
    if (s == steps) break;
    if (rk4) {
      auto axpy = [&](const StateVector& k, double a) {
        for (std::size_t i = 0; i < N; ++i) yt[i] = y[i] + a * k[i];
      };
      sys->set_window(t, t + h);
      sys->derivative(y, k1, t);
      yt = y;
      axpy(k1, h / 2);
      sys->derivative(yt, k2, t + h / 2);
      axpy(k2, h / 2);
      sys->derivative(yt, k3, t + h / 2);
      axpy(k3, h);
      sys->derivative(yt, k4, t + h);
      for (std::size_t i = 0; i < N; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
      sys->project(y, t + h);
    } else {
      double tt = t, hh = h;
      ros.invalidate();  // the output evaluation above moved the system's last evaluation
      EXPECT_TRUE(ros.try_step(y, tt, hh));
    }
  }
  return out;
}

double max_error(const std::vector<double>& a, const std::vector<double>& ref) {
  double e = 0, peak = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) e = std::max(e, std::abs(a[i] - ref[i])), peak = std::max(peak, ref[i]);
  return e / peak;
}

TEST(RosenbrockTimeDerivative, MoreAccurateOnTheDrivenCableAndOrderThree) {
  using TD = RosenbrockW::TimeDerivative;
  const std::vector<double> ref = tow_force(1e-3, TD::None, true);
  const double with_1 = max_error(tow_force(0.1, TD::FiniteDifference), ref);
  const double with_2 = max_error(tow_force(0.05, TD::FiniteDifference), ref);
  const double without_1 = max_error(tow_force(0.1, TD::None), ref);
  const double without_2 = max_error(tow_force(0.05, TD::None), ref);
  std::cout << "[measured] tow force error, h = 0.1 / 0.05 s: with f_t " << with_1 << " / " << with_2 << ", without "
            << without_1 << " / " << without_2 << "\n";
  EXPECT_LT(with_1, 0.5 * without_1);
  EXPECT_LT(with_2, 0.5 * without_2);
  EXPECT_GT(with_1 / with_2, 5.0);
}

}  // namespace
}  // namespace towsim
