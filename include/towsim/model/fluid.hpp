// The water and gravity, and what the loads ask of the water: its velocity
// and acceleration at a point and time (docs/theory.md 3).
#pragma once

#include <memory>
#include <vector>

#include "towsim/model/types.hpp"

namespace towsim {

struct WaveField;  // towsim/waves/waves.hpp

/// Water and gravity. `rho == 0` means no fluid at all (vacuum).
///
/// The loads see the water only through velocity(), rate_seen() and
/// acceleration(): a new kind of flow (waves) adds its terms there.
struct Fluid {
  double rho = 1025.0;  // water density [kg/m^3]
  double g = 9.81;      // gravitational acceleration [m/s^2], along -z_g

  /// Current profile: velocity U(z) [m/s, R_g] given at depths, linearly
  /// interpolated in depth, held constant beyond the table's ends. A single
  /// row means a uniform current. Empty means still water.
  std::vector<double> current_depth;   // depth = -z of each row [m], increasing
  std::vector<Vec3> current_velocity;  // U at that depth [m/s, R_g]

  /// Water velocity u(x, t) at point x [m, R_g] and time t [s]: [m/s, R_g].
  Vec3 velocity(const Vec3& x, double t) const;
  /// Rate of change of the water velocity seen by a point passing x at
  /// velocity v: du/dt + (v . grad) u [m/s^2, R_g]. The added-mass loads of a
  /// body or element moving through a non-uniform flow need it.
  Vec3 rate_seen(const Vec3& x, const Vec3& v, double t) const;
  /// Material acceleration of the water Du/Dt = du/dt + (u . grad) u at x
  /// [m/s^2, R_g] (Froude-Krylov and added-mass inertia forces).
  Vec3 acceleration(const Vec3& x, double t) const;
  /// velocity(), rate_seen() and acceleration() at one point with waves, the
  /// harmonics summed once: what an element's loads ask for (all three from
  /// the same sums, so equal to the separate calls to round-off).
  void flow(const Vec3& x, const Vec3& v, double t, Vec3& velocity, Vec3& rate_seen, Vec3& acceleration) const;
  /// True when the water velocity is the same at every point and time, so
  /// that rate_seen() and acceleration() are zero.
  bool uniform() const { return current_velocity.size() < 2 && !waves; }
  /// Waves (linear, long-crested; towsim/waves/waves.hpp), or none. Shared
  /// and immutable; velocity(), rate_seen() and acceleration() include them.
  std::shared_ptr<const WaveField> waves;

  /// Current U at height z [m/s, R_g].
  Vec3 current(double z) const;
  /// dU/dz at height z [1/s, R_g] (zero for a uniform current).
  Vec3 current_gradient(double z) const;
  bool has_current() const { return !current_velocity.empty(); }
};

}  // namespace towsim
