// Sea-state statistics of a run's signals for summary.json (INTERFACE.md
// "Ship motion from waves"): mean, standard deviation, extremes, mean
// zero-up-crossing period and the most probable maximum over 3 hours.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/sim/simulate.hpp"

namespace towsim::output {

/// Duration of the most probable maximum [s] (a 3-hour storm).
inline constexpr double kMpmDuration = 3 * 3600.0;

/// Statistics of one sampled signal x(t).
struct SignalStats {
  long samples = 0;
  double mean = 0, std = 0, min = 0, max = 0;  // [unit of x]
  double zero_crossing_period = 0;             // record length / up-crossings of the mean [s]; 0 = none
  double mpm = 0;                // mean + std sqrt(2 ln(kMpmDuration / Tz)) (Rayleigh maxima); NaN without crossings
  double skewness = 0;           // m3 / std^3 (0 for a Gaussian process) [-]; NaN when std = 0
  double kurtosis = 0;           // m4 / std^4 (3 for a Gaussian process) [-]; NaN when std = 0
  bool max_above_mpm = false;    // the record's max exceeds its Rayleigh 3-hour mpm: the Gaussian model fails
  long peaks = 0;                // cycle maxima: the largest sample between consecutive mean up-crossings
  double weibull_threshold = 0;  // u: the peaks' excess over the mean above which the Weibull law is fitted,
                                 // the largest not among the top kWeibullTail of them [unit of x]
  double weibull_shape = 0;      // beta of the Weibull law fitted to the excesses above u (Rayleigh: 2) [-]
  double weibull_scale = 0;      // its scale [unit of x]
  double weibull_mpm = 0;        // mean + scale ((u / scale)^beta + ln(p kMpmDuration / Tz))^(1 / beta), p the share
                                 // of peaks above u; NaN below kMinPeaks of them
};

/// Fewest cycle maxima for the Weibull fit (its shape's standard error,
/// ~0.78 beta / sqrt(n), is then below 0.2 for beta = 2).
inline constexpr long kMinPeaks = 50;

/// Share of the cycle maxima, the largest, to which the Weibull law is
/// fitted [-]: fitted to every peak, the law follows the many small cycles of
/// a broad-banded record and misplaces the largest (a 3-hour storm of
/// sea-state-tow: shape 1.23, an mpm 22 % above the largest peak seen; the
/// top third: shape 1.92, 2 % above).
inline constexpr double kWeibullTail = 1.0 / 3;

/// Maximum-likelihood Weibull law F(y) = 1 - exp(-(y / scale)^shape) of the
/// values y above `threshold` u >= 0, given that they exceed it (the law
/// conditioned on y > u: P(Y > y | Y > u) = exp((u / scale)^shape - (y /
/// scale)^shape)): the shape solves sum (y^b ln y - u^b ln u) / sum (y^b -
/// u^b) - 1/b = mean ln y (bisection on [0.05, 50] to 1e-12), scale^shape =
/// mean (y^shape - u^shape); u = 0 is the plain fit to every positive value.
/// Returns {shape, scale}; {NaN, NaN} for fewer than 2 values above u or equal ones.
std::pair<double, double> weibull_fit(const std::vector<double>& y, double threshold = 0);

/// Statistics of samples x at times t (equal length, increasing times).
SignalStats signal_stats(const std::vector<double>& t, const std::vector<double>& x);

/// One-sided spectral density estimate [unit^2 s/rad] of x sampled at the
/// uniform step dt, at the Fourier frequencies omega_k = 2 pi k / (N dt),
/// k = 1..N/2, averaged over `band` adjacent ones (resolution band * 2 pi /
/// (N dt)): S_j = 2 mean_k I(omega_k), I = dt / (2 pi N) |sum_n (x_n - mean)
/// e^{-i omega n dt}|^2. Sum_j S_j * band * 2 pi / (N dt) = variance when band
/// divides N/2 (Parseval). Returns (omega_j, S_j) at the band centres. The
/// sums by FFT (towsim/output/dft.hpp): O(N log N) for any N.
std::vector<std::pair<double, double>> spectral_density_estimate(const std::vector<double>& x, double dt, int band);

/// Share of its peak below which an input spectrum is taken as negligible
/// and spectra.csv leaves the transfer function blank: a 300 s record without
/// a window leaks ~2e-3 of the peak into bands with no wave energy, where a
/// slow drift of the output then read as gains of 3-7 [-].
inline constexpr double kTransferMask = 1e-2;

/// Collects tow tension, link force and body depth from `start` on.
class SeaStatistics {
 public:
  explicit SeaStatistics(double start = 0) : start_(start) {}
  /// Keep the sample's values when t >= start (body: the end body).
  void add(const Model& model, const Sample& s);
  /// {"from_time", "duration", "mpm_duration", "tow_tension": {...}, ...}.
  nlohmann::ordered_json json() const;
  /// One warning per signal whose maximum exceeds its Rayleigh mpm.
  std::vector<std::string> warnings() const;
  /// spectra.csv: omega, spectral densities of wave elevation, tow tension,
  /// link force and body depth, and sqrt(S_depth / S_eta) (the body heave per
  /// metre of wave, blank where S_eta < kTransferMask of its peak), then the tow
  /// point's wave heave and sqrt(S_depth / S_tow_heave) (the ship -> fish
  /// heave transfer function, blank where S_tow_heave < kTransferMask of its peak).
  /// False on I/O error.
  bool write_spectra(const std::string& path) const;

 private:
  double start_;                                                      // [s]
  std::vector<double> t_, eta_, tension_, link_, depth_, tow_heave_;  // tow_heave_: Sample::tow_wave.z [m]
};

}  // namespace towsim::output
