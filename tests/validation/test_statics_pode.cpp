// Steady tow of a chain of n rigid elements (solve_statics) against the
// continuous cable theory of Pode (1951), integrated independently with
// Boost.Odeint (tests/support/pode.hpp; derivation there and in
// docs/validation.md section 1).
#include <gtest/gtest.h>

#include <iomanip>
#include <iostream>
#include <sstream>

#include "../support/models.hpp"
#include "../support/pode.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {
namespace {

using testing::CableSpec;
using validation::PodeCable;
using validation::PodePoint;

constexpr double kPi = std::numbers::pi;
const std::vector<int> kElementCounts = {5, 10, 20, 40, 80, 160};

/// One towed-cable configuration: cable, sphere at the end, speed.
struct PodeCase {
  std::string name;
  double length, mass_per_length, diameter, cd, f;
  double body_mass, body_radius, body_cd;  // body_mass 0: no body
  double V;
  AddedMassModel am;
};
void PrintTo(const PodeCase& c, std::ostream* os) { *os << c.name; }

Model chain_model(const PodeCase& c, int n) {
  CableSpec spec;
  spec.n = n;
  spec.length = c.length;
  spec.mass_per_length = c.mass_per_length;
  spec.diameter = c.diameter;
  spec.cd = c.cd;
  spec.tangential = c.f;
  spec.law = TangentialLaw::Pode;
  spec.ca = 1.0;
  spec.am = c.am;
  Model m = testing::cable_model(spec);
  if (c.body_mass > 0) testing::add_sphere_body(m, c.body_mass, c.body_radius, c.body_cd, 0.5);
  return m;
}

/// The continuous theory for the same cable: loads per length written from
/// docs/theory.md §3 (not read from the compiled model).
PodeCable theory_of(const PodeCase& c, bool with_munk, double rho = 1025, double g = 9.81) {
  const double A = kPi * c.diameter * c.diameter / 4;
  PodeCable p;
  p.length = c.length;
  p.w = (c.mass_per_length - rho * A) * g;
  p.R = 0.5 * rho * c.cd * c.diameter * c.V * c.V;
  p.f = c.f;
  p.c = with_munk ? 1.0 * rho * A * c.V * c.V : 0.0;  // Ca = 1
  p.V = c.V;
  p.v_s = 1e-3;  // towsim's default sign smoothing speed (exactness; irrelevant here)
  if (c.body_mass > 0) {
    const double r = c.body_radius;
    p.end_x = 0.5 * rho * c.body_cd * kPi * r * r * c.V * c.V;        // sphere drag
    p.end_z = (c.body_mass - rho * 4.0 / 3.0 * kPi * r * r * r) * g;  // apparent weight
  }
  return p;
}

/// The four compared quantities of a chain or of the theory.
struct TowQuantities {
  double tension;  // |F_R| [N]
  double angle;    // tow angle atan2(F_Rz, F_Rx) from the horizontal [rad]
  double depth;    // depth of the lower end below the tow point [m]
  double offset;   // horizontal distance of the lower end behind the tow point [m]
};

TowQuantities chain_quantities(const Model& m, const StaticsResult& r) {
  Vec3 P = r.state.r0;
  for (int k = 0; k < m.cable.n(); ++k) P += m.cable.elements[k].length * r.state.e[k];
  const Vec3 d = P - r.state.r0;
  return {r.tow_force.norm(), std::atan2(r.tow_force.z(), r.tow_force.x()), -d.z(), -d.x()};
}

TowQuantities theory_quantities(const PodeCable& p) {
  const PodePoint top = validation::integrate_pode(p, {p.length}).back();
  return {std::hypot(top.Fx(), top.Fz()), std::atan2(top.Fz(), top.Fx()), top.z, top.x};
}

/// Errors of a chain against the theory: tension, depth and offset relative
/// to the theory's value, angle absolute [rad].
std::array<double, 4> errors(const TowQuantities& a, const TowQuantities& th) {
  return {std::abs(a.tension - th.tension) / th.tension, std::abs(a.angle - th.angle),
          std::abs(a.depth - th.depth) / th.depth, std::abs(a.offset - th.offset) / th.offset};
}

class StaticsPode : public ::testing::TestWithParam<PodeCase> {};

// ---------------------------------------------------------------------------
// The chain converges to the continuous cable, at second order in 1/n.
// Morison added mass is compared with Pode's equations; the ideal-fluid form
// (Munk moment) with Pode's equations plus the distributed Munk couple, and
// shown NOT to converge to plain Pode.
// ---------------------------------------------------------------------------
TEST_P(StaticsPode, ChainConvergesToContinuousCable) {
  const PodeCase c = GetParam();
  const bool ideal = c.am == AddedMassModel::IdealFluid;
  const PodeCable theory = theory_of(c, ideal);
  const TowQuantities th = theory_quantities(theory);
  const TowQuantities th_plain = theory_quantities(theory_of(c, false));
  // The reference is converged: halving the ODE tolerance changes nothing
  // visible at the chain errors' scale (they reach ~1e-6 at n = 160).
  {
    const PodePoint a = validation::integrate_pode(theory, {theory.length}, 1e-13).back();
    const PodePoint b = validation::integrate_pode(theory, {theory.length}, 1e-10).back();
    EXPECT_LT(std::abs(a.T - b.T) / a.T, 1e-9);
    EXPECT_LT(std::abs(a.z - b.z) / a.z, 1e-9);
  }

  std::vector<std::array<double, 4>> err, err_plain;
  std::ostringstream table;
  table << std::setprecision(4);
  table << "[measured] Pode " << c.name << " (" << (ideal ? "ideal fluid vs Pode+Munk" : "Morison vs Pode")
        << "): theory T=" << th.tension << " N, angle=" << th.angle * 180 / kPi << " deg, depth=" << th.depth
        << " m, offset=" << th.offset << " m\n";
  table << "   n   err_T        p     err_angle    p     err_depth    p     err_offset   p";
  if (ideal) table << "     | vs plain Pode: err_T  err_angle  err_depth  err_offset";
  table << "\n";
  auto out = validation::data_file("validation_pode_" + c.name + ".dat");
  if (out)
    *out << "# n err_tension err_angle_rad err_depth err_offset (relative; angle absolute), then the same against"
            " plain Pode (no Munk couple)\n";
  for (std::size_t i = 0; i < kElementCounts.size(); ++i) {
    const int n = kElementCounts[i];
    const Model m = chain_model(c, n);
    const StaticsResult r = solve_statics(m, Vec3(c.V, 0, 0));
    ASSERT_TRUE(r.converged) << "n=" << n << ": " << r.message;
    const TowQuantities q = chain_quantities(m, r);
    err.push_back(errors(q, th));
    err_plain.push_back(errors(q, th_plain));
    table << std::setw(4) << n;
    for (int j = 0; j < 4; ++j) {
      table << "   " << std::scientific << std::setprecision(3) << err[i][j] << std::fixed << std::setprecision(2);
      if (i > 0) {
        table << "  " << std::setw(4) << validation::observed_order(err[i - 1][j], err[i][j]);
      } else {
        table << "      ";
      }
    }
    if (ideal) {
      table << "     |" << std::scientific << std::setprecision(2);
      for (int j = 0; j < 4; ++j) table << "  " << err_plain[i][j];
      table << std::fixed;
    }
    table << "\n";
    if (out) {
      *out << n;
      for (int j = 0; j < 4; ++j) *out << " " << err[i][j];
      for (int j = 0; j < 4; ++j) *out << " " << err_plain[i][j];
      *out << "\n";
    }
  }
  std::cout << table.str();

  for (int j = 0; j < 4; ++j) {
    // Monotone convergence from n = 20 on (at n = 5-10 the 300 m cable's
    // errors are still pre-asymptotic, and its tow angle's error is tiny by
    // accident), and the observed order of the last doubling within 2 +- 0.05
    // (measured 1.97-2.00), the one before at least 1.7 (measured >= 1.87):
    // the chain is a second-order (midpoint-like) discretisation of the
    // continuous equations, loads being applied at each element's centre.
    for (std::size_t i = 3; i < err.size(); ++i) EXPECT_LT(err[i][j], err[i - 1][j]) << "quantity " << j;
    const std::size_t last = err.size() - 1;
    EXPECT_NEAR(validation::observed_order(err[last - 1][j], err[last][j]), 2.0, 0.05) << "quantity " << j;
    EXPECT_GT(validation::observed_order(err[last - 2][j], err[last - 1][j]), 1.7) << "quantity " << j;
    // At n = 160 the chain is within 3e-4 of the theory (relative, or rad;
    // measured at most 1.7e-4, the 300 m cable's tension).
    EXPECT_LT(err.back()[j], 3e-4) << "quantity " << j;
  }
  if (ideal) {
    // The Munk couple is an O(1) distributed moment, not a discretisation
    // error. It shows most in the tow angle: against plain Pode the
    // ideal-fluid chain's tow angle stops converging (falls by less than 1.5x
    // over the last doubling, where second order gives 4x), at more than 10x
    // its distance to the modified theory (measured 35x and 670x).
    const std::size_t last = err.size() - 1;
    EXPECT_GT(err_plain[last][1], err_plain[last - 1][1] / 1.5);
    EXPECT_GT(err_plain[last][1], 10 * err[last][1]);
  }
}

std::vector<PodeCase> pode_cases() {
  // A: the paper 5.1 cable (1.5 kg/m, D 19 mm, Cd 1.8), 100 m, towing a
  //    heavy sphere (50 kg, r 0.15 m) at 1 m/s: strongly curved, phi from
  //    ~87 deg at the sphere towards phi_c ~ 49 deg.
  // B: the same with Pode friction f = 0.03.
  // C: the paper 5.2 cable (0.14 kg/m, D 10 mm, Cd 1.9), 300 m, paper 5.2
  //    sphere (3 kg, r 0.05 m), at 0.5 m/s: the bend at the sphere has the
  //    length T0/R ~ 10 m, resolved from n ~ 40 on (at the paper's 1.57 m/s
  //    it is ~1 m: see StaticsPodeResolution).
  std::vector<PodeCase> out;
  for (AddedMassModel am : {AddedMassModel::Morison, AddedMassModel::IdealFluid}) {
    const std::string s = am == AddedMassModel::Morison ? "_morison" : "_ideal";
    out.push_back({"heavy_sphere" + s, 100, 1.5, 0.019, 1.8, 0.0, 50, 0.15, 0.5, 1.0, am});
    out.push_back({"heavy_sphere_f003" + s, 100, 1.5, 0.019, 1.8, 0.03, 50, 0.15, 0.5, 1.0, am});
    out.push_back({"paper52_v05" + s, 300, 0.14, 0.010, 1.9, 0.0, 3, 0.05, 0.5, 0.5, am});
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(StaticsChain, StaticsPode, ::testing::ValuesIn(pode_cases()),
                         [](const auto& info) { return info.param.name; });

// ---------------------------------------------------------------------------
// Resolution: the paper 5.2 cable and sphere at the paper's 1.57 m/s. Near
// the sphere the cable turns from phi_0 ~ 78 deg to phi_c ~ 8.9 deg over
// the bend length T0/R ~ 1 m (phi' ~ -R sin^2 phi / T there), so the chain
// only becomes second order once its elements are shorter than ~2 m (n >~
// 150 for 300 m); before that the errors are large and erratic. The same
// cable at 0.5 m/s (bend ~10 m) is in the table above.
// ---------------------------------------------------------------------------
TEST(StaticsPodeResolution, SecondOrderOnlyOnceTheEndBendIsResolved) {
  const PodeCase c{"paper52_v157_morison", 300, 0.14, 0.010, 1.9, 0.0, 3, 0.05, 0.5, 1.57, AddedMassModel::Morison};
  const PodeCable theory = theory_of(c, false);
  const TowQuantities th = theory_quantities(theory);
  const double bend = std::hypot(theory.end_x, theory.end_z) / theory.R;
  std::ostringstream os;
  os << std::setprecision(4) << "[measured] Pode " << c.name << ": theory T=" << th.tension
     << " N, angle=" << th.angle * 180 / kPi << " deg, depth=" << th.depth << " m, offset=" << th.offset
     << " m; end bend length T0/R=" << bend << " m\n   n   L/n [m]  err_T       p      err_depth   p\n";
  std::vector<std::array<double, 4>> err;
  const std::vector<int> ns = {10, 20, 40, 80, 160, 320};
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const Model m = chain_model(c, ns[i]);
    const StaticsResult r = solve_statics(m, Vec3(c.V, 0, 0));
    ASSERT_TRUE(r.converged) << r.message;
    err.push_back(errors(chain_quantities(m, r), th));
    os << std::setw(4) << ns[i] << "   " << std::setw(6) << c.length / ns[i] << "   " << std::scientific
       << std::setprecision(3) << err[i][0] << "  " << std::fixed << std::setprecision(2)
       << (i ? validation::observed_order(err[i - 1][0], err[i][0]) : 0.0) << "   " << std::scientific
       << std::setprecision(3) << err[i][2] << "  " << std::fixed << std::setprecision(2)
       << (i ? validation::observed_order(err[i - 1][2], err[i][2]) : 0.0) << "\n";
  }
  std::cout << os.str();
  // Unresolved (L/n = 7.5 m > T0/R): still several percent off.
  EXPECT_GT(err[2][0], 2e-2);
  // Resolved (L/n < 2 T0/R): second order for the last doubling (2 +- 0.3:
  // measured 2.03 for the tension, 2.18 for the depth, still settling), and
  // within 1.5e-3 at n = 320 (measured 9.5e-4).
  EXPECT_NEAR(validation::observed_order(err[4][0], err[5][0]), 2.0, 0.3);
  EXPECT_NEAR(validation::observed_order(err[4][2], err[5][2]), 2.0, 0.3);
  EXPECT_LT(err[5][0], 1.5e-3);
  EXPECT_LT(err[5][2], 1.5e-3);
}

// ---------------------------------------------------------------------------
// Shape: every joint of the n = 20 chain lies on the continuous curve (same
// arc length from the lower end) to second order. Writes the figure's data.
// ---------------------------------------------------------------------------
TEST(StaticsPodeShape, JointsLieOnTheContinuousCurve) {
  const PodeCase c = pode_cases()[0];  // heavy sphere, Morison, f = 0
  const PodeCable theory = theory_of(c, false);
  std::vector<double> s_curve;
  for (int i = 0; i <= 400; ++i) s_curve.push_back(c.length * i / 400.0);
  const auto curve = validation::integrate_pode(theory, s_curve);
  const PodePoint& top = curve.back();
  auto out = validation::data_file("validation_pode_shape.dat");
  if (out) {
    *out << "# continuous (Pode): x z relative to the tow point [m], horizontal then depth up\n";
    for (const auto& p : curve) *out << p.x - top.x << " " << p.z - top.z << "\n";
  }
  double prev = 0;
  for (int n : {5, 10, 20, 40}) {
    const Model m = chain_model(c, n);
    const StaticsResult r = solve_statics(m, Vec3(c.V, 0, 0));
    ASSERT_TRUE(r.converged) << r.message;
    std::vector<double> s_joint;  // arc length from the lower end of joint k = n..0
    for (int k = n; k >= 0; --k) s_joint.push_back(c.length * (n - k) / n);
    const auto ref = validation::integrate_pode(theory, s_joint);
    if (out) *out << "\n\n# chain n=" << n << ": joints x z relative to the tow point [m]\n";
    Vec3 P = r.state.r0;
    double dmax = 0;
    std::vector<Vec3> joints{P};
    for (int k = 0; k < n; ++k) joints.push_back(P += m.cable.elements[k].length * r.state.e[k]);
    for (int k = 0; k <= n; ++k) {
      const PodePoint& p = ref[n - k];
      const Vec3 d = joints[k] - r.state.r0;
      dmax = std::max(dmax, std::hypot(d.x() - (p.x - top.x), d.z() - (p.z - top.z)) / c.length);
      if (out) *out << d.x() << " " << d.z() << "\n";
    }
    std::cout << "[measured] Pode shape n=" << n << ": max joint distance from the curve / L = " << dmax;
    if (prev > 0) std::cout << " (order " << validation::observed_order(prev, dmax) << ")";
    std::cout << "\n";
    // Second order: the largest joint distance falls ~4x per doubling once
    // the elements resolve the bend at the sphere (measured orders 1.56,
    // 1.86, 1.96 for n = 10, 20, 40): at least 3.5x for the last doubling.
    if (n == 40) {
      EXPECT_LT(dmax, prev / 3.5);
    }
    if (prev > 0) {
      EXPECT_LT(dmax, prev);
    }
    prev = dmax;
  }
  EXPECT_LT(prev, 2e-4);  // n = 40: measured 1.3e-4 of the length
}

// ---------------------------------------------------------------------------
// Critical angle. Without an end load the continuous cable is straight at
// phi_c, w cos phi_c = R sin^2 phi_c, for any f (the friction is tangential);
// the tension grows linearly, dT/ds = w sin phi_c + f R, so the tow tension
// is L (w sin phi_c + f R) (Pode's relation with friction). The Morison chain
// reproduces this EXACTLY at any n: the free lowest element's moment balance
// about its top joint forces its load along e (zero normal load, i.e. phi_c),
// and then every joint force is along the next element. With the ideal-fluid
// form the lowest element also carries the Munk moment, so it is tilted away
// from phi_c by an amount that depends on its length (a boundary layer:
// the continuous cable with the Munk couple needs phi = 90 deg at a free
// end); far from the end the angle tends to phi_c as T grows.
// ---------------------------------------------------------------------------
struct CriticalCase {
  double f;
  AddedMassModel am;
};
void PrintTo(const CriticalCase& c, std::ostream* os) {
  *os << (c.am == AddedMassModel::Morison ? "Morison" : "ideal") << " f=" << c.f;
}
class StaticsCriticalAngle : public ::testing::TestWithParam<CriticalCase> {};

TEST_P(StaticsCriticalAngle, FreeCableTrailsAtCriticalAngle) {
  const CriticalCase cc = GetParam();
  const PodeCase c{"free", 100, 1.5, 0.019, 1.8, cc.f, 0, 0, 0, 1.5, cc.am};
  const PodeCable p = theory_of(c, false);
  const double phi_c = validation::critical_angle(p.w, p.R);
  // Friction with towsim's smoothed sign sgn_s(u.e), u.e = -V cos phi_c
  // (a 3e-7 relative effect on the friction at v_s = 1e-3 m/s).
  const double ue = c.V * std::cos(phi_c), vs = 1e-3;
  const double T_top = c.length * (p.w * std::sin(phi_c) + c.f * p.R * ue / std::sqrt(ue * ue + vs * vs));
  const int n = 40;
  const Model m = chain_model(c, n);
  const StaticsResult r = solve_statics(m, Vec3(c.V, 0, 0));
  ASSERT_TRUE(r.converged) << r.message;
  std::vector<double> phi(n);
  for (int k = 0; k < n; ++k) phi[k] = std::atan2(-r.state.e[k].z(), -r.state.e[k].x());
  double dmax = 0;
  for (double a : phi) dmax = std::max(dmax, std::abs(a - phi_c));
  const double eT = std::abs(r.tow_force.norm() - T_top) / T_top;
  std::cout << "[measured] critical angle f=" << c.f << (cc.am == AddedMassModel::Morison ? " Morison" : " ideal")
            << ": phi_c=" << phi_c * 180 / kPi << " deg; elements: top " << phi[0] * 180 / kPi << ", middle "
            << phi[n / 2] * 180 / kPi << ", bottom " << phi[n - 1] * 180 / kPi << " deg; max|phi-phi_c|=" << dmax
            << " rad; tow tension " << r.tow_force.norm() << " N vs L(w sin phi_c + f R)=" << T_top << " (rel " << eT
            << ")\n";
  if (cc.am == AddedMassModel::Morison) {
    // Exact at any n: only the statics residual (|alpha| < 1e-10 rad/s^2)
    // and round-off remain; 1e-9 rad / 1e-9 relative.
    EXPECT_LT(dmax, 1e-9);
    EXPECT_LT(eT, 1e-9);
  } else {
    // The lowest element, free at its lower end, balances moments about its
    // top joint: its load at mid-length, arm -(l/2) t, against its Munk
    // moment c sin(phi) cos(phi) l (2D, tests/support/pode.hpp), so its normal
    // load is not zero but R sin^2 phi - w cos phi = c sin(2 phi) / l (l its
    // length, c = Ca rho A V^2): solved here by Newton. Exact up to the
    // statics residual: 1e-9 rad.
    const double l = c.length / n, cm = 1.0 * 1025 * kPi * c.diameter * c.diameter / 4 * c.V * c.V;
    double pb = phi_c;
    for (int it = 0; it < 50; ++it) {
      const double g = p.R * std::sin(pb) * std::sin(pb) - p.w * std::cos(pb) - cm * std::sin(2 * pb) / l;
      const double dg = p.R * std::sin(2 * pb) + p.w * std::sin(pb) - 2 * cm * std::cos(2 * pb) / l;
      pb -= g / dg;
    }
    std::cout << "   ideal fluid: bottom element predicted " << pb * 180 / kPi << " deg, measured "
              << phi[n - 1] * 180 / kPi << " deg (diff " << std::abs(phi[n - 1] - pb)
              << " rad); |phi_top - phi_c|=" << std::abs(phi[0] - phi_c) << " rad\n";
    EXPECT_NEAR(phi[n - 1], pb, 1e-9);
    // Up the cable the tilt dies out within a few elements (measured: the
    // top element at phi_c to ~1e-12 rad; 1e-9 allowed), and the tow tension
    // stays within 1e-3 of the straight cable's (measured 1.5e-4: the
    // bottom element's tilt).
    EXPECT_LT(std::abs(phi[0] - phi_c), 1e-9);
    EXPECT_LT(eT, 1e-3);
  }
}

INSTANTIATE_TEST_SUITE_P(StaticsFree, StaticsCriticalAngle,
                         ::testing::Values(CriticalCase{0.0, AddedMassModel::Morison},
                                           CriticalCase{0.02, AddedMassModel::Morison},
                                           CriticalCase{0.0, AddedMassModel::IdealFluid},
                                           CriticalCase{0.02, AddedMassModel::IdealFluid}),
                         [](const auto& info) {
                           return std::string(info.param.am == AddedMassModel::Morison ? "Morison" : "Ideal") +
                                  (info.param.f > 0 ? "_f002" : "_f0");
                         });

}  // namespace
}  // namespace towsim
