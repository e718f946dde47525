// Checks of a run's state after each step and at each sample, shared by
// a chain's run and a network's: divergence, slack folds, the rk4 step
// against its stability limit, stalled surfaces, parts above the surface,
// the element length drift, elastic slack episodes.
#pragma once

#include <string>

#include "towsim/integrators/system.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim::run {

/// After an accepted step at t: slack episodes and peak tensions of an elastic cable.
void track_elastic(const Model& model, const System& sys, const StateVector& y, double t, RunStats& stats);
/// RK4 only: the step against the stability limit at this sample: a
/// warning (once) beyond 0.9 times it; beyond 1.5 times it an error text
/// (the run stops), else empty.
std::string check_rk4_step(const Model& model, const Workspace& ws, double t, RunStats& stats);
/// The first time each lifting surface is seen stalled at a sample: a warning.
void check_stall(const Model& model, const Workspace& ws, double t, RunStats& stats);
/// The first sample where the cable or a body is above the water surface: a warning, once per part.
void check_surface(const Model& model, const Sample& s, RunStats& stats);
/// Empty when every row of y is finite; else the row's part and the problem.
std::string check_finite(const System& sys, const StateVector& y);
/// Empty when the chain's state is sound (no diverged rate, no folded
/// slack element); else the element or body and the problem.
std::string check_chain(const Model& model, const PhysicalState& s);
/// Absolute force scale of the force error norm: the chain's apparent weight [N] (at least 1).
double force_scale(const Model& model);
/// An adaptive tolerance's warnings into stats: above 3e-4 the time step's
/// error of the tow force may pass 0.1 % of its peak, above 1e-2 the results
/// may be far from converged.
void tolerance_warnings(const Simulation& sim, RunStats& stats);

/// The sample of the evaluated state (s, ws) at t into `out`, with the
/// sample's checks (rk4 step into *err when given, stall, surface) and the
/// element length drift into stats.
void sample_checks(const Model& model, const PhysicalState& s, const Workspace& ws, double t, RunStats& stats,
                   Sample& out, std::string* err = nullptr);

}  // namespace towsim::run
