// The Rosenbrock-W method's time column (docs/theory.md §6.3, "The explicit
// time dependence"): the tow law drives the top of the cable through time
// only, so W's column for time, f_t, enters the stages as gamma_i h^2 f_t.
// On the paper 5.2 chain (300 m in 10 elements, the 3 kg sphere), ramp and
// turn, at fixed steps against RK4 at 1 ms: the tow force with f_t is more
// accurate than without (W's time column zero, as before) and still of
// order 3 (W's time column may be anything: it is part of W). The same on
// the winch's pay-out ramp of fish-depth-change, where the time dependence
// is the imposed top length l_1(t) (docs/performance.md "W's time column").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "../support/models.hpp"
#include "../support/physics.hpp"
#include "../support/rosenbrock.hpp"
#include "towsim/integrators/rosenbrock.hpp"
#include "towsim/integrators/system.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

/// paper-3d-turn (scenarios/paper-3d-turn.yaml) as a Model: 300 m of cable
/// in 10 elements, the 3 kg sphere, the ramp and the 7.5 m turn.
Model paper_turn() {
  Model m = testing::paper52_turn(10, 300);
  m.sim.integrator = Integrator::Rosenbrock;
  return m;
}

constexpr double kEnd = 30;      // ramp and half a turn [s]
constexpr double kBreak = 15;    // the tow law's breakpoint: steps land on it [s]
constexpr double kSample = 0.1;  // tow force compared every 0.1 s [s]

/// At fixed steps h from 0 to kEnd (h a divisor of kSample): sample(t)
/// every kSample, then step(t) but at the end.
template <class SampleFn, class StepFn>
void fixed_steps(double h, SampleFn sample, StepFn step) {
  const int per_sample = static_cast<int>(std::lround(kSample / h));
  const int steps = static_cast<int>(std::lround(kEnd / h));
  for (int s = 0; s <= steps; ++s) {
    const double t = s * h;
    if (s % per_sample == 0) sample(t);
    if (s == steps) break;
    step(t);
  }
}

/// |F_R| of state y at time t, evaluated on `sys`.
double tow_force_at(System& sys, const StateVector& y, double t) {
  StateVector dy;
  sys.derivative(y, dy, t, StepWindow{t, t});
  return sys.last_accelerations()->tow_force.norm();
}

