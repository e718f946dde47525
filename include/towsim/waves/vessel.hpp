// The vessel's wave-induced motion and the tow point it carries
// (INTERFACE.md "Ship motion from waves"; docs/theory.md "Ship motion").
//
// Vessel axes: origin at the RAO origin, x forward along the course, y to
// port, z up. The six motions are surge, sway, heave [m] and roll, pitch,
// yaw [rad]: roll + = starboard down (about +x), pitch + = bow up (about -y:
// a point at x rises by x pitch), yaw + = bow to port (about +z). The tow law
// moves the RAO origin; the course is the direction of its horizontal velocity.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "towsim/model/model.hpp"
#include "towsim/sim/simulate.hpp"
#include "towsim/waves/waves.hpp"

namespace towsim {

/// Displacement RAOs on a full grid of wave periods and relative headings.
struct RaoTable {
  std::vector<double> periods;   // wave periods, increasing [s]
  std::vector<double> headings;  // relative wave headings, increasing, in [0, 360) [deg]
  // Per (dof, heading, period) at index (dof * headings + heading) * periods + period:
  std::vector<double> amplitude;  // per metre of wave amplitude [m/m or deg/m]
  std::vector<double> phase_deg;  // lag behind the wave crest at the RAO origin [deg]
  double amp(int dof, std::size_t h, std::size_t p) const { return amplitude[index(dof, h, p)]; }
  double phase(int dof, std::size_t h, std::size_t p) const { return phase_deg[index(dof, h, p)]; }
  std::size_t index(int dof, std::size_t h, std::size_t p) const {
    return (static_cast<std::size_t>(dof) * headings.size() + h) * periods.size() + p;
  }
};

/// The six motions of the vessel and their rates at one instant, vessel axes.
struct VesselMotion {
  Vec6 x = Vec6::Zero(), v = Vec6::Zero(), a = Vec6::Zero();  // [m, rad], per s, per s^2
  double course = 0;                                          // psi: direction of the course from x_g [rad]
  double course_rate = 0;                                     // dpsi/dt [rad/s]
  double elevation = 0;                                       // wave elevation at the RAO origin [m]
};

/// An immutable vessel: RAOs in a sea, or a measured motion record.
class Vessel {
 public:
  /// RAO-driven: `raos` in the sea `waves` (headings relative to the course).
  Vessel(const Vec3& tow_point, double initial_course, std::shared_ptr<const WaveField> waves, const RaoTable& raos);
  /// Measured motions: rows at `time` [s] of (surge, sway, heave [m], roll,
  /// pitch, yaw [rad]), a natural cubic spline through them, held at the ends.
  /// `waves` (may be null) only gives the elevation output.
  Vessel(const Vec3& tow_point, double initial_course, std::shared_ptr<const WaveField> waves, std::vector<double> time,
         std::vector<Vec6> motions);

  /// The motions at t for the RAO origin moving as `origin` (the tow law);
  /// the wave elevation there only `with_elevation` (else 0: one sum less).
  VesselMotion motion(const TowKinematics& origin, double t, bool with_elevation = true) const;
  /// The tow point: sheave offset r_s moved by the motions (small angles:
  /// r_s + translation + theta x r_s, theta = (roll, -pitch, yaw)), turned to
  /// the course, on the origin.
  TowKinematics tow_point(const TowKinematics& origin, double t) const;
  /// True for a measured motion record (else RAOs).
  bool measured() const { return !time_.empty(); }
  /// Turn the sheave offset by the exact rotation R = Rz(yaw) Ry(-pitch) Rx(roll)
  /// instead of the small-angle theta x r_s (`vessel.rotations: exact`).
  void set_exact_rotations(bool exact) { exact_ = exact; }
  /// The sheave offset r_s [m, vessel axes].
  const Vec3& sheave() const { return sheave_; }

 private:
  Vec3 sheave_;     // r_s [m, vessel axes]
  double course0_;  // course while the vessel is (nearly) at rest [rad]
  std::shared_ptr<const WaveField> waves_;
  // RAOs per wave component, interpolated in period at construction, at each
  // table heading: index (component * headings + heading) * 6 + dof.
  std::vector<double> headings_;   // [deg]
  std::vector<double> amp_, lag_;  // [m/m or rad/m], [rad]
  std::vector<double> dlag_;       // lag at the next heading (periodic) minus this one's, in (-pi, pi] [rad]
  bool mirror_ = false;            // headings only in [0, 180]: port-starboard symmetry
  bool exact_ = false;             // exact rotation of the sheave offset
  // cos and sin of every lag at one heading weight (long-crested seas):
  // index component * 6 + dof, for this vessel (id) and heading interval h0-h1 at weight w.
  struct LagTable {
    std::uint64_t id = 0;
    std::size_t h0 = 0, h1 = 0;
    double w = 0;
    std::vector<double> cos, sin;  // [-]
  };
  const LagTable& lag_table(std::size_t h0, std::size_t h1, double w) const;
  std::uint64_t id_ = 0;  // this RAO vessel's number (0: a measured record), keys the lag tables
  static std::atomic<std::uint64_t> next_id_;
  // Measured record.
  std::vector<double> time_;
  std::vector<Vec6> rec_, curv_;  // values and spline second derivatives
};

/// The vessel's initial course from the tow law: the direction of its
/// horizontal velocity just after t = 0 (else at t = 1 s), +x_g at rest [rad].
double initial_course(const Tow& tow);

/// True when the model has waves or a vessel (sea-state outputs).
inline bool has_sea(const Model& m) { return m.fluid.waves || m.tow.vessel; }

/// Start of the sea-state statistics [s] (Simulation::statistics_start).
inline double statistics_start(const Model& m) {
  return m.sim.statistics_start >= 0 ? m.sim.statistics_start : 0.5 * m.sim.duration;
}

/// Fill a sample's sea-state fields: wave elevation at the vessel's RAO
/// origin (else at the tow point), tow-point displacement by the vessel's
/// wave motion. Needs out.tow_pos.
void sea_sample(const Model& model, double t, Sample& out);

}  // namespace towsim
