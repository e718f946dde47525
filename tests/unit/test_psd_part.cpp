// psd_part (the symmetric part of a damping or a stiffness with its negative
// eigenvalues dropped, for the Rosenbrock-W stage matrix, docs/theory.md
// §6.3): the 3x3 case uses Eigen's closed-form eigen-decomposition
// (SelfAdjointEigenSolver::computeDirect), checked here against the iterative
// solver (QR iteration, SelfAdjointEigenSolver::compute) and against the
// exact PSD part of matrices built from their eigen-decomposition, on random
// symmetric matrices of scales 1e-6 to 1e6 with well-separated, nearly
// repeated (relative gaps 1e-16 to 1e-4), repeated and nearly zero eigenvalues.
//
// Tolerance kDirect = 4 sqrt(eps) ~ 6e-8 relative to |S|_F: the closed form
// takes the roots of the characteristic cubic, and a root near a double root
// moves by ~sqrt(eps) |S| under a rounding of the coefficients (Eigen's
// documentation states a worst case of 1e-8 relative on the eigenvalues for
// double). The map S -> S+ is 1-Lipschitz in the Frobenius norm (a projection
// onto a convex cone), so the eigenvalue error carries over to the PSD part
// with no gain. Measured worst: 1.07e-8 over these 20000 matrices, 1.15e-8
// over 2e5 (nearly repeated pairs); well-separated eigenvalues stay near 1e-12. Such an error only
// shapes W, which the W-method may take approximate (its order does not
// depend on W).
//
// kRound = 16 eps relative to |S|_F: what the product V diag(l+) V^T itself
// rounds (the result's asymmetry and its most negative eigenvalue; the result
// is a sum of rank-one PSD terms l+_i v_i v_i^T, PSD in exact arithmetic
// whatever the accuracy of V). The iterative solver meets it against the
// exact PSD part too (backward stable: measured 3e-15).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "towsim/dynamics/implicit.hpp"

namespace towsim {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
const double kDirect = 4 * std::sqrt(kEps);  // closed form vs exact [relative to |S|_F]
constexpr double kRound = 16 * kEps;         // rounding of the reconstruction [relative to |S|_F]

/// The PSD part by the iterative solver (the reference).
Mat3 psd_iterative(const Mat3& A) {
  const Mat3 S = 0.5 * (A + A.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat3> es(S);
  const Vec3 l = es.eigenvalues().cwiseMax(0.0);
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}

/// A random symmetric matrix of scale `scale` with eigenvalues of the given
/// kind (0: independent, 1: a nearly repeated pair, 2: a nearly repeated
/// triple, 3: one nearly zero, 4: an exactly repeated pair), and its exact PSD part.
struct Case {
  Mat3 S, exact;
};
Case random_case(std::mt19937& rng, int kind) {
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Mat3 Q = Quat(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix();
  Vec3 l(N(rng), N(rng), N(rng));
  const double gap = std::pow(10.0, -16 + 12 * U(rng));  // relative, 1e-16 to 1e-4
  if (kind == 1) l(1) = l(0) * (1 + gap);
  if (kind == 2) l(1) = l(0) * (1 + gap), l(2) = l(0) * (1 - gap);
  if (kind == 3) l(0) *= gap;
  if (kind == 4) l(1) = l(0);
  const double scale = std::pow(10.0, -6 + 12 * U(rng));  // 1e-6 to 1e6
  Mat3 S = scale * Q * l.asDiagonal() * Q.transpose();
  S = (0.5 * (S + S.transpose())).eval();
  const Vec3 lp = l.cwiseMax(0.0);
  return {S, scale * Q * lp.asDiagonal() * Q.transpose()};
}

TEST(PsdPart, ClosedFormMatchesTheIterativeSolverAndIsPsd) {
  std::mt19937 rng(2026);
  double worst_iter = 0, worst_exact = 0, worst_asym = 0, worst_neg = 0;
  for (int i = 0; i < 20000; ++i) {
    const Case c = random_case(rng, i % 5);
    const double n = c.S.norm();
    const Mat3 P = psd_part(c.S);
    const Mat3 R = psd_iterative(c.S);
    ASSERT_LE((R - c.exact).norm(), kRound * n) << "the reference itself";
    worst_iter = std::max(worst_iter, (P - R).norm() / n);
    worst_exact = std::max(worst_exact, (P - c.exact).norm() / n);
    worst_asym = std::max(worst_asym, (P - P.transpose()).norm() / n);
    const Eigen::SelfAdjointEigenSolver<Mat3> es(0.5 * (P + P.transpose()), Eigen::EigenvaluesOnly);
    worst_neg = std::max(worst_neg, -es.eigenvalues()(0) / n);
  }
  std::cout << "[measured] psd_part 3x3 closed form, 20000 matrices: |P - P_iterative| / |S| <= " << worst_iter
            << ", |P - P_exact| / |S| <= " << worst_exact << ", asymmetry " << worst_asym
            << ", most negative eigenvalue " << -worst_neg << " |S|\n";
  EXPECT_LE(worst_iter, kDirect);
  EXPECT_LE(worst_exact, kDirect);
  EXPECT_LE(worst_asym, kRound);
  EXPECT_LE(worst_neg, kRound);
}

// Continuous: along a path on which two eigenvalues cross each other and
// zero, the PSD part moves no more than the matrix (1-Lipschitz) plus twice
// the closed form's error.
TEST(PsdPart, ContinuousThroughCrossingEigenvalues) {
  const Mat3 Q = Quat(0.3, -0.5, 0.7, 0.2).normalized().toRotationMatrix();
  const Mat3 E = Q * Vec3(1, -1, 0.5).asDiagonal() * Q.transpose();  // direction of the path
  const Mat3 S0 = Q * Vec3(0, 0, 2).asDiagonal() * Q.transpose();    // l = (t, -t, 2 + t/2)
  const int steps = 20001;
  const double dt = 2e-4;
  Mat3 prev = psd_part(Mat3(S0 - 2.0 * E));
  double worst = 0;
  for (int i = 1; i < steps; ++i) {
    const Mat3 S = S0 + (-2.0 + i * dt) * E;
    const Mat3 P = psd_part(S);
    const double allowed = dt * E.norm() + 2 * kDirect * S.norm();
    worst = std::max(worst, (P - prev).norm() / allowed);
    prev = P;
  }
  std::cout << "[measured] psd_part along the path: largest move / allowed " << worst << "\n";
  EXPECT_LE(worst, 1.0);
}

}  // namespace
}  // namespace towsim
