// Transient figures per manoeuvre phase (include/towsim/output/transients.hpp).
#include "towsim/output/transients.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "towsim/output/output.hpp"

namespace towsim::output {

namespace {

/// {value, time}: nulls when never set.
nlohmann::ordered_json extreme(double v, double t) {
  return {{"value", num(v)}, {"time", std::isnan(v) ? nlohmann::ordered_json(nullptr) : num(t)}};
}

/// Where a phase comes from, as a scenario key: tow.motion.N, tow.force, winch; null for steady.
nlohmann::ordered_json source_of(const Phase& p) {
  if (p.winch) return "winch";
  if (p.kind == Phase::Kind::ForceChange) return "tow.force";
  if (p.piece >= 0) return "tow.motion." + std::to_string(p.piece);
  return nullptr;
}

}  // namespace

void Settling::add(double t, double v) {
  if (samples_++ == 0) first_ = v, first_t_ = t;
  last_t_ = t;
  last_ = v;
  // The newest sample is the top of both staircases: it gets its successor's time.
  if (!hi_.empty()) hi_.back().t_next = t;
  if (!lo_.empty()) lo_.back().t_next = t;
  while (!hi_.empty() && hi_.back().v <= v) hi_.pop_back();
  while (!lo_.empty() && lo_.back().v >= v) lo_.pop_back();
  hi_.push_back({t, v, t});
  lo_.push_back({t, v, t});
}

Settling::Result Settling::result(double change_fraction, double value_fraction, double floor, double hold_fraction,
                                  double window_start) const {
  Result r;
  if (samples_ == 0) return r;
  r.first = first_;
  r.settled = last_;
  r.band = std::max({change_fraction * std::abs(last_ - first_), value_fraction * std::abs(last_), floor});
  if (samples_ < 2) return r;
  // The last sample above last + band is the last staircase step above it (every
  // sample after it is lower), and the same below; the signal settles at the sample after.
  double since = first_t_;
  for (auto it = hi_.rbegin(); it != hi_.rend(); ++it)
    if (it->v > last_ + r.band) {
      since = std::max(since, it->t_next);
      break;
    }
  for (auto it = lo_.rbegin(); it != lo_.rend(); ++it)
    if (it->v < last_ - r.band) {
      since = std::max(since, it->t_next);
      break;
    }
  if (last_t_ - since >= hold_fraction * (last_t_ - window_start)) r.since = since;
  return r;
}

TransientRecord::TransientRecord(std::vector<Phase> phases, double duration, bool link)
    : phases_(std::move(phases)), figures_(phases_.size()), duration_(tidy_time(duration)), link_(link) {
  for (Phase& p : phases_) {  // compared with the times as written
    p.start = tidy_time(p.start);
    p.end = tidy_time(p.end);
    p.settle_end = tidy_time(p.settle_end);
  }
}

void TransientRecord::add(double t, double tow_tension, double depth, double link_tension) {
  const double v[3] = {tow_tension, depth, link_tension};
  for (std::size_t i = 0; i < phases_.size(); ++i) {
    const Phase& p = phases_[i];
    // [start, end), closed at the run's end.
    auto before = [this, t](double end) { return t < end || (t == end && end >= duration_); };
    if (t < p.start || !before(p.settle_end)) continue;
    for (int k = 0; k < (link_ ? 3 : 2); ++k) {
      Quantity& q = figures_[i].q[k];
      if (std::isnan(v[k])) continue;
      q.settling.add(t, v[k]);
      if (!before(p.end)) continue;
      if (std::isnan(q.max) || v[k] > q.max) q.max = v[k], q.max_t = t;
      if (std::isnan(q.min) || v[k] < q.min) q.min = v[k], q.min_t = t;
    }
  }
}

nlohmann::ordered_json TransientRecord::json(double end_time) const {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  int count[9] = {};  // per kind, for the names
  const char* names[3] = {"tow_tension", "depth", "link_tension"};
  const double floors[3] = {kSettleTensionFloor, kSettleDepthFloor, kSettleTensionFloor};
  const double value_fractions[3] = {kSettleValueFraction, 0.0, kSettleValueFraction};  // not for a position
  for (std::size_t i = 0; i < phases_.size(); ++i) {
    const Phase& p = phases_[i];
    const bool reached = tidy_time(end_time) >= p.settle_end;  // the window's end was simulated
    nlohmann::ordered_json o;
    o["name"] = std::string(phase_kind_name(p.kind)) + " " + std::to_string(++count[static_cast<int>(p.kind)]);
    o["kind"] = phase_kind_name(p.kind);
    o["source"] = source_of(p);
    o["start"] = num(p.start);
    o["end"] = num(p.end);
    o["settle_end"] = num(p.settle_end);
    double settle[3];
    nlohmann::ordered_json q_json[3];
    for (int k = 0; k < (link_ ? 3 : 2); ++k) {
      const Quantity& q = figures_[i].q[k];
      const Settling::Result r = q.settling.result(kSettleChangeFraction, value_fractions[k], floors[k],
                                                   kSettleHoldFraction, p.start);
      settle[k] = reached ? tidy_time(r.since - p.start) : std::nan("");
      nlohmann::ordered_json j;
      j["min"] = extreme(q.min, q.min_t);
      j["max"] = extreme(q.max, q.max_t);
      j["settled_value"] = reached ? num(r.settled) : nlohmann::ordered_json(nullptr);
      j["band"] = reached ? num(tidy(r.band)) : nlohmann::ordered_json(nullptr);
      j["settle_time"] = num(settle[k]);
      q_json[k] = j;
    }
    // The phase settles when its tow tension and its depth have.
    o["settle_time"] = std::isnan(settle[0]) || std::isnan(settle[1]) ? nlohmann::ordered_json(nullptr)
                                                                      : num(std::max(settle[0], settle[1]));
    for (int k = 0; k < (link_ ? 3 : 2); ++k) o[names[k]] = q_json[k];
    list.push_back(o);
  }
  return list;
}

}  // namespace towsim::output
