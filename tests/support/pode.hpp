// Independent references for the statics and theory validation tests
// (docs/validation.md §1): the continuous cable of Pode (1951) integrated by Boost.Odeint,
// the linearised hanging chain, and small helpers. Nothing here calls the
// code under test; formulas are derived in the comments and in
// docs/validation.md.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace towsim::validation {

// ---------------------------------------------------------------------------
// Continuous cable in a uniform stream (Pode 1951), planar, in the x-z plane.
//
// The cable moves at V along +x relative to the water (towing in still water,
// or the same relative flow). Arc length s runs from the LOWER end (s = 0) up
// to the tow point (s = L); phi is the angle of the tangent t = dr/ds =
// (cos phi, sin phi) from the horizontal (t points up the cable, towards the
// tow point); n = (-sin phi, cos phi) is t turned by +90 degrees. The
// internal force F(s) = T t + N n is the force the part above s exerts on the
// part below.
//
// Loads per unit length (towsim's element loads divided by L):
//   relative velocity u = (V, 0): u.t = V cos phi, u_n = V sin phi (sin phi, -cos phi)
//   normal drag     -k |u_n| u_n = R sin^2 phi n,     R = 1/2 rho Cd D V^2
//   Pode friction   -k f |u|^2 sgn(u.e) e = -f R sgn(V cos phi) t
//                   (e = -t is towsim's element axis; sgn(u.e) e is even in e)
//   apparent weight -w z = -w (sin phi t + cos phi n)
// Equilibrium of ds: dF/ds + loads = 0, with dt/ds = phi' n, dn/ds = -phi' t:
//   T' - N phi' = f R sgn + w sin phi
//   T phi' + N' = w cos phi - R sin^2 phi
// Moment balance of ds about r(s) (no bending stiffness): t x F + mu = 0,
// i.e. N = -mu, with mu the distributed couple (2D cross a x b = a_x b_z - a_z b_x).
//  * Morison added mass (or any form without a steady moment): mu = 0, N = 0,
//    and these are Pode's equations
//      dT/ds = w sin phi + f R,     T dphi/ds = w cos phi - R sin^2 phi.
//  * Ideal-fluid added mass: the Munk moment of an element, ma (e.u)(u x e)
//    with ma = Ca rho A L, is a couple per length mu = c sin phi cos phi,
//    c = Ca rho A V^2, that does NOT vanish as the elements get shorter, so
//    the chain converges to the modified equations
//      N = -c sin phi cos phi,  phi' = (w cos phi - R sin^2 phi) / (T - c cos 2phi),
//      T' = -c sin phi cos phi phi' + f R sgn + w sin phi.
// Boundary at the lower end: F(0) = the load the end point must carry,
// F_end = -(external loads on the towed body) = (drag, apparent weight) for a
// sphere towed at V. phi_0 solves F_end . n(phi_0) = -c sin phi_0 cos phi_0,
// T_0 = F_end . t(phi_0). The tow force (vessel on cable) is F(L).
// The critical angle (phi' = 0 far from the end) is w cos phi_c = R sin^2 phi_c
// with or without f and c.
// ---------------------------------------------------------------------------
struct PodeCable {
  double length;     // L [m]
  double w;          // apparent weight per length [N/m]
  double R;          // 1/2 rho Cd D V^2 [N/m]
  double f = 0;      // Pode friction coefficient [-]
  double c = 0;      // Munk couple coefficient Ca rho A V^2 [N] (0: Morison / Pode)
  double V = 1;      // speed relative to the water [m/s] (for the smoothed sign)
  double v_s = 0;    // sign smoothing speed (towsim's sgn_s); 0 = exact sign [m/s]
  double end_x = 0;  // F_end, x component [N]
  double end_z = 0;  // F_end, z component [N]
};

