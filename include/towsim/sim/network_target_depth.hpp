// `towsim statics --target-depth` on a network: the deployed length of the
// line from the vessel for which the network's deepest body (or, without
// bodies, its deepest line end) tows at a given depth (docs/scenario.md
// "Statics of a network").
#pragma once

#include <string>

#include "towsim/sim/simulate_network.hpp"

namespace towsim {

/// The search's result.
struct NetworkTargetDepth {
  bool found = false;
  std::string message;   // why not, when not found
  int line = -1;         // the line from the vessel whose length is varied (TreeModel::lines index) [-]
  double length = 0;     // its deployed length found [m]
  double depth = 0;      // the deepest body's (or line end's) depth there [m]
  int evaluations = 0;   // steady tows computed [-]
  Network network;       // the network with that length
  NetworkSteady steady;  // its steady tow (network_statics)
};

/// Depth of the network's deepest body origin (or, without bodies, of its
/// deepest line end) in the steady tow st [m, positive down]; with
/// `below` >= 0, of those that hang below that line from the vessel.
double deepest_depth(const Network& net, const NetworkSteady& st, int below = -1);

/// The length of the network's one line from the vessel (its top section's
/// elements stretched or shortened together, with_deployed_length) for which
/// deepest_depth of its steady tow (network_statics) is `depth` [m], to
/// 1e-3 m: bracketed by halving or doubling the length, then regula falsi
/// (Illinois). Not found (with the message) when the network has more than
/// one line from the vessel, the depth is out of reach, or a steady tow fails.
/// With `line` >= 0 (a line from the vessel, TreeModel::lines index): that
/// line's length, for the deepest body (or line end) below it.
NetworkTargetDepth network_length_for_depth(const Network& net, double depth, const volatile int* stop_flag = nullptr,
                                            int line = -1);

}  // namespace towsim
