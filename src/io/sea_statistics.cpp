#include "towsim/io/sea_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace towsim::io {

SignalStats signal_stats(const std::vector<double>& t, const std::vector<double>& x) {
  SignalStats s;
  s.samples = static_cast<long>(x.size());
  if (x.empty()) return s;
  double sum = 0;
  for (double v : x) sum += v;
  s.mean = sum / static_cast<double>(x.size());
  double ss = 0;
  for (double v : x) ss += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(ss / static_cast<double>(x.size()));
  s.min = *std::min_element(x.begin(), x.end());
  s.max = *std::max_element(x.begin(), x.end());
  // Up-crossings of the mean: the first and last bound whole cycles.
  double first = 0, last = 0;
  long n = 0;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < s.mean && x[i] >= s.mean) {
      const double tc = t[i - 1] + (t[i] - t[i - 1]) * (s.mean - x[i - 1]) / (x[i] - x[i - 1]);
      if (n == 0) first = tc;
      last = tc;
      ++n;
    }
  s.mpm = std::numeric_limits<double>::quiet_NaN();
  if (n >= 2) {
    s.zero_crossing_period = (last - first) / static_cast<double>(n - 1);
    const double N = kMpmDuration / s.zero_crossing_period;
    if (N > 1) s.mpm = s.mean + s.std * std::sqrt(2 * std::log(N));
  }
  return s;
}

void SeaStatistics::add(const Sample& s) {
  if (s.t < start_) return;
  t_.push_back(s.t);
  tension_.push_back(s.tow_force.norm());
  if (!s.has_body) return;
  link_.push_back(s.link_force.norm());
  depth_.push_back(-s.body_pos.z());
}

nlohmann::ordered_json SeaStatistics::json() const {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  auto one = [&](const std::vector<double>& x) {
    const SignalStats s = signal_stats(t_, x);
    nlohmann::ordered_json j;
    j["mean"] = num(s.mean);
    j["std"] = num(s.std);
    j["min"] = num(s.min);
    j["max"] = num(s.max);
    j["zero_crossing_period"] = s.zero_crossing_period > 0 ? num(s.zero_crossing_period) : nullptr;
    j["mpm"] = num(s.mpm);
    return j;
  };
  nlohmann::ordered_json j;
  j["from_time"] = num(start_);
  j["duration"] = t_.empty() ? 0.0 : t_.back() - t_.front();
  j["mpm_duration"] = kMpmDuration;
  j["samples"] = t_.size();
  j["tow_tension"] = one(tension_);
  if (!link_.empty()) {
    j["link_force"] = one(link_);
    j["body_depth"] = one(depth_);
  }
  return j;
}

}  // namespace towsim::io
