// Faired cable at steady tow: a cable whose normal and tangential loads are
// tables of the flow angle lies at the critical angle phi_c of the closed form
// R f_n(phi_c) = w cos(phi_c) (docs/theory.md §3 "Faired cable"), solved here
// by bisection on the test's own interpolation of the table; its top tension
// is L (w sin phi_c + R f_t(phi_c)).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "towsim/scenario/scenario.hpp"
#include "towsim/sim/statics.hpp"

namespace {

constexpr double kPi = std::numbers::pi;

/// A table [[deg, f], ...] as the YAML flow list and as rows for the test's interpolation.
struct Table {
  std::vector<double> deg, f;
  std::string yaml() const {
    std::string s = "[";
    for (std::size_t i = 0; i < deg.size(); ++i)
      s += (i ? ", [" : "[") + std::to_string(deg[i]) + ", " + std::to_string(f[i]) + "]";
    return s + "]";
  }
  /// Linear interpolation at phi [rad], held at the ends (written here, not towsim's).
  double operator()(double phi) const {
    const double x = phi * 180 / kPi;
    if (x <= deg.front()) return f.front();
    for (std::size_t i = 1; i < deg.size(); ++i)
      if (x <= deg[i]) return f[i - 1] + (f[i] - f[i - 1]) * (x - deg[i - 1]) / (deg[i] - deg[i - 1]);
    return f.back();
  }
};

// A generic faired-cable loading (ribbon fairing: low normal load, flat
// tangential friction): plausible shapes, not a particular product's data.
const Table kFn{{0, 15, 30, 45, 60, 75, 90}, {0, 0.03, 0.10, 0.21, 0.33, 0.42, 0.45}};
const Table kFt{{0, 45, 90}, {0.06, 0.05, 0.03}};

constexpr double kRho = 1025, kG = 9.81, kCd = 1.2, kD = 0.03, kMass = 2.0, kV = 2.5, kLength = 200;

/// The critical angle: root of R f_n(phi) - w cos(phi) on (0, pi/2) by bisection.
double critical_angle(double w, double R) {
  double lo = 0, hi = kPi / 2;  // g(lo) = -w < 0, g(hi) = R f_n(90 deg) > 0
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (R * kFn(mid) - w * std::cos(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(FairedCableSteady, CriticalAngleAndTopTension) {
  const std::string yaml = "cable:\n  length: " + std::to_string(kLength) +
                           "\n  elements: 20\n  mass_per_length: " + std::to_string(kMass) +
                           "\n  diameter: " + std::to_string(kD) +
                           "\n  added_mass: 0\n"  // no Munk moment: the closed form has none
                           "  normal_drag: {law: table, cd: " +
                           std::to_string(kCd) + ", fn: " + kFn.yaml() +
                           "}\n  tangential_drag: {law: table, ft: " + kFt.yaml() +
                           "}\ntow:\n  motion:\n    - {type: ramp, direction: [1, 0, 0], speed: " + std::to_string(kV) +
                           ", ramp_time: 0}\ninitial: steady\nsimulation:\n  duration: 1\n";
  const auto s = towsim::scenario::load_scenario_text(yaml, "faired.yaml", "faired", ".");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const towsim::StaticsResult r = towsim::steady_state(*s.model);
  ASSERT_TRUE(r.converged) << r.message;

  const double w = (kMass - kRho * kPi * kD * kD / 4) * kG;  // apparent weight [N/m]
  const double R = 0.5 * kRho * kCd * kD * kV * kV;          // [N/m]
  const double phi_c = critical_angle(w, R);
  ASSERT_GT(phi_c, 0.3);  // a faired cable tows steeper than bare (28.9 deg here, bare 18.7)
  ASSERT_LT(phi_c, 1.0);
  // Every element trails at phi_c below the horizontal, behind the tow point.
  // Tolerance: the statics converge to |alpha| < 1e-9 rad/s^2 (angle error
  // ~1e-10); the table's smoothed normal direction changes the normal load by
  // v_s^2 / (2 |u_n|^2) ~ 1e-7 relative: 1e-6 rad covers both.
  double worst = 0;
  for (std::size_t k = 0; k < r.state.e.size(); ++k) {
    const towsim::Vec3& e = r.state.e[k];
    worst = std::max(worst, std::abs(std::atan2(-e.z(), -e.x()) - phi_c));
    EXPECT_NEAR(std::atan2(-e.z(), -e.x()), phi_c, 1e-6) << "element " << k + 1;
    EXPECT_NEAR(e.y(), 0.0, 1e-9);
  }
  // Tangential balance of the straight cable: top tension (relative 1e-6, as above).
  const double T = kLength * (w * std::sin(phi_c) + R * kFt(phi_c));
  EXPECT_NEAR(r.tow_force.norm(), T, 1e-6 * T);
  std::cout << "[measured] faired: phi_c = " << phi_c * 180 / kPi << " deg, max |phi_k - phi_c| = " << worst
            << " rad, tow tension " << r.tow_force.norm() << " N vs " << T << " N (rel "
            << std::abs(r.tow_force.norm() - T) / T << ")\n";
}

// The same cable with the bare-cable laws (cross-flow, Pode f = 0) reaches
// the classic critical angle sin^2(phi)/cos(phi) = w/R (closed form:
// cos(phi) = (-w/R + sqrt((w/R)^2 + 4)) / 2): the default laws are untouched.
TEST(FairedCableSteady, DefaultLawGivesTheClassicCriticalAngle) {
  const std::string yaml = "cable:\n  length: 200\n  elements: 20\n  mass_per_length: " + std::to_string(kMass) +
                           "\n  diameter: " + std::to_string(kD) +
                           "\n  added_mass: 0\n  normal_drag: " + std::to_string(kCd) +
                           "\ntow:\n  motion:\n    - {type: ramp, direction: [1, 0, 0], speed: " + std::to_string(kV) +
                           ", ramp_time: 0}\ninitial: steady\nsimulation:\n  duration: 1\n";
  const auto s = towsim::scenario::load_scenario_text(yaml, "bare.yaml", "bare", ".");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const towsim::StaticsResult r = towsim::steady_state(*s.model);
  ASSERT_TRUE(r.converged) << r.message;
  const double a = (kMass - kRho * kPi * kD * kD / 4) * kG / (0.5 * kRho * kCd * kD * kV * kV);
  const double phi_c = std::acos((-a + std::sqrt(a * a + 4)) / 2);
  double worst = 0;
  for (const towsim::Vec3& e : r.state.e) {
    worst = std::max(worst, std::abs(std::atan2(-e.z(), -e.x()) - phi_c));
    EXPECT_NEAR(std::atan2(-e.z(), -e.x()), phi_c, 1e-6);
  }
  std::cout << "[measured] bare: phi_c = " << phi_c * 180 / kPi << " deg, max |phi_k - phi_c| = " << worst << " rad\n";
}
