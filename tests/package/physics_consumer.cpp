// A user's program linking towsim::physics only: a model built in code, one
// evaluation of the dynamics, a physical result checked. A chain hanging at
// rest in still water from a fixed tow point: every element is in
// equilibrium, so the tow force F_R carries the cable's apparent weight,
// n (mu L - rho pi D^2/4 L) g, straight up, and joint k carries the weight of
// the n - k elements below it; the angular accelerations vanish.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "towsim/dynamics/dynamics.hpp"
#include "towsim/dynamics/state.hpp"
#include "towsim/model/model.hpp"
#include "towsim/version.hpp"

int main() {
  using namespace towsim;
  constexpr int n = 10;             // elements [-]
  constexpr double length = 100.0;  // cable length [m]
  constexpr double mu = 1.5;        // mass per length in air [kg/m]
  constexpr double D = 0.019;       // diameter [m]
  Model m;
  m.fluid.rho = 1025.0;  // [kg/m^3]
  m.fluid.g = 9.81;      // [m/s^2]
  for (int i = 0; i < n; ++i)
    m.cable.elements.push_back(make_element(length / n, mu, D, 1.8, 0.0, TangentialLaw::Pode, 1.0, m.fluid));
  m.tow.mode = Tow::Mode::Motion;  // no pieces: the tow point stays at the origin

  PhysicalState s;  // hanging straight down at rest: e_k = -z, omega_k = 0
  s.e.assign(n, -Vec3::UnitZ());
  s.w.assign(n, Vec3::Zero());
  Workspace ws(m);
  forward_dynamics(m, s, 0.0, ws);

  // Apparent weight from the inputs, not from the model's derived fields [N].
  const double W = (mu - m.fluid.rho * std::numbers::pi * D * D / 4) * length * m.fluid.g;
  // A sum of n equal terms: rounding is ~n * 1e-16 relative; 1e-9 leaves margin
  // for any summation order and still fails on any modelling error.
  constexpr double kRel = 1e-9;
  int failures = 0;
  auto check = [&](const char* what, const Vec3& got, const Vec3& want) {
    const double err = (got - want).norm() / W;
    std::printf("%-16s (%.6f, %.6f, %.6f) N, expected (%.6f, %.6f, %.6f) N, error %.1e of W\n", what, got.x(), got.y(),
                got.z(), want.x(), want.y(), want.z(), err);
    if (!(err <= kRel)) ++failures;
  };
  check("tow force F_R", ws.acc.tow_force, Vec3(0, 0, W));
  for (int k = 1; k < n; k += 4)
    check(("joint force f_" + std::to_string(k)).c_str(), ws.acc.joint_force[k], Vec3(0, 0, W * (n - k) / n));
  // Accelerations: zero up to rounding (scale: g / element length) [rad/s^2].
  double amax = 0;
  for (const Vec3& a : ws.acc.alpha) amax = std::max(amax, a.norm());
  std::printf("max |alpha_k| = %.1e rad/s^2\n", amax);
  if (!(amax <= kRel * m.fluid.g / (length / n))) ++failures;
  // The header's version is the package's (towsimConfigVersion.cmake).
  std::printf("towsim %s (package %s)\n", towsim::kVersion, PACKAGE_VERSION);
  if (std::string(towsim::kVersion) != PACKAGE_VERSION) ++failures;
  return failures == 0 ? 0 : 1;
}
