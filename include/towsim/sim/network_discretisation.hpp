// The element count's share of a network run's error: the network's steady
// tow with its elements and with every element halved, and Richardson
// extrapolation (docs/theory.md §7.1, §7.2).
#pragma once

#include "towsim/model/network.hpp"
#include "towsim/sim/discretisation.hpp"

namespace towsim {

/// Largest network (elements of all its lines) whose run gets the estimate:
/// the two steady tows are relaxations of the network's dynamics, the
/// refined one with twice the elements, and their cost grows as the square
/// of the count. Measured on 1000 m of light cable (0.14 kg/m) to a 200 kg
/// sphere at 2 m/s, whose run of 20 s takes 4-18 ms: 2.3 s at 100
/// elements, 9.9 s at 200, 41 s at 400, over 10 min at 1000 [-].
inline constexpr int kNetworkEstimateMaxElements = 250;

/// The relative error of the tow tension due to the element count: for each
/// line from the vessel |T_n - T_2n| / (1 - 2^-p) / |T_n| with
/// p = kDiscretisationOrder, T its top tension in the network's steady tow
/// at the tow law's final velocity (network_statics) with its elements and
/// with every element of every line halved (refined_model); the largest.
/// None (with the message) when a steady tow fails or is interrupted (a
/// bottom that is not flat among the reasons), or above
/// kNetworkEstimateMaxElements elements.
DiscretisationEstimate estimate_network_discretisation(const Network& net, const volatile int* stop_flag = nullptr);

/// The estimate into stats.discretisation_error_estimate and its warning
/// (above kDiscretisationWarnAbove, or why there is none) into stats.warnings.
void record_network_discretisation_estimate(const Network& net, RunStats& stats,
                                            const volatile int* stop_flag = nullptr);

}  // namespace towsim
