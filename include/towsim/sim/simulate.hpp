// Running a compiled Model through time and handing samples to an output sink.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "towsim/dynamics/state.hpp"
#include "towsim/sim/slack.hpp"

namespace towsim {

/// One depth controller's outputs at a sample time.
struct ControlSample {
  double deflection_deg = 0;  // applied deflection delta [deg]
  double rate_deg_s = 0;      // d delta/dt [deg/s]
  double depth_error = 0;     // e = depth - target_depth [m]
};

/// One body's outputs at a sample time.
struct BodySample {
  Vec3 pos;                               // O_t [m, R_g]
  Vec3 vel;                               // velocity of O_t [m/s, R_g]
  Vec3 rpy_deg;                           // roll phi, pitch theta, yaw psi (ZYX as in the paper) [deg]
  Vec3 omega;                             // angular velocity [rad/s, R_g]
  Vec3 link_force;                        // F_L exerted by the cable above on the body at Q [N, R_g]
  Vec3 lower_link_force;                  // in-line body: force on the cable below at Q2 [N, R_g]
  std::vector<ControlSample> controls{};  // per surface with a depth controller, in surface order
};

/// Everything written for one output time (docs/scenario.md "Output files").
/// Nodes are the cable's joints top to bottom; an in-line body's joint gives
/// two nodes, its upper link Q (end of the section above) then its lower
/// link Q2 (top of the section below).
struct Sample {
  double t = 0;                     // simulated time [s]
  Vec3 tow_pos, tow_vel;            // O_r = P_0 [m], [m/s], R_g
  Vec3 tow_force;                   // F_R exerted by the vessel on the cable at O_r [N, R_g]
  double deployed_length = 0;       // sum of the element lengths [m]
  double payout_speed = 0;          // winch: l_1', cable leaving the sheave (< 0: hauled in) [m/s]
  std::vector<long> node_id;        // per node: its material identity, stable across winch events [-]
  std::vector<Vec3> node_pos;       // cable nodes [m, R_g]
  std::vector<Vec3> node_vel;       // their velocities [m/s, R_g]
  std::vector<double> tension;      // |force carried through the node onto the part below| [N]
  std::vector<double> axial;        // that force along the adjacent element (the one above; below, at the
                                    // top of a section): positive in tension, negative in compression [N]
  std::vector<double> strain;       // strain l/L - 1 of the same adjacent element (0: inextensible;
                                    // < 0: slack, no tension) [-]
  std::vector<double> utilisation;  // per node: tension / breaking load of its section [-] (0 where none is
                                    // given); empty when no section gives a breaking load
  std::vector<Vec3> node_seabed;    // per node: the seabed's contact force on the cable there [N, R_g];
                                    // empty without a seabed
  std::vector<double> bending;      // per node: |bending moment| of the joint's spring [N m] (0 at the
                                    // ends and at bodies); empty without bending stiffness
  double contact_length = 0;        // cable length in contact with the seabed [m]
  double touchdown_arc_length = 0;  // arc length along the elements from the tow point to the first point
                                    // of the cable below the bottom [m] (NaN: none, or no seabed)
  Vec3 touchdown = Vec3::Zero();    // that point [m, R_g] (NaN: none)
  double lying_length = 0;          // cable length beyond the touchdown point [m] (0: none)
  double seabed_normal = 0;         // sum of |normal force| of the seabed on the cable and the bodies [N]
  double seabed_friction = 0;       // sum of |friction force| [N]
  std::vector<BodySample> bodies;   // per Model::bodies entry
  bool has_waves = false;           // waves or a vessel in the model
  double wave_elevation = 0;        // at the vessel's RAO origin (else at the tow point) [m]
  Vec3 tow_wave = Vec3::Zero();     // tow point displacement by the vessel's wave motion [m, R_g]
};

/// The sample of a physical state at time t from a workspace the dynamics
/// just filled for it (forward_dynamics(model, s, t, ws)): the one place
/// where outputs are assembled, for runs and statics alike.
Sample make_sample(const Model& model, const PhysicalState& s, const Workspace& ws, double t);
/// The same into `out`, every field set again (its vectors' storage reused).
void make_sample(const Model& model, const PhysicalState& s, const Workspace& ws, double t, Sample& out);

/// Receives samples in time order. Implementations write files.
class OutputSink {
 public:
  virtual ~OutputSink() = default;
  /// Record one sample.
  virtual void write(const Sample& s) = 0;
  /// Push everything recorded so far to disk.
  virtual void flush() = 0;
};

/// A sink that keeps every sample in memory (tests, statics, tools).
class MemorySink : public OutputSink {
 public:
  std::vector<Sample> samples;
  void write(const Sample& s) override { samples.push_back(s); }
  void flush() override {}
};

/// How a run ended and what it cost.
struct RunStats {
  std::string status = "ok";          // "ok", "failed" (numerical), "interrupted"
  std::string message;                // why it failed: time, element or body, quantity
  double end_time = 0;                // last simulated time reached [s]
  long steps = 0;                     // accepted steps
  long rejected_steps = 0;            // adaptive: rejected trial steps
  long rhs_evaluations = 0;           // evaluations of the dynamics
  double wall_seconds = 0;            // wall-clock time of the integration [s]
  std::string integrator;             // the method used: rk4, dopri5, cash_karp54, rosenbrock
  int threads = 1;                    // threads the dynamics were evaluated on (evaluation_threads) [-]
  double error_estimate = -1;         // rosenbrock: largest local error estimate of an accepted step,
                                      // relative, state and tow/link forces [-]; < 0: none
  double force_error_estimate = -1;   // rosenbrock: its part from the tow and link forces [-]; < 0: none
  double rk4_step_limit = -1;         // rk4: smallest estimated stability limit over the samples [s]; < 0: none
  std::vector<std::string> warnings;  // e.g. an rk4 step beyond the estimated stability limit
  long winch_splits = 0;              // top elements split as cable was paid out [-]
  long winch_removals = 0;            // top elements removed as cable was hauled in [-]
  double winch_energy_lost = 0;       // kinetic energy lost at removals (Removal::energy_lost, summed) [J]
  double max_element_drift = 0;       // max |  |P_k - P_{k-1}| / l_k - 1 | seen (l_k: the state's length) [-]
  SlackRecord slack;                  // elastic cable: slack episodes, snap and peak element tensions
  // Relative error of the steady tow tension due to the element count
  // (record_discretisation_estimate, towsim/sim/discretisation.hpp) [-]; < 0: none.
  double discretisation_error_estimate = -1;
};

/// Estimated largest stable RK4 step for the state whose evaluation `ws`
/// holds (at time t [s]): the rocking mode of a short element under tension T,
/// omega_max = 2 sqrt(3) sqrt(T / (L (m + m_a))), h_max = 2 sqrt(2) / omega_max
/// = sqrt(2/3) sqrt(L (m + m_a) / T), and the drag damping of an element,
/// h_max = 2.785 / sigma, sigma = drag damping / inertia (docs/theory.md §6.4).
/// Smallest over the elements; `element` (1-based) and `tension` [N] say where. [s]
double rk4_step_limit(const Model& model, const Workspace& ws, double t, int* element = nullptr,
                      double* tension = nullptr);

/// Progress callback: fraction done in [0, 1].
using ProgressFn = std::function<void(double)>;

/// Integrate `model` from its initial state to `model.sim.duration`, writing a
/// sample at t = 0 and every `output_interval`. Never throws on numerical
/// failure: it stops, flushes the sink and reports it in RunStats.
/// `stop_flag`, when non-null and set, interrupts the run cleanly.
RunStats simulate(const Model& model, OutputSink& sink, const ProgressFn& progress = {},
                  const volatile int* stop_flag = nullptr);

}  // namespace towsim
