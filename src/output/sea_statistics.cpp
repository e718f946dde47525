#include "towsim/output/sea_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <tuple>

#include "towsim/output/dft.hpp"

namespace towsim::output {

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
  // Third and fourth central moments: skewness and kurtosis.
  double m3 = 0, m4 = 0;
  for (double v : x) {
    const double d2 = (v - s.mean) * (v - s.mean);
    m3 += d2 * (v - s.mean), m4 += d2 * d2;
  }
  const double var = s.std * s.std, cnt = static_cast<double>(x.size());
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  s.skewness = var > 0 ? m3 / cnt / (var * s.std) : kNaN;
  s.kurtosis = var > 0 ? m4 / cnt / (var * var) : kNaN;
  // Cycle maxima: the largest excess over the mean between consecutive up-crossings.
  std::vector<double> peaks;
  double top = -1;  // < 0: before the first up-crossing
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i - 1] < s.mean && x[i] >= s.mean) {
      if (top >= 0) peaks.push_back(top);
      top = 0;
    }
    if (top >= 0) top = std::max(top, x[i] - s.mean);
  }
  s.peaks = static_cast<long>(peaks.size());
  s.mpm = s.weibull_mpm = s.weibull_shape = s.weibull_scale = s.weibull_threshold = kNaN;
  if (n >= 2) {
    s.zero_crossing_period = (last - first) / static_cast<double>(n - 1);
    const double N = kMpmDuration / s.zero_crossing_period;
    if (N > 1) s.mpm = s.mean + s.std * std::sqrt(2 * std::log(N));
    std::vector<double> positive;
    for (double p : peaks)
      if (p > 0) positive.push_back(p);
    // The upper tail: the top kWeibullTail of the peaks, above the largest of the rest, u.
    std::sort(positive.begin(), positive.end());
    const auto np = static_cast<long>(positive.size());
    const auto top = static_cast<long>(static_cast<double>(np) * kWeibullTail);
    if (top >= kMinPeaks && top < np) {
      const double u = positive[static_cast<std::size_t>(np - top - 1)];
      const auto above = static_cast<double>(positive.end() - std::upper_bound(positive.begin(), positive.end(), u));
      s.weibull_threshold = u;
      std::tie(s.weibull_shape, s.weibull_scale) = weibull_fit(positive, u);
      // Most probable largest of N peaks, a share p above u: P(Y > y) = p exp((u/scale)^b - (y/scale)^b) = 1 / N.
      const double pN = above / static_cast<double>(np) * N, b = s.weibull_shape, sc = s.weibull_scale;
      if (pN > 1 && std::isfinite(b)) s.weibull_mpm = s.mean + sc * std::pow(std::pow(u / sc, b) + std::log(pN), 1 / b);
    }
  }
  s.max_above_mpm = std::isfinite(s.mpm) && s.max > s.mpm;
  return s;
}

std::pair<double, double> weibull_fit(const std::vector<double>& all, double threshold) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const double u = std::max(threshold, 0.0);
  std::vector<double> y;
  for (double v : all)
    if (v > u) y.push_back(v);
  if (y.size() < 2) return {kNaN, kNaN};
  const double n = static_cast<double>(y.size());
  // Scaled by the largest value (the likelihood equation is scale-free): no overflow of y^b.
  const double ymax = *std::max_element(y.begin(), y.end());
  std::vector<double> ly(y.size());
  double mean_ly = 0;
  for (std::size_t i = 0; i < y.size(); ++i) ly[i] = std::log(y[i] / ymax), mean_ly += ly[i] / n;
  if (!(mean_ly < 0)) return {kNaN, kNaN};  // all equal
  // The threshold's terms u^b and u^b ln u, scaled likewise (none for u = 0).
  const double lu = u > 0 ? std::log(u / ymax) : 0.0;
  auto ub = [&](double b) { return u > 0 ? std::exp(b * lu) : 0.0; };
  // g(b) = sum (y^b ln y - u^b ln u) / sum (y^b - u^b) - 1/b - mean ln y increases in b.
  auto g = [&](double b) {
    double sw = 0, swl = 0;
    for (double l : ly) {
      const double w = std::exp(b * l);
      sw += w, swl += w * l;
    }
    const double wu = ub(b);
    return (swl - n * wu * lu) / (sw - n * wu) - 1 / b - mean_ly;
  };
  double lo = 0.05, hi = 50;
  if (g(lo) > 0 || g(hi) < 0) return {kNaN, kNaN};
  while (hi - lo > 1e-12 * hi) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0 ? lo : hi) = mid;
  }
  const double b = 0.5 * (lo + hi);
  double mean_yb = 0;
  for (double l : ly) mean_yb += std::exp(b * l) / n;
  return {b, ymax * std::pow(mean_yb - ub(b), 1 / b)};
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
  // The record's DFT at every Fourier frequency at once (O(N log N)).
  std::vector<double> d(N);
  for (std::size_t n = 0; n < N; ++n) d[n] = x[n] - mean;
  const std::vector<std::complex<double>> X = dft(d);
  const double dw = 2 * std::numbers::pi / (static_cast<double>(N) * dt);
  const std::size_t K = N / 2, b = static_cast<std::size_t>(band);
  for (std::size_t k0 = 1; k0 + b - 1 <= K; k0 += b) {
    double sum = 0;
    for (std::size_t k = k0; k < k0 + b; ++k) {
      // Two-sided I at +/- omega_k, folded: the Nyquist bin (k = N/2, N even) is not doubled.
      const double fold = (2 * k == N) ? 1.0 : 2.0;
      sum += fold * dt / (2 * std::numbers::pi * static_cast<double>(N)) * std::norm(X[k]);
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
      // Gains only where the input carries energy (>= kTransferMask of its peak): elsewhere
      // the input is the record's leakage and the ratio meaningless.
      if (!sd.empty() && peak > 0 && se[j].second >= kTransferMask * peak) f << std::sqrt(sd[j].second / se[j].second);
      f << ',' << sh[j].second << ',';
      if (!sd.empty() && peak_h > 0 && sh[j].second >= kTransferMask * peak_h)
        f << std::sqrt(sd[j].second / sh[j].second);
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
    j["max_above_mpm"] = s.max_above_mpm;
    j["skewness"] = num(s.skewness);
    j["kurtosis"] = num(s.kurtosis);
    j["peaks"] = s.peaks;
    j["weibull_threshold"] = num(s.weibull_threshold);
    j["weibull_shape"] = num(s.weibull_shape);
    j["weibull_scale"] = num(s.weibull_scale);
    j["weibull_mpm"] = num(s.weibull_mpm);
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

std::vector<std::string> SeaStatistics::warnings() const {
  std::vector<std::string> out;
  auto one = [&](const char* name, const std::vector<double>& x) {
    if (x.empty()) return;
    const SignalStats s = signal_stats(t_, x);
    if (!s.max_above_mpm) return;
    std::ostringstream os;
    os << std::setprecision(6) << "statistics." << name << ": the record's maximum " << s.max
       << " exceeds its Gaussian (Rayleigh) " << kMpmDuration / 3600 << "-hour most probable maximum " << s.mpm
       << ": the process is not Gaussian (skewness " << s.skewness << ", kurtosis " << s.kurtosis
       << "); see weibull_mpm " << s.weibull_mpm;
    out.push_back(os.str());
  };
  one("tow_tension", tension_);
  one("link_force", link_);
  one("body_depth", depth_);
  return out;
}

}  // namespace towsim::output
