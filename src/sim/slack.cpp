// Slack episodes and snap loads of an elastic cable (include/towsim/sim/slack.hpp).
#include "towsim/sim/slack.hpp"

#include <algorithm>

#include "towsim/dynamics/elastic.hpp"

namespace towsim {

void SlackRecord::update(const Model& model, const std::vector<double>& length, const std::vector<double>& rate,
                         double t, double top_unstretched) {
  const auto& els = model.cable.elements;
  int first = 0, last = 0;
  double min_strain = 0, from = 0, to = 0;
  double peak = -1, arc = 0;
  int peak_el = 0;
  for (std::size_t i = 0; i < els.size() && i < length.size(); ++i) {
    const Element& el = els[i];
    // Unstretched length of element i along the cable [m].
    const double Lu = i == 0 && top_unstretched > 0 ? top_unstretched : el.length;
    if (!is_elastic(el)) {
      arc += Lu;
      continue;
    }
    const double strain = element_strain(el, length[i]);
    if (strain < -kSlackStrain) {
      if (first == 0) first = static_cast<int>(i) + 1, from = arc;
      last = static_cast<int>(i) + 1;
      to = arc + Lu;
      min_strain = std::min(min_strain, strain);
    }
    const double T = element_tension(el, length[i], i < rate.size() ? rate[i] : 0.0);
    if (T > peak) peak = T, peak_el = static_cast<int>(i) + 1;
    arc += Lu;
  }
  // Peak tension of the run and of the current snap.
  if (peak > max_tension) max_tension = peak, max_tension_time = t, max_tension_element = peak_el;
  if (active_) slack_time += t - last_t_;
  last_t_ = t;
  if (first > 0) {
    if (!active_) {  // a new episode
      snap_open_ = false;
      active_ = true;
      ++episodes;
      if (events_.size() < kMaxEvents) {
        SlackEvent ev;
        ev.start = ev.end = t;
        ev.first_element = first, ev.last_element = last, ev.from = from, ev.to = to, ev.min_strain = min_strain;
        events_.push_back(ev);
      }
      return;
    }
    if (static_cast<long>(events_.size()) == episodes) {  // widen the open episode
      SlackEvent& ev = events_.back();
      if (first < ev.first_element) ev.first_element = first, ev.from = from;
      if (last > ev.last_element) ev.last_element = last, ev.to = to;
      ev.min_strain = std::min(ev.min_strain, min_strain);
      ev.end = t;
    }
    return;
  }
  const bool kept = static_cast<long>(events_.size()) == episodes && !events_.empty();
  if (active_) {  // taut again: the episode ends, its snap begins
    active_ = false;
    snap_open_ = kept;
    if (kept) events_.back().end = t, events_.back().ended = true;
  }
  if (snap_open_ && peak > events_.back().snap_tension)
    events_.back().snap_tension = peak, events_.back().snap_time = t, events_.back().snap_element = peak_el;
}

void SlackRecord::finish(double t) {
  if (!active_) return;
  slack_time += t - last_t_;
  last_t_ = t;
  if (static_cast<long>(events_.size()) == episodes && !events_.empty()) events_.back().end = t;
}

}  // namespace towsim
