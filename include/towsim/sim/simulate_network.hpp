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
  Vec3 velocity = Vec3::Zero();  // the tow velocity at t = 0+ [m/s, R_g]
  double relaxed_time = 0;       // simulated time the relaxation took [s]
  double residual_speed = 0;     // largest joint speed relative to the tow left [m/s]
  long steps = 0;                // the relaxation's steps
};

/// Joints slower than this relative to the tow: the network is steady [m/s].
inline constexpr double kNetworkSettledSpeed = 1e-6;
/// Longest relaxation [s of simulated time].
inline constexpr double kNetworkRelaxTime = 20000;

/// The steady state of the network towed at its tow law's velocity at
/// t = 0+ (every root line's the same): its own dynamics in the tow's frame
/// (the tow points held at their t = 0 positions, the current less the tow
/// velocity, calm water), integrated from the hanging start (loops
/// assembled) by the Rosenbrock method until every joint moves by less than
/// kNetworkSettledSpeed; then every line at rest relative to the tow.
/// Throws std::invalid_argument for what it cannot relax (tow points at
/// different velocities, a seabed: its friction is relative to the bottom,
/// not to the tow), std::runtime_error when the relaxation fails or does not
/// settle within kNetworkRelaxTime.
NetworkSteady network_steady_state(const Network& net, const volatile int* stop_flag = nullptr);

/// Integrate the network from its initial state (network_initial_state, or
/// network_steady_state for `initial: steady`) to
/// the run's duration (the first line's simulation settings), writing a
/// sample at t = 0 and every output interval: the run loop of simulate()
/// with the network's system. Never throws on numerical failure.
RunStats simulate_network(const Network& net, NetworkSink& sink, const ProgressFn& progress = {},
                          const volatile int* stop_flag = nullptr);

}  // namespace towsim
