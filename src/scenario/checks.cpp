#include "checks.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace towsim::scenario {
namespace {

void report(const Where& w, Diagnostics& d, const std::string& msg) { d.error(w.loc, w.path, msg); }

std::string list3(const Vec3& v) { return fmt_num(v[0]) + ", " + fmt_num(v[1]) + ", " + fmt_num(v[2]); }

/// Largest asymmetry |A(i,j) - A(j,i)| relative to the largest term; reports it.
template <class M>
bool check_symmetric(const Field<M>& f, Diagnostics& d) {
  const M& a = f.value;
  const double scale = std::max(a.cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < a.rows(); ++i)
    for (int j = i + 1; j < a.cols(); ++j)
      if (std::abs(a(i, j) - a(j, i)) > 1e-9 * scale) {
        report(f.where, d,
               "must be symmetric (got " + fmt_num(a(i, j)) + " at row " + std::to_string(i) + ", column " +
                   std::to_string(j) + " but " + fmt_num(a(j, i)) + " at row " + std::to_string(j) + ", column " +
                   std::to_string(i) + ")");
        return false;
      }
  return true;
}

}  // namespace

void check_positive(const Field<double>& f, Diagnostics& d) {
  if (f.given && !(f.value > 0)) report(f.where, d, "must be > 0 (got " + fmt_num(f.value) + ")");
}

void check_non_negative(const Field<double>& f, Diagnostics& d) {
  if (f.given && !(f.value >= 0)) report(f.where, d, "must be >= 0 (got " + fmt_num(f.value) + ")");
}

void check_at_least(const Field<long long>& f, long long minimum, Diagnostics& d) {
  if (f.given && f.value < minimum)
    report(f.where, d, "must be >= " + std::to_string(minimum) + " (got " + std::to_string(f.value) + ")");
}

void check_at_most(const Field<long long>& f, long long maximum, Diagnostics& d) {
  if (f.given && f.value > maximum)
    report(f.where, d, "must be <= " + std::to_string(maximum) + " (got " + std::to_string(f.value) + ")");
}

void check_nonzero(const Field<Vec3>& f, Diagnostics& d) {
  if (!f.given) return;
  const double n = f.value.norm();
  if (!(n > 0))
    report(f.where, d, "must be a non-zero vector (got [" + list3(f.value) + "])");
  else if (!std::isfinite(n))
    report(f.where, d, "is too large to normalise (got [" + list3(f.value) + "])");
}

void check_increasing(const std::vector<RowSpec>& rows, const std::string& what, Diagnostics& d) {
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double prev = rows[i - 1].values[0];
    const double cur = rows[i].values[0];
    if (!(cur > prev))
      report(rows[i].where, d,
             what + " must be strictly increasing (got " + fmt_num(cur) + " after " + fmt_num(prev) + ")");
  }
}

void check_inertia(const Field<Mat3>& f, Diagnostics& d) {
  if (!f.given || !check_symmetric(f, d)) return;
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(f.value);
  const Vec3 m = eig.eigenvalues();  // ascending
  if (!(m[0] > 0)) {
    report(f.where, d, "must be positive definite (principal moments " + list3(m) + ")");
    return;
  }
  if (m[2] > (m[0] + m[1]) * (1 + 1e-9))
    report(f.where, d,
           "principal moments must satisfy the triangle inequality (got " + list3(m) + ": " + fmt_num(m[2]) + " > " +
               fmt_num(m[0]) + " + " + fmt_num(m[1]) + ")");
}

void check_psd6(const Field<Mat6>& f, Diagnostics& d) {
  if (!f.given || !check_symmetric(f, d)) return;
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(f.value);
  const double scale = std::max(f.value.cwiseAbs().maxCoeff(), 1e-300);
  const double lo = eig.eigenvalues()[0];
  if (lo < -1e-9 * scale)
    report(f.where, d, "must be positive semi-definite (smallest eigenvalue " + fmt_num(lo) + ")");
}

void check_diagonal_non_negative(const Field<Mat6>& f, Diagnostics& d) {
  if (!f.given) return;
  for (int i = 0; i < 6; ++i)
    if (f.value(i, i) < 0) {
      report(f.where, d,
             "diagonal terms must be >= 0 (got " + fmt_num(f.value(i, i)) + " at row " + std::to_string(i) + ")");
      return;
    }
}

}  // namespace towsim::scenario
