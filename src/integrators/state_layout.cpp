// The flat states' layouts (docs/theory.md §6).
#include "towsim/integrators/state_layout.hpp"

#include <algorithm>

#include "towsim/dynamics/paper.hpp"
#include "towsim/dynamics/state.hpp"

namespace towsim {

namespace {

/// The block of `size` rows after `prev`.
StateBlock after(const StateBlock& prev, std::size_t size) { return {prev.end(), size}; }

}  // namespace

StateLayout StateLayout::default_of(const Model& model) {
  StateLayout l;
  const std::size_t n = model.cable.elements.size();
  std::size_t controls = 0;
  for (const Body& b : model.bodies) controls += static_cast<std::size_t>(control_count(b));
  l.elements = n;
  l.tow = {0, 6};
  l.directions = after(l.tow, 3 * n);
  l.rates = after(l.directions, 3 * n);
  l.bodies = after(l.rates, kBodyRows * model.bodies.size());
  l.winch = after(l.bodies, model.winch.active() && n > 0 ? 2 : 0);
  l.lengths = after(l.winch, lengths_in_state(model) ? 2 * n : 0);
  l.controls = after(l.lengths, 2 * controls);
  // The paper's blocks: absent, at the end.
  l.angles = l.angle_rates = l.charts = after(l.controls, 0);
  l.size = l.controls.end();
  return l;
}

StateLayout StateLayout::paper_of(const Model& model) {
  StateLayout l;
  const auto na = static_cast<std::size_t>(paper_angle_count(model));
  l.elements = model.cable.elements.size();
  l.tow = {0, 6};
  // The default formulation's blocks: absent, after the tow point.
  l.directions = l.rates = l.bodies = l.winch = l.lengths = l.controls = after(l.tow, 0);
  l.angles = after(l.tow, na);
  l.angle_rates = after(l.angles, na);
  l.charts = after(l.angle_rates, kChartRows * (l.elements + model.bodies.size()));
  l.size = l.charts.end();
  return l;
}

std::string StateLayout::describe(std::size_t i, const Model& model) const {
  const auto element = [](std::size_t k) { return "element " + std::to_string(k + 1); };
  const auto body = [&model](std::size_t b) {
    return "body " + model.bodies[std::min(b, model.bodies.size() - 1)].name;
  };
  if (tow.contains(i)) return "tow point";
  if (directions.contains(i)) return element((i - directions.offset) / 3);
  if (rates.contains(i)) return element((i - rates.offset) / 3);
  if (bodies.contains(i)) return body((i - bodies.offset) / kBodyRows);
  if (winch.contains(i)) return "winch";
  if (lengths.contains(i)) return element((i - lengths.offset) % elements) + " (length)";
  if (controls.contains(i)) return "depth controller " + std::to_string((i - controls.offset) / 2 + 1);
  if (angles.contains(i) || angle_rates.contains(i)) {
    const std::size_t j = (i - angles.offset) % angles.size;
    return j < 2 * elements ? element(j / 2) : std::string("body");
  }
  if (charts.contains(i)) {
    const std::size_t k = (i - charts.offset) / kChartRows;
    return (k < elements ? element(k) : std::string("body")) + " (chart)";
  }
  return "row " + std::to_string(i);
}

}  // namespace towsim
