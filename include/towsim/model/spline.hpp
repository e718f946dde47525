// Natural cubic spline through samples of a vector-valued signal: the one
// interpolation used by the tow track (Vec3) and the measured ship motion (Vec6).
#pragma once

#include <cstddef>
#include <vector>

namespace towsim {

/// Second derivatives M_i of the natural cubic spline through (ts[i], xs[i])
/// (ts increasing; M_0 = M_last = 0), by the Thomas algorithm on the
/// tridiagonal continuity equations. V is any fixed-size Eigen vector;
/// M has the units of xs per s^2 (per unit of ts squared).
template <class V>
std::vector<V> natural_spline_curvatures(const std::vector<double>& ts, const std::vector<V>& xs) {
  const std::size_t m = ts.size();
  std::vector<V> M(m, V::Zero());
  if (m <= 2) return M;
  // Forward sweep: eliminate the sub-diagonal.
  std::vector<double> c(m, 0.0);
  std::vector<V> d(m, V::Zero());
  for (std::size_t i = 1; i + 1 < m; ++i) {
    const double h0 = ts[i] - ts[i - 1], h1 = ts[i + 1] - ts[i];
    const V rhs = 6 * ((xs[i + 1] - xs[i]) / h1 - (xs[i] - xs[i - 1]) / h0);
    const double diag = 2 * (h0 + h1) - h0 * c[i - 1];
    c[i] = h1 / diag;
    d[i] = (rhs - h0 * d[i - 1]) / diag;
  }
  // Back substitution.
  for (std::size_t i = m - 2; i >= 1; --i) M[i] = d[i] - c[i] * M[i + 1];
  return M;
}

}  // namespace towsim
