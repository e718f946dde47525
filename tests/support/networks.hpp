// Networks built in code for the tests (no YAML).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "towsim/model/network.hpp"

namespace towsim::testing {

/// A network of the given lines, tops and loops, its lines named l0, l1, ...
inline Network network_of(std::vector<Model> lines, std::vector<LineTop> tops, std::vector<LoopJoint> loops = {}) {
  Network net;
  net.name = "net";
  net.tree.lines = std::move(lines);
  net.tree.tops = std::move(tops);
  net.tree.loops = std::move(loops);
  for (std::size_t i = 0; i < net.tree.lines.size(); ++i) net.line_names.push_back("l" + std::to_string(i));
  return net;
}

/// Fixed-step rk4 settings for a run of `duration` [s] at step h [s], a sample every 0.5 s.
inline void rk4(Model& m, double duration, double h) {
  m.sim.integrator = Integrator::RK4;
  m.sim.time_step = h;
  m.sim.duration = duration;
  m.sim.output_interval = 0.5;
}

}  // namespace towsim::testing
