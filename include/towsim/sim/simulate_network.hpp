// Running a compiled Network through time and handing samples to a sink.
#pragma once

#include <vector>

#include "towsim/dynamics/tree.hpp"
#include "towsim/model/network.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim {

/// Everything written for one output time of a network: each line's sample
/// (its tow point is its top: the vessel's tow point, or its node).
struct NetworkSample {
  double t = 0;               // simulated time [s]
  std::vector<Sample> lines;  // per TreeModel::lines entry
};

/// Receives network samples in time order.
class NetworkSink {
 public:
  virtual ~NetworkSink() = default;
  virtual void write(const NetworkSample& s) = 0;
  virtual void flush() = 0;
};

/// A network sink that keeps every sample in memory (tests, tools).
class NetworkMemorySink : public NetworkSink {
 public:
  std::vector<NetworkSample> samples;
  void write(const NetworkSample& s) override { samples.push_back(s); }
  void flush() override {}
};

/// The steady tow of a network (`initial: steady`, docs/theory.md §7.2).
struct NetworkSteady {
  TreeState state;               // every line at rest relative to the tow, moving at `velocity`
  Vec3 velocity = Vec3::Zero();  // the tow velocity [m/s, R_g]
  double yaw = 0;                // the tow points' turn from their t = 0 layout [rad]
  double relaxed_time = 0;       // simulated time the relaxation took [s]
  double residual_speed = 0;     // largest joint speed relative to the tow left [m/s]
  long steps = 0;                // the relaxation's steps
};

/// Joints slower than this relative to the tow: the network is steady [m/s].
inline constexpr double kNetworkSettledSpeed = 1e-6;
/// Longest relaxation [s of simulated time].
inline constexpr double kNetworkRelaxTime = 20000;

/// The steady tow of the network at velocity V [m/s, R_g]: its own dynamics
/// in the tow's frame (the tow points held at their t = 0 positions, turned
/// by `yaw` [rad] about the vertical through the first, the current less V,
/// calm water), integrated from the hanging start (loops assembled) by the
/// Rosenbrock method until every joint moves by less than
/// kNetworkSettledSpeed; then every line at rest relative to the tow,
/// moving at V; from `start` instead of hanging when given (network_statics).
/// Over a flat seabed, the bottom moves at -V in that frame (its friction
/// and damping act on the velocity relative to it). Throws
/// std::invalid_argument for what it cannot relax (network_steady_refusal),
/// std::runtime_error when the relaxation fails, is stopped,
/// stops decaying (a limit cycle) or does not settle within kNetworkRelaxTime.
NetworkSteady network_steady_state(const Network& net, const Vec3& V, double yaw,
                                   const volatile int* stop_flag = nullptr, const TreeState* start = nullptr);

/// Why the network has no steady tow to relax to ("" when it has): a
/// seabed that is not flat (a table of depths moves under the tow), a line
/// from the vessel in force mode.
std::string network_steady_refusal(const Network& net);

/// `initial: steady`: the steady tow at the tow law's velocity at t = 0+
/// (every root line's the same, else std::invalid_argument), tow points as
/// at t = 0.
NetworkSteady network_steady_state(const Network& net, const volatile int* stop_flag = nullptr);

/// `towsim statics`: the steady tow at the tow law's final velocity
/// (final_tow_velocity, as for a chain), the tow points turned with the
/// vessel from its heading before any manoeuvre to its final one. `start`
/// (optional): the shape to relax from (each line's directions, lengths and
/// attitudes; its tops are put where the tow's frame has them), instead of
/// the hanging start.
NetworkSteady network_statics(const Network& net, const volatile int* stop_flag = nullptr,
                              const TreeState* start = nullptr);

/// The steady tow's sample at t = 0 written to `sink` (towsim statics):
/// evaluated in the tow's frame of network_steady_state, every velocity
/// then V plus the frame's (zero); the statistics of that one sample.
RunStats write_network_steady(const Network& net, const NetworkSteady& st, NetworkSink& sink);

/// Integrate the network from its initial state (network_initial_state, or
/// network_steady_state for `initial: steady`) to
/// the run's duration (the first line's simulation settings), writing a
/// sample at t = 0 and every output interval: the run loop of simulate()
/// with the network's system. Never throws on numerical failure.
RunStats simulate_network(const Network& net, NetworkSink& sink, const ProgressFn& progress = {},
                          const volatile int* stop_flag = nullptr);

}  // namespace towsim
