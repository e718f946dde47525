// Discrete Fourier transform of a real record of any length in O(N log N)
// (spectra.csv's periodogram): Eigen's FFT (kissfft) when the length has no
// prime factor above 5, else Bluestein's chirp-z transform through FFTs of a
// power-of-two length.
#pragma once

#include <complex>
#include <vector>

namespace towsim::output {

/// X_k = sum_{n<N} x_n exp(-2 pi i k n / N), k = 0..N-1 [unit of x]; empty
/// for an empty record. Round-off ~eps log2(N) times the record's norm.
std::vector<std::complex<double>> dft(const std::vector<double>& x);

/// True when n > 0 has no prime factor above 5 (Eigen's FFT is then O(n log n)).
bool has_small_factors(std::size_t n);

}  // namespace towsim::output
