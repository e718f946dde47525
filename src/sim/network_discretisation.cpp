// The element count's share of a network run's error
// (towsim/sim/network_discretisation.hpp).
#include "towsim/sim/network_discretisation.hpp"

#include <cmath>
#include <exception>

#include "towsim/sim/simulate_network.hpp"

namespace towsim {

namespace {

/// The top tension of every line in the steady tow st [N].
std::vector<double> top_tensions(const Network& net, const NetworkSteady& st) {
  NetworkMemorySink mem;
  write_network_steady(net, st, mem);
  std::vector<double> T;
  for (const Sample& l : mem.samples.front().lines) T.push_back(l.tow_force.norm());
  return T;
}

/// A line's state with every element split in two halves along it (the
/// order of refined_model), at rest.
PhysicalState halved(const PhysicalState& s) {
  PhysicalState h = s;
  h.e.clear(), h.w.clear(), h.length.clear(), h.length_rate.clear();
  for (std::size_t k = 0; k < s.e.size(); ++k) {
    h.e.insert(h.e.end(), 2, s.e[k]);
    h.w.insert(h.w.end(), 2, Vec3::Zero());
    if (k < s.length.size()) h.length.insert(h.length.end(), 2, 0.5 * s.length[k]);
    if (k < s.length_rate.size()) h.length_rate.insert(h.length_rate.end(), 2, 0.0);
  }
  return h;
}

}  // namespace

DiscretisationEstimate estimate_network_discretisation(const Network& net, const volatile int* stop_flag) {
  DiscretisationEstimate d;
  d.proxy = needs_steady_proxy(net.settings());
  for (const Model& m : net.tree.lines) d.elements += m.cable.n();
  if (d.elements > kNetworkEstimateMaxElements) {
    d.message = "not made above " + std::to_string(kNetworkEstimateMaxElements) + " elements (this network has " +
                std::to_string(d.elements) +
                "; its two steady tows by relaxation would cost more than the run: towsim statics on the network "
                "with its elements doubled gives the refined tensions)";
    return d;
  }
  try {
    // The steady tow with the network's elements, then with every element halved.
    const NetworkSteady coarse = network_statics(net, stop_flag);
    Network fine = net;
    for (Model& m : fine.tree.lines) m = refined_model(m, 2);
    // Relaxed from the coarse shape, each element's two halves along it.
    TreeState start = coarse.state;
    for (std::size_t i = 0; i < start.size(); ++i) start[i] = halved(coarse.state[i]);
    const NetworkSteady refined = network_statics(fine, stop_flag, &start);
    const std::vector<double> Tn = top_tensions(net, coarse), T2n = top_tensions(fine, refined);
    d.speed = coarse.velocity.norm();
    // The worst line from the vessel.
    for (std::size_t i = 0; i < Tn.size(); ++i) {
      if (net.tree.tops[i].line >= 0 || !(Tn[i] > 0)) continue;
      const double e = std::abs(Tn[i] - T2n[i]) / (1 - std::pow(2.0, -kDiscretisationOrder)) / Tn[i];
      if (e > d.estimate) d.estimate = e, d.tension = Tn[i], d.refined_tension = T2n[i];
    }
    if (!d.available()) d.message = "the tow tension is zero";
  } catch (const std::exception& e) {
    d.interrupted = stop_flag != nullptr && *stop_flag != 0;
    d.estimate = -1;
    d.message = e.what();
  }
  return d;
}

void record_network_discretisation_estimate(const Network& net, RunStats& stats, const volatile int* stop_flag) {
  if (stats.status == "interrupted") return;
  const DiscretisationEstimate d = estimate_network_discretisation(net, stop_flag);
  stats.discretisation_error_estimate = d.estimate;
  if (const std::string w = discretisation_warning(d, ElementAdvice{}); !w.empty()) stats.warnings.push_back(w);
}

}  // namespace towsim
