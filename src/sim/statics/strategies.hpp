// The statics strategies (docs/theory.md §7): each a free function of the
// steady problem, in its own file under src/sim/statics/, named by the
// driver's plan (plan.hpp). Internal to src/sim/statics.cpp and src/sim/statics/.
#pragma once

#include <string>
#include <vector>

#include "plan.hpp"
#include "problem.hpp"

namespace towsim::statics {

// --- Starts (start.cpp, seabed_start.cpp) ----------------------------------

/// The starting configuration: each element along the force it carries, then
/// on a seabed the dragged-cable start or the chain laid on the bottom. p.base: the start.
Start lay_start(SteadyProblem& p);

/// The chain laid on the seabed where it would cross it; true when it turned
/// a dragged in-line body on the bottom along the cable above it.
bool lay_on_seabed(SteadyProblem& p);

/// The dragged-cable start (a moving tow, no body, no attachment): the
/// lying length found by shooting; false when not applicable.
bool lay_along_bottom(SteadyProblem& p);

// --- Seabed contact (contact.cpp) ------------------------------------------

/// How far the body's lowest point in contact lies below its link Q along the bottom's normal n [m, >= 0].
double body_drop(const Seabed& sb, const Body& body, const Mat3& R, const Vec3& Q, const Vec3& n);

/// The step x with the contact points held at their linear moves along the bottom's normal.
Eigen::VectorXd on_bottom(SteadyProblem& p, const Eigen::VectorXd& x);

// --- Sweeps, O(n) (sweeps.cpp) ---------------------------------------------

/// Sweeps until the joints stop moving; the number of sweeps; `why` empty or why it stopped early.
int solve_by_sweeps(SteadyProblem& p, const volatile int* stop_flag, std::string& why);

// --- A body's balance (body.cpp) -------------------------------------------

/// The body's attitude balancing its moments about Q (from q, else from the trims); false when none.
bool solve_body(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2, Quat& q, BodyWork& bw);

/// The body's balance at q classified by its restoring stiffness.
BodyEquilibrium classify_balance(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2,
                                 const Quat& q, BodyWork bw, std::vector<Vec3>* neutral = nullptr);

/// The balances of each body at an equilibrium (StaticsResult's equilibria).
std::vector<BodyEquilibria> find_equilibria(const Model& m, const PhysicalState& state, const Workspace& ws,
                                            const Vec3& V, const std::vector<Vec3>& below);

// --- Newton on all angles (newton_krylov.cpp, levenberg_marquardt.cpp) ---------

/// Newton-Krylov, O(n) per product; adds its steps to `iterations`; true
/// when the compression guard dropped the result for the start.
bool newton_krylov(SteadyProblem& p, double floor, const volatile int* stop_flag, int& iterations);

/// Levenberg-Marquardt with a dense Jacobian from the iterate whose residual
/// is r (r: the result's); adds its iterations to out.iterations, sets out.interrupted.
void levenberg_marquardt(SteadyProblem& p, const Attempt& a, double floor, const volatile int* stop_flag,
                         Eigen::VectorXd& r, StaticsResult& out);

// --- Dynamic relaxation (relaxation.cpp) -----------------------------------

/// The dynamics with kinetic damping from the iterate until every |alpha| at rest is below target.
void relax(SteadyProblem& p, double target, const volatile int* stop_flag);

// --- One attempt, the elastic stretch (rigid.cpp, stretch.cpp) -------------

/// The rigid elements' equilibrium from the iterate by attempt a's sweeps,
/// Newton-Krylov and Levenberg-Marquardt (its relaxation runs before);
/// sets out.iterations, residual, converged, interrupted, message.
void solve_rigid(SteadyProblem& p, const Attempt& a, const volatile int* stop_flag, StaticsResult& out);

/// Elastic elements stretched by their tensions, each pass a warm-started solve_rigid of attempt a.
void stretch(const Model& elastic, SteadyProblem& p, const Attempt& a, const volatile int* stop_flag,
             StaticsResult& out);

}  // namespace towsim::statics
