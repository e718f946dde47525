// The discrete Fourier transform of spectra.csv (towsim::output::dft) and the
// spectral estimate built on it, against the direct sum: twiddles from the
// exact k n mod N, summed in long double (its own error ~1e-19 relative, far
// below the tolerances), on random records of lengths that take each path
// (2, 3 and 5 only: Eigen's FFT; a prime or a factor 109: Bluestein).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "towsim/output/dft.hpp"
#include "towsim/output/sea_statistics.hpp"

namespace {

using Cl = std::complex<long double>;

/// X_k = sum_n x_n e^{-2 pi i k n / N} directly, k n reduced mod N into a table of the N twiddles.
std::vector<Cl> direct_dft(const std::vector<double>& x) {
  const std::size_t N = x.size();
  const long double pi = 3.141592653589793238462643383279502884L;
  std::vector<Cl> tw(N), X(N);
  for (std::size_t m = 0; m < N; ++m) {
    const long double ang = -2 * pi * static_cast<long double>(m) / static_cast<long double>(N);
    tw[m] = Cl(std::cos(ang), std::sin(ang));
  }
  for (std::size_t k = 0; k < N; ++k)
    for (std::size_t n = 0; n < N; ++n) X[k] += static_cast<long double>(x[n]) * tw[(k * n) % N];
  return X;
}

/// n uniform values in [offset - 1/2, offset + 1/2).
std::vector<double> random_record(std::size_t n, std::uint64_t seed, double offset = 0) {
  std::mt19937_64 g(seed);
  std::vector<double> x(n);
  for (double& v : x) v = offset + static_cast<double>(g() >> 11) * 0x1.0p-53 - 0.5;
  return x;
}

// Every bin within kDftTol sqrt(N) |x|_2 (= kDftTol |X|_2, Parseval) of the
// direct sum. An FFT's round-off is ~eps log2(length) |X|_2; Bluestein adds
// two more FFTs of M >= 2N - 1 points and the chirp products, so
// ~3 eps log2(M) = 3 * 2.2e-16 * 13 = 9e-15 here: kDftTol = 5e-14 leaves a
// factor 5 (measured: printed).
constexpr double kDftTol = 5e-14;

TEST(Dft, EqualsTheDirectSumForEveryKindOfLength) {
  for (std::size_t N : {1u, 2u, 7u, 360u, 1000u, 997u, 2180u, 4096u}) {
    const auto x = random_record(N, N);
    const auto X = towsim::output::dft(x);
    const auto R = direct_dft(x);
    ASSERT_EQ(X.size(), N);
    double norm = 0, err = 0;
    for (double v : x) norm += v * v;
    norm = std::sqrt(norm * static_cast<double>(N));
    for (std::size_t k = 0; k < N; ++k)
      err = std::max(err, std::abs(X[k] - std::complex<double>(static_cast<double>(R[k].real()),
                                                               static_cast<double>(R[k].imag()))));
    std::printf("[measured] N = %zu (%s): max |X - X_direct| / |X|_2 = %.2e\n", N,
                towsim::output::has_small_factors(N) ? "FFT" : "Bluestein", err / norm);
    EXPECT_LE(err, kDftTol * norm) << "N = " << N;
  }
  EXPECT_TRUE(towsim::output::dft({}).empty());
  EXPECT_TRUE(towsim::output::has_small_factors(54000));
  EXPECT_FALSE(towsim::output::has_small_factors(54500));  // 2^2 5^3 109
}

// spectral_density_estimate against its definition summed directly: S_j =
// 2 mean_k I(omega_k), I = dt / (2 pi N) |X_k|^2 over each band of 5 bins.
// A bin's |X_k|^2 moves by at most 2 |X_k| kDftTol |X|_2 and |X|_2 <=
// sqrt(N) max |X_k|, so relative to the largest bin by 2 kDftTol sqrt(N) =
// 4.7e-12 at N = 2180: kEstimateTol = 1e-11 of the largest band (measured:
// printed).
constexpr double kEstimateTol = 1e-11;

TEST(Dft, SpectralEstimateEqualsTheDirectEstimate) {
  const double dt = 0.5;
  for (std::size_t N : {1000u, 997u, 2180u}) {
    const auto x = random_record(N, 10 + N, 3.0);  // a mean to remove
    double mean = 0;
    for (double v : x) mean += v / static_cast<double>(N);
    std::vector<double> d(N);
    for (std::size_t n = 0; n < N; ++n) d[n] = x[n] - mean;
    const auto R = direct_dft(d);
    const int band = 5;
    const auto S = towsim::output::spectral_density_estimate(x, dt, band);
    const double dw = 2 * std::numbers::pi / (static_cast<double>(N) * dt);
    ASSERT_EQ(S.size(), N / 2 / band);
    double peak = 0, err = 0;
    for (std::size_t j = 0; j < S.size(); ++j) {
      long double sum = 0;
      for (std::size_t k = 1 + band * j; k < 1 + band * (j + 1); ++k)
        sum += (2 * k == N ? 1 : 2) * dt / (2 * std::numbers::pi * N) * std::norm(R[k]);
      const double ref = static_cast<double>(sum / band);
      EXPECT_DOUBLE_EQ(S[j].first, dw * (1 + band * j + 0.5 * (band - 1))) << "band centre, j = " << j;
      peak = std::max(peak, ref), err = std::max(err, std::abs(S[j].second - ref));
    }
    std::printf("[measured] N = %zu: max |S - S_direct| / max S = %.2e\n", N, err / peak);
    EXPECT_LE(err, kEstimateTol * peak) << "N = " << N;
  }
}

}  // namespace
