#include "towsim/output/dft.hpp"

#include <cstdint>
#include <numbers>

#include <unsupported/Eigen/FFT>

namespace towsim::output {

bool has_small_factors(std::size_t n) {
  if (n == 0) return false;
  for (std::size_t p : {2u, 3u, 5u})
    while (n % p == 0) n /= p;
  return n == 1;
}

std::vector<std::complex<double>> dft(const std::vector<double>& x) {
  using C = std::complex<double>;
  const std::size_t N = x.size();
  std::vector<C> out;
  if (N <= 1) return std::vector<C>(x.begin(), x.end());  // X_0 = x_0 (kissfft needs N >= 2)
  Eigen::FFT<double> fft;
  // Lengths of 2, 3 and 5 only: kissfft's own butterflies.
  if (has_small_factors(N)) {
    const std::vector<C> in(x.begin(), x.end());
    fft.fwd(out, in);
    return out;
  }
  // Bluestein: kn = (k^2 + n^2 - (k-n)^2) / 2, so X_k = w_k sum_n (x_n w_n) conj(w_{k-n}),
  // w_m = exp(-i pi m^2 / N): a convolution, done circularly in M >= 2N - 1 points.
  std::size_t M = 1;
  while (M < 2 * N - 1) M *= 2;
  // The chirp's phase from m^2 mod 2N in integers: exact for any N below 2^31.
  std::vector<C> w(N);
  for (std::size_t m = 0; m < N; ++m) {
    const std::uint64_t q = (static_cast<std::uint64_t>(m) * m) % (2 * static_cast<std::uint64_t>(N));
    w[m] = std::polar(1.0, -std::numbers::pi * static_cast<double>(q) / static_cast<double>(N));
  }
  std::vector<C> a(M, C(0)), b(M, C(0)), fa, fb;
  for (std::size_t n = 0; n < N; ++n) a[n] = x[n] * w[n];
  b[0] = 1;
  for (std::size_t m = 1; m < N; ++m) b[m] = b[M - m] = std::conj(w[m]);
  fft.fwd(fa, a);
  fft.fwd(fb, b);
  for (std::size_t j = 0; j < M; ++j) fa[j] *= fb[j];
  fft.inv(a, fa);  // scaled by 1/M
  out.resize(N);
  for (std::size_t k = 0; k < N; ++k) out[k] = w[k] * a[k];
  return out;
}

}  // namespace towsim::output
