// Piecewise-linear tables (current profiles, force and deflection histories).
#pragma once

#include <algorithm>
#include <vector>

namespace towsim {

/// Linear interpolation of ys over increasing xs at x, held constant beyond
/// the ends; one row is a constant. ys must not be empty. A NaN x (a
/// rejected trial state) gives the first row, never a read past the table.
template <class T>
T interpolate(const std::vector<double>& xs, const std::vector<T>& ys, double x) {
  if (ys.size() == 1 || !(x > xs.front())) return ys.front();
  if (x >= xs.back()) return ys.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) - 1;
  const double s = (x - xs[i]) / (xs[i + 1] - xs[i]);
  return (1 - s) * ys[i] + s * ys[i + 1];
}

}  // namespace towsim