/// State of the continuous cable at arc length s from the lower end.
struct PodePoint {
  double s, T, phi, x, z;  // [m], [N], [rad], position relative to the lower end [m]
  double N;                // shear, -c sin phi cos phi [N]
  double Fx() const { return T * std::cos(phi) - N * std::sin(phi); }
  double Fz() const { return T * std::sin(phi) + N * std::cos(phi); }
};

/// Critical angle: w cos phi = R sin^2 phi, phi in (0, pi/2] [rad].
inline double critical_angle(double w, double R) {
  // R c^2 + w c - R = 0 for c = cos phi.
  const double c = (-w + std::sqrt(w * w + 4 * R * R)) / (2 * R);
  return std::acos(c);
}

/// Integrate the continuous cable from the lower end to the tow point with
/// Dormand-Prince 5(4) (dense output) at absolute and relative tolerance
/// `tol`, returning the state at each arc length in `s_out` (increasing,
/// within [0, L]).
inline std::vector<PodePoint> integrate_pode(const PodeCable& p, const std::vector<double>& s_out, double tol = 1e-13) {
  namespace ode = boost::numeric::odeint;
  using State = std::array<double, 4>;  // T, phi, x, z
  auto sgn = [&](double x) { return p.v_s > 0 ? x / std::sqrt(x * x + p.v_s * p.v_s) : (x > 0) - (x < 0); };
  auto rhs = [&](const State& y, State& dy, double) {
    const double T = y[0], ph = y[1], sp = std::sin(ph), cp = std::cos(ph);
    const double dphi = (p.w * cp - p.R * sp * sp) / (T - p.c * std::cos(2 * ph));
    dy[0] = -p.c * sp * cp * dphi + p.f * p.R * sgn(p.V * cp) + p.w * sp;
    dy[1] = dphi;
    dy[2] = cp;
    dy[3] = sp;
  };
  // Lower-end angle: g(phi) = F_end . n(phi) + c sin phi cos phi = 0 (Newton
  // from the Morison value atan2(Fz, Fx)).
  double ph = std::atan2(p.end_z, p.end_x);
  for (int it = 0; it < 100 && p.c != 0; ++it) {
    const double g = -p.end_x * std::sin(ph) + p.end_z * std::cos(ph) + 0.5 * p.c * std::sin(2 * ph);
    const double dg = -p.end_x * std::cos(ph) - p.end_z * std::sin(ph) + p.c * std::cos(2 * ph);
    const double d = g / dg;
    ph -= d;
    if (std::abs(d) < 1e-16) break;
  }
  State y{p.end_x * std::cos(ph) + p.end_z * std::sin(ph), ph, 0.0, 0.0};
  std::vector<PodePoint> out;
  auto record = [&](const State& x, double s) {
    out.push_back({s, x[0], x[1], x[2], x[3], -p.c * std::sin(x[1]) * std::cos(x[1])});
  };
  std::vector<double> times = s_out;
  if (times.empty() || times.front() > 0) times.insert(times.begin(), 0.0);
  auto stepper = ode::make_dense_output(tol, tol, ode::runge_kutta_dopri5<State>());
  ode::integrate_times(stepper, rhs, y, times.begin(), times.end(), 1e-3 * p.length / 1000,
                       [&](const State& x, double s) { record(x, s); });
  if (s_out.empty() || s_out.front() > 0) out.erase(out.begin());
  return out;
}

// ---------------------------------------------------------------------------
// Linearised chain of n equal links hanging from a fixed point (vacuum).
//
// Link k = 1..n (1 at the top), length l, mass m, inertia m l^2/12 about its
// centre, small angle th_k from the vertical. Centre abscissa
//   x_Gk = l sum_{j<k} th_j + (l/2) th_k = l sum_j a_kj th_j,
//   a_kj = 1 (j < k), 1/2 (j = k), 0 (j > k);
// vertical velocities are second order. Kinetic energy
//   T = 1/2 sum_k [ m xdot_Gk^2 + (m l^2/12) thdot_k^2 ]  ->  M = m l^2 (A^T A + I/12).
// Potential: z_Gk = -l sum_{j<k} cos th_j - (l/2) cos th_k, so to second order
//   V = const + m g l sum_j th_j^2/2 [ (n - j) + 1/2 ]  ->  K = m g l diag(n - j + 1/2).
// Frequencies: K v = w^2 M v (ascending).
// ---------------------------------------------------------------------------
struct ChainModes {
  Eigen::VectorXd omega;   // angular frequencies, ascending [rad/s]
  Eigen::MatrixXd shapes;  // column k: link angles of mode k (M-normalised)
};

