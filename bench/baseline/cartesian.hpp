// The EARLIER formulation the paper replaced, as a benchmark baseline only
// (not part of the library API; see docs/performance.md).
//
// Paper, introduction: Cartesian coordinates of the joints, one Lagrange
// multiplier per element for the length constraint |P_k - P_{k-1}| = L_k,
// and central differences in time (the state at t_{n+1} from the states at
// t_n and t_{n-1}):
//
//   M(x_n) (x_{n+1} - 2 x_n + x_{n-1}) / h^2 = Q(x_n, v_n) + C(x_n)^T lambda
//   g(x_n) + C(x_n) (x_{n+1} - x_n) = 0      (the constraint, linearised)
//
// solved for (x_{n+1}, lambda) together at every step (a block-tridiagonal
// saddle-point system, O(n)). The tow point P_0 is imposed; the tow force is
// the reaction in P_0's own equation (multiplier force of element 1 plus
// P_0's share of element 1's inertia and loads).
//
// Same physical model as towsim, element by element:
//  - rigid uniform elements: the kinetic energy of a uniform rod in terms of
//    its end velocities, m/6 (va^2 + va.vb + vb^2), IS the rigid element's
//    (translation m, rotation m L^2/12 about G, none about e) when the length
//    is held; so the consistent mass matrix m/6 [[2I, I], [I, 2I]] is used
//    (no lumping).
//  - normal added mass ma (I - ee^T) and ma L^2/12 in rotation: the same
//    consistent form with (I - ee^T). Acceleration term only (Morison form):
//    the ideal-fluid velocity terms and Munk moment of towsim's default are
//    NOT in the baseline, so comparisons use towsim's Morison option.
//  - loads at the element centre G (apparent weight, normal drag Cd, Pode or
//    skin friction, smoothed sign): the same code path as towsim
//    (towsim::element_loads with Morison), half to each end joint.
//  - optional point masses at joints (sphere: mass, isotropic added mass,
//    drag -1/2 rho Cd pi r^2 |u| u, apparent weight) and massless rigid links
//    with a rotational inertia J about their centre (a dumbbell body: two
//    spheres on a massless rod, paper 5.1, is exact in these coordinates
//    except the spin about its own axis, which no load excites there).
#pragma once

#include <vector>

#include "towsim/model/model.hpp"

namespace towsim::baseline {

/// A rigid straight link between joints k-1 and k.
struct Link {
  double length = 0;        // L [m]
  double J = 0;             // extra rotational inertia about the centre, normal to the link [kg m^2]
  bool is_element = false;  // a cable element (mass, added mass and loads of `element`)
  Element element{};        // towsim's element data (when is_element)
};

/// A point mass at a joint (a sphere of the body).
struct PointMass {
  double mass = 0;        // [kg]
  double added_mass = 0;  // isotropic [kg]
  double drag = 0;        // 1/2 rho Cd pi r^2: F = -drag |u| u [kg/m]
  double weight = 0;      // apparent weight, along -z [N]
};

/// The chain: joints 0 (tow point) .. N, links 1..N (index k-1), point masses per joint.
struct Chain {
  Model model;                   // fluid, cable options (tangential law, smoothing) and tow law
  std::vector<Link> links;       // link k joins joints k-1 and k
  std::vector<PointMass> point;  // index 0..N (point[0] unused: imposed)
  int joints() const { return static_cast<int>(links.size()) + 1; }
};

/// The cable of `m` (its elements, in order), no body.
Chain cable_chain(const Model& m);

/// Append the paper-5.1 body: two spheres (radius r, mass ms each, drag cd,
/// added-mass coefficient ca) whose centres are `spacing` apart on a massless
/// rod; the leading sphere's centre is the cable's last joint. J = the two
/// spheres' own rotational inertia 2 * 2/5 ms r^2.
void add_dumbbell(Chain& c, double ms, double r, double cd, double ca, double spacing);

/// Velocity estimate used for the loads at t_n (explicit scheme).
enum class VelocityEstimate {
  Backward,  // (x_n - x_{n-1}) / h                 (first order)
  BDF2,      // (3 x_n - 4 x_{n-1} + x_{n-2}) / 2h   (second order)
};

/// The explicit central-difference integrator with linearised constraints.
class CentralDifference {
 public:
  CentralDifference(const Chain& chain, double h, VelocityEstimate ve = VelocityEstimate::BDF2);

  /// Start at rest at t = 0 from joint positions x (x[0] = tow point).
  void start(const std::vector<Vec3>& x);
  /// Advance one step; returns false if the state is no longer finite.
  bool step();

  double time() const { return t_; }
  const std::vector<Vec3>& positions() const { return x_; }
  /// F_R exerted on the cable at P_0 at the current time t_n (computed with
  /// the accelerations of the step that leaves t_n) [N].
  const Vec3& tow_force() const { return FR_; }
  /// Largest | |P_k - P_{k-1}| / L_k - 1 | at the current positions.
  double length_error() const;
  long steps() const { return steps_; }

 private:
  void velocities();
  void assemble_and_solve();

  const Chain& c_;
  double h_;
  VelocityEstimate ve_;
  int N_;  // moving joints 1..N
  double t_ = 0;
  long steps_ = 0;
  std::vector<Vec3> x_, xm1_, xm2_, v_, e_, Q_, a_, xnew_;
  std::vector<double> g_, lam_;
  std::vector<Mat3> Md_, Mo_;  // diagonal blocks (joint k) and off-diagonal (k-1,k)
  // block Thomas storage
  std::vector<Eigen::Matrix4d> Dinv_;
  std::vector<Eigen::Matrix4d> U_;
  std::vector<Eigen::Vector4d> y_;
  Vec3 FR_ = Vec3::Zero();
};

}  // namespace towsim::baseline
