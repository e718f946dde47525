// Running a compiled Network through time and handing samples to a sink.
#pragma once

#include <vector>

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

/// Integrate the network from its initial state (network_initial_state) to
/// the run's duration (the first line's simulation settings), writing a
/// sample at t = 0 and every output interval: the run loop of simulate()
/// with the network's system. Never throws on numerical failure.
RunStats simulate_network(const Network& net, NetworkSink& sink, const ProgressFn& progress = {},
                          const volatile int* stop_flag = nullptr);

}  // namespace towsim