inline ChainModes hanging_chain_modes(int n, double link_length, double link_mass, double g) {
  const double l = link_length, m = link_mass;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < k; ++j) A(k, j) = 1.0;
    A(k, k) = 0.5;
  }
  const Eigen::MatrixXd M = m * l * l * (A.transpose() * A + Eigen::MatrixXd::Identity(n, n) / 12.0);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int j = 1; j <= n; ++j) K(j - 1, j - 1) = m * g * l * (n - j + 0.5);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  return {eig.eigenvalues().cwiseSqrt(), eig.eigenvectors()};
}

/// First zeros of the Bessel function J0 (Abramowitz & Stegun, table 9.5).
inline constexpr double kBesselJ0Zeros[] = {2.404825557695773, 5.520078110286311, 8.653727912911012, 11.79153443901428,
                                            14.93091770848779};

/// Continuous hanging chain (uniform, inextensible, top fixed): the small
/// lateral motion y(x, t) with tension T = m' g x (x measured up from the free
/// end) obeys m' y_tt = (m' g x y_x)_x; with y = Y(x) cos(wt), xi = 2 w sqrt(x/g)
/// turns it into Bessel's equation of order 0, so Y = J0(2 w sqrt(x / g))
/// (bounded at the free end) and Y(L) = 0 gives w_k = (j_{0,k} / 2) sqrt(g / L).
inline double continuous_chain_omega(int k, double total_length, double g) {
  return 0.5 * kBesselJ0Zeros[k - 1] * std::sqrt(g / total_length);
}

// ---------------------------------------------------------------------------
// Helpers.
// ---------------------------------------------------------------------------

/// Observed order of convergence between two successive errors at h and h/2.
inline double observed_order(double e_coarse, double e_fine) { return std::log2(e_coarse / e_fine); }

/// Zero crossings of a sampled signal x(t), located on the cubic Hermite
/// interpolant of (x, dx/dt) between samples (error O(dt^4)), by bisection.
inline std::vector<double> hermite_zero_crossings(const std::vector<double>& t, const std::vector<double>& x,
                                                  const std::vector<double>& xd) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (!((x[i] < 0 && x[i + 1] >= 0) || (x[i] > 0 && x[i + 1] <= 0))) continue;
    const double h = t[i + 1] - t[i];
    auto H = [&](double s) {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * x[i] + (s3 - 2 * s2 + s) * h * xd[i] + (-2 * s3 + 3 * s2) * x[i + 1] +
             (s3 - s2) * h * xd[i + 1];
    };
    double a = 0, b = 1;
    const bool neg_a = H(a) < 0;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (a + b);
      ((H(mid) < 0) == neg_a ? a : b) = mid;
    }
    out.push_back(t[i] + 0.5 * (a + b) * h);
  }
  return out;
}

/// Where the validation tests write data for docs/figures (scripts/validation_figures.sh
/// sets TOWSIM_VALIDATION_DATA); nothing is written when unset.
inline std::optional<std::ofstream> data_file(const std::string& name) {
  const char* dir = std::getenv("TOWSIM_VALIDATION_DATA");
  if (!dir || !*dir) return std::nullopt;
  std::filesystem::create_directories(dir);
  std::ofstream f(std::filesystem::path(dir) / name);
  f.precision(12);
  return f;
}

}  // namespace towsim::validation
