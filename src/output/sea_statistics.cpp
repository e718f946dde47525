#include "towsim/output/sea_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numbers>

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

void SeaStatistics::add(const Model& model, const Sample& s) {
  if (s.t < start_) return;
  t_.push_back(s.t);
  eta_.push_back(s.wave_elevation);
  tension_.push_back(s.tow_force.norm());
  tow_heave_.push_back(s.tow_wave.z());
  if (end_body(model) == nullptr || s.bodies.empty()) return;
  const BodySample& b = s.bodies.back();  // the end body is the last of the chain
  link_.push_back(b.link_force.norm());
  depth_.push_back(-b.pos.z());
}

std::vector<std::pair<double, double>> spectral_density_estimate(const std::vector<double>& x, double dt, int band) {
  std::vector<std::pair<double, double>> out;
  const std::size_t N = x.size();
  if (N < 4 || band < 1 || !(dt > 0)) return out;
  double mean = 0;
  for (double v : x) mean += v / static_cast<double>(N);
  const double dw = 2 * std::numbers::pi / (static_cast<double>(N) * dt);
  const std::size_t K = N / 2, b = static_cast<std::size_t>(band);
  for (std::size_t k0 = 1; k0 + b - 1 <= K; k0 += b) {
    double sum = 0;
    for (std::size_t k = k0; k < k0 + b; ++k) {
      // Direct DFT at omega_k by a rotating phasor (O(N) per frequency).
      const std::complex<double> step = std::polar(1.0, -dw * static_cast<double>(k) * dt);
      std::complex<double> z = 1, acc = 0;
      for (double v : x) acc += (v - mean) * z, z *= step;
      // Two-sided I at +/- omega_k, folded: the Nyquist bin (k = N/2, N even) is not doubled.
      const double fold = (2 * k == N) ? 1.0 : 2.0;
      sum += fold * dt / (2 * std::numbers::pi * static_cast<double>(N)) * std::norm(acc);
    }
    out.emplace_back(dw * (static_cast<double>(k0) + 0.5 * static_cast<double>(b - 1)), sum / static_cast<double>(b));
  }
  return out;
}

bool SeaStatistics::write_spectra(const std::string& path) const {
  std::ofstream f(path);
  f << std::setprecision(12);  // as the other output files
  f << "omega,wave_elevation,tow_tension,link_force,body_depth,body_heave_per_wave,tow_heave,"
       "body_heave_per_tow_heave\n";
  if (t_.size() >= 4) {
    const double dt = (t_.back() - t_.front()) / static_cast<double>(t_.size() - 1);
    constexpr int kBand = 5;  // Fourier bins per estimate: ~10 degrees of freedom
    const auto se = spectral_density_estimate(eta_, dt, kBand), st = spectral_density_estimate(tension_, dt, kBand);
    const auto sl = spectral_density_estimate(link_, dt, kBand), sd = spectral_density_estimate(depth_, dt, kBand);
    const auto sh = spectral_density_estimate(tow_heave_, dt, kBand);
    double peak = 0, peak_h = 0;
    for (const auto& p : se) peak = std::max(peak, p.second);
    for (const auto& p : sh) peak_h = std::max(peak_h, p.second);
    for (std::size_t j = 0; j < se.size(); ++j) {
      f << se[j].first << ',' << se[j].second << ',' << st[j].second << ',';
      if (!sl.empty()) f << sl[j].second;
      f << ',';
      if (!sd.empty()) f << sd[j].second;
      f << ',';
      // Gains only where the input carries energy (>= 1e-3 of its peak): elsewhere 0/0.
      if (!sd.empty() && peak > 0 && se[j].second >= 1e-3 * peak) f << std::sqrt(sd[j].second / se[j].second);
      f << ',' << sh[j].second << ',';
      if (!sd.empty() && peak_h > 0 && sh[j].second >= 1e-3 * peak_h) f << std::sqrt(sd[j].second / sh[j].second);
      f << '\n';
    }
  }
  f.flush();
  return static_cast<bool>(f);
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