/// |F_R| every kSample from 0 to kEnd: Rosenbrock-W at fixed steps h (a
/// divisor of kSample), with or without f_t, or RK4 at h (rk4 = true).
std::vector<double> tow_force(double h, RosenbrockW::TimeDerivative td, bool rk4 = false) {
  const Model m = paper_turn();
  auto sys = make_system(m);
  StateVector y = sys->initial(initial_state(m), 0.0);
  testing::Rk4Scratch rk;
  RosenbrockW ros(*sys, 1e10, 1.0, RosenbrockW::ForceEstimate::Embedded, td);  // error control off
  std::vector<double> out;
  fixed_steps(
      h, [&](double t) { out.push_back(tow_force_at(*sys, y, t)); },
      [&](double t) {
        if (rk4) {
          testing::rk4_step(*sys, y, t, h, rk);
        } else {
          double tt = t, hh = h;
          ros.invalidate();  // the output evaluation above moved the system's last evaluation
          EXPECT_TRUE(ros.try_step(y, tt, hh));
        }
      });
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

/// As tow_force, the steps run on without invalidate() (as in simulate():
/// f_t's history kept) but at the law's breakpoint; the tow force from a
/// second system. evaluations: the stepping system's count.
std::vector<double> tow_force_run_on(double h, RosenbrockW::TimeDerivative td, long& evaluations) {
  const Model m = paper_turn();
  auto sys = make_system(m), probe = make_system(m);
  StateVector y = sys->initial(initial_state(m), 0.0);
  RosenbrockW ros(*sys, 1e10, 1.0, RosenbrockW::ForceEstimate::Embedded, td);  // error control off
  std::vector<double> out;
  fixed_steps(
      h, [&](double t) { out.push_back(tow_force_at(*probe, y, t)); },
      [&](double t) {
        if (std::abs(t - kBreak) < 1e-9) ros.invalidate();  // the law's acceleration jumps (simulate() does so)
        double tt = t, hh = h;
        EXPECT_TRUE(ros.try_step(y, tt, hh));
      });
  evaluations = static_cast<long>(sys->rhs_evaluations);
  return out;
}

// W's time column extrapolated on every other step (simulate()'s default
// without a winch, docs/performance.md "W's time column extrapolated"):
// one evaluation fewer on each such step, the order kept (any column is
// part of W) and the error that of the difference on every step.
TEST(RosenbrockTimeDerivative, ExtrapolatedColumnKeepsOrderThreeAndAccuracy) {
  using TD = RosenbrockW::TimeDerivative;
  const std::vector<double> ref = tow_force(1e-3, TD::None, true);
  long n_fd1 = 0, n_fd2 = 0, n_ex1 = 0, n_ex2 = 0, n_no1 = 0;
  const double fd_1 = max_error(tow_force_run_on(0.1, TD::FiniteDifference, n_fd1), ref);
  const double fd_2 = max_error(tow_force_run_on(0.05, TD::FiniteDifference, n_fd2), ref);
  const double ex_1 = max_error(tow_force_run_on(0.1, TD::Extrapolated, n_ex1), ref);
  const double ex_2 = max_error(tow_force_run_on(0.05, TD::Extrapolated, n_ex2), ref);
  const double no_1 = max_error(tow_force_run_on(0.1, TD::None, n_no1), ref);
  std::cout << "[measured] tow force error, h = 0.1 / 0.05 s: difference every step " << fd_1 << " / " << fd_2 << " ("
            << n_fd1 << " / " << n_fd2 << " evaluations), extrapolated between " << ex_1 << " / " << ex_2 << " ("
            << n_ex1 << " / " << n_ex2 << "), none " << no_1 << " (" << n_no1 << ")\n";
  // The evaluations: 300 / 600 steps, f_t by a difference on each (none
  // with the column left out); extrapolated on the 3rd, 5th, ... steps of
  // each of the law's 2 pieces (n steps: (n - 2) / 2 of them), the first two
  // after invalidate() by differences.
  EXPECT_EQ(n_fd1 - n_no1, 300);
  EXPECT_EQ(n_fd1 - n_ex1, 2 * ((150 - 2) / 2));
  EXPECT_EQ(n_fd2 - n_ex2, 2 * ((300 - 2) / 2));
  // Order 3 halving h: 8x; 5 as the difference's own test above.
  EXPECT_GT(ex_1 / ex_2, 5.0);
  // As accurate as the difference on every step (measured: the same to
  // 1e-5 relative at both steps; 5 % is far above a platform's round-off),
  // far more than without the column (3.0x).
  constexpr double kExtrapolationLoss = 1.05;  // [-]
  EXPECT_LT(ex_1, kExtrapolationLoss * fd_1);
  EXPECT_LT(ex_2, kExtrapolationLoss * fd_2);
  EXPECT_LT(ex_1, 0.5 * no_1);
}

// A rejected try's column: a difference is kept for the retry (as with a
// difference on every step), an extrapolated one is not, the retry takes
// the difference. Counted by the system's evaluations on the paper 5.2
// ramp: an accepted try costs its 3 stage evaluations, the embedded
// solution's and f(y1), and the difference when it takes one.
TEST(RosenbrockTimeDerivative, RejectedExtrapolatedColumnIsRetriedWithADifference) {
  const Model m = paper_turn();
  auto sys = make_system(m);
  StateVector y = sys->initial(initial_state(m), 0.0);
  RosenbrockW ros(*sys, 1e-5, 1.0, RosenbrockW::ForceEstimate::Embedded, RosenbrockW::TimeDerivative::Extrapolated);
  constexpr double kSmall = 0.01;  // accepted at tol 1e-5 in the ramp (its steps are ~0.1 s) [s]
  constexpr double kLarge = 5;     // rejected: a third of the ramp [s]
  double t = 0;
  const auto accepted_try = [&] {
    const auto n0 = sys->rhs_evaluations;
    double h = kSmall;
    EXPECT_TRUE(ros.try_step(y, t, h));
    return sys->rhs_evaluations - n0;
  };
  const auto rejected_try = [&] {
    double h = kLarge;
    EXPECT_FALSE(ros.try_step(y, t, h));
  };
  EXPECT_EQ(accepted_try(), 1 + 3 + 1 + 2);  // f(y0) first, then the difference
  EXPECT_EQ(accepted_try(), 3 + 1 + 2);      // the second difference
  rejected_try();                            // extrapolated
  EXPECT_EQ(accepted_try(), 3 + 1 + 2);      // retried with the difference
  EXPECT_EQ(accepted_try(), 3 + 2);          // extrapolated
  rejected_try();                            // a difference
  EXPECT_EQ(accepted_try(), 3 + 2);          // ... kept
}

/// fish-depth-change (scenarios/fish-depth-change.yaml) from its steady tow
/// at t = 50 s to 76 s: the winch starts paying out at 60 s (l_1'' = 0.1
/// m/s^2 until 70 s, then 1 m/s); no split before 80 s (the top element
/// reaches 45 m = split_at L_e at 80 s). The link tension every 0.5 s:
/// Rosenbrock-W at fixed steps h (dividing 0.5 s: steps land on the
/// schedule's breakpoints 60 and 70 s), with or without f_t, or RK4 at h.
std::vector<double> winch_link_tension(double h, RosenbrockW::TimeDerivative td, bool rk4 = false) {
  const scenario::Example* ex = scenario::find_example("fish-depth-change");
  EXPECT_NE(ex, nullptr);
  if (!ex) return {};
  const scenario::LoadedScenario sc = scenario::load_scenario_text(ex->yaml, "fish-depth-change.yaml", ex->name, ".");
  EXPECT_TRUE(sc.ok());
  const Model& m = *sc.model;
  const StaticsResult st = steady_state(m);
  EXPECT_TRUE(st.converged);
  constexpr double kT0 = 50, kT1 = 76, kOut = 0.5;  // window and sampling [s]
  auto sys = make_system(m);
  StateVector y = sys->initial(st.state, kT0);
  sys->project(y, kT0);
  testing::Rk4Scratch rk;
  RosenbrockW ros(*sys, 1e10, 1.0, RosenbrockW::ForceEstimate::Embedded, td);  // error control off
  const std::vector<double> breaks = winch_breakpoints(m.winch);
  std::vector<double> out;
  const long per_sample = std::lround(kOut / h), steps = std::lround((kT1 - kT0) / h);
  for (long s = 0; s <= steps; ++s) {
    const double t = kT0 + static_cast<double>(s) * h;
    // A breakpoint of the schedule: its (here zero) speed jump, and f_t anew.
    if (std::any_of(breaks.begin(), breaks.end(), [&](double b) { return std::abs(b - t) < 1e-9; })) {
      sys->apply_tow_jump(y, t);
      ros.invalidate();
    }
    if (s % per_sample == 0) {
      out.push_back(sys->evaluate(y, t).acc.link_force.at(0).norm());
      ros.invalidate();  // the evaluation moved the system's last evaluation
    }
    if (s == steps) break;
    if (rk4) {
      testing::rk4_step(*sys, y, t, h, rk);
    } else {
      double tt = t, hh = h;
      EXPECT_TRUE(ros.try_step(y, tt, hh));
    }
  }
  return out;
}

// With a winch f_t is right too: at equal fixed steps the link tension is
// more accurate with it (measured 1.9x and 1.7x) and of order 3. simulate()
// still leaves it out with a winch: the adaptive run's loss there is the
// step controller's, not f_t's (docs/performance.md "W's time column").
TEST(RosenbrockTimeDerivative, MoreAccurateOnTheWinchRampAndOrderThree) {
  using TD = RosenbrockW::TimeDerivative;
  const std::vector<double> ref = winch_link_tension(1e-3, TD::None, true);  // RK4 at 1 ms: ~1e-9 of these errors
  const double with_1 = max_error(winch_link_tension(0.25, TD::FiniteDifference), ref);
  const double with_2 = max_error(winch_link_tension(0.125, TD::FiniteDifference), ref);
  const double without_1 = max_error(winch_link_tension(0.25, TD::None), ref);
  const double without_2 = max_error(winch_link_tension(0.125, TD::None), ref);
  std::cout << "[measured] winch ramp link tension error, h = 0.25 / 0.125 s: with f_t " << with_1 << " / " << with_2
            << ", without " << without_1 << " / " << without_2 << "\n";
  // More accurate (measured 1.9x, 1.7x; 1.2x leaves room for the platform).
  EXPECT_LT(with_1, without_1 / 1.2);
  EXPECT_LT(with_2, without_2 / 1.2);
  // Order 3 halving h: 8x; measured 7.0x (6 would be between orders 2.6 and 3).
  EXPECT_GT(with_1 / with_2, 6.0);
}

}  // namespace
}  // namespace towsim
