// Linear (Airy) waves: regular or synthesised from a JONSWAP / Pierson-Moskowitz
// spectrum, and their elevation, particle velocity and acceleration at a
// point (MODEL.md 9 "Waves and ship motion"; docs/theory.md "Waves").
//
// Frames: R_g, z up, still water level at z = 0. A component i is
//   eta_i = a_i cos(Theta_i),  Theta_i = omega_i t - k_i d.x - eps_i,
// d the unit horizontal direction the waves travel.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Dense>

namespace towsim {

/// One harmonic of the sea.
struct WaveComponent {
  double amplitude;       // a_i [m]
  double omega;           // circular frequency omega_i [rad/s]
  double k;               // wavenumber k_i (dispersion relation) [1/m]
  double phase;           // eps_i [rad]
  double z_cut;           // below this height its kinematics are skipped (kWaveCutoff) [m, R_g]
  double dx = 0, dy = 0;  // its unit horizontal travel direction (short-crested seas) [-, R_g]
  double e2kh = 0;        // exp(-2 k h) in finite depth h, 0 in deep water [-]
};

/// Relative size of a component's kinematics (to their value at z = 0) below
/// which they are skipped: exp(k z) < kWaveCutoff (deep water), or the cosh
/// ratio (finite depth). The skipped part of velocity or acceleration at any
/// point is at most kWaveCutoff * sum_i a_i omega_i (resp. a_i omega_i^2), i.e.
/// 0.1 % of the largest possible surface value.
inline constexpr double kWaveCutoff = 1e-3;

/// An immutable linear, long-crested sea.
struct WaveField {
  double g = 9.81;                                         // [m/s^2]
  double depth = std::numeric_limits<double>::infinity();  // water depth h [m]; infinity = deep
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();    // unit horizontal travel direction d [-, R_g]
  std::vector<WaveComponent> components;                   // sorted by z_cut, deepest first
  double ramp_time = 0;  // build-up: everything scaled by r(t), 0 -> 1 over [0, ramp_time] [s]
  bool spread = false;   // short-crested: each component travels along its own (dx, dy), else along `direction`
  bool wheeler = false;  // Wheeler stretching: kinematics up to the surface eta, at the stretched height
                         // z' = (z - eta) h / (h + eta) (deep water: z - eta); else linear up to z = 0

  /// Build-up factor r(t) = s^3 (10 - 15 s + 6 s^2), s = t / ramp_time in [0, 1]
  /// (twice continuously differentiable), and its first two derivatives.
  void ramp(double t, double& r, double& rd, double& rdd) const;

  /// Surface elevation eta at the horizontal position of x [m].
  double elevation(const Eigen::Vector3d& x, double t) const;
  /// Particle velocity at x [m/s, R_g]; zero above the still surface (z > 0),
  /// or with `wheeler` above the wave surface eta, the linear velocity at the
  /// stretched height z' below it (so the crest sees the z = 0 value).
  Eigen::Vector3d velocity(const Eigen::Vector3d& x, double t) const;
  /// Particle (local) acceleration du/dt at x [m/s^2, R_g] (with the
  /// build-up's rate: d(r u)/dt); zero for z > 0 (`wheeler`: z > eta, and
  /// evaluated at z' like the velocity, without the rate of z' itself).
  Eigen::Vector3d acceleration(const Eigen::Vector3d& x, double t) const;
  /// velocity() into *u and acceleration() into *a (either may be null) in
  /// one pass over the harmonics: what a load at a point needs, at the cost
  /// of one sum.
  void kinematics(const Eigen::Vector3d& x, double t, Eigen::Vector3d* u, Eigen::Vector3d* a) const;
  /// The height at which the linear kinematics are evaluated for a point at
  /// height z under the surface eta: z itself, or Wheeler's stretched z' [m].
  double stretched(double z, double eta) const;
  /// Sum of the component variances a_i^2 / 2 [m^2] (Hs = 4 sqrt of it).
  double variance() const;
};

/// Short-crested sea: each component of `w` gets its own travel direction,
/// `direction` turned by theta drawn from the cos-2s spreading function
/// D(theta) ~ cos^(2s)(theta / 2), |theta| <= pi (inverse of its CDF,
/// tabulated, at U = (u >> 11) 2^-53 of std::mt19937_64(seed ^ 0x5eed5eed5eed5eed),
/// one per component in the sea's order of construction, so the phases stay
/// those of the long-crested sea). s > 0 [-].
void spread_directions(WaveField& w, double s, std::uint64_t seed);

/// Wavenumber k [1/m] with omega^2 = g k tanh(k h) (Newton, relative
/// residual <= 1e-14); h = infinity gives k = omega^2 / g.
double wave_number(double omega, double depth, double g);

enum class SpectrumType { Jonswap, PiersonMoskowitz };

/// One-sided spectral density S(omega) [m^2 s] of a JONSWAP spectrum
/// (PM: gamma = 1) with significant wave height hs [m] and peak period
/// tp [s], scaled so that its integral is hs^2 / 16 exactly.
double spectral_density(double hs, double tp, double gamma, double omega);

/// A regular wave of height H [m], period T [s], crest at the origin at t = 0.
WaveField make_regular_wave(double height, double period, const Eigen::Vector3d& direction, double depth, double g);

/// A sea of `n` harmonics from the spectrum (see docs/theory.md "Waves"):
/// equal-energy frequency bins (each component carries hs^2 / (16 n), its
/// frequency the median of its bin, so the record does not repeat), phases
/// 2 pi U with U = (w >> 11) 2^-53 from the 64-bit words w of
/// std::mt19937_64(seed), drawn in increasing frequency: the same sea on
/// every platform.
WaveField make_irregular_sea(double hs, double tp, double gamma, int n, std::uint64_t seed,
                             const Eigen::Vector3d& direction, double depth, double g);

}  // namespace towsim
