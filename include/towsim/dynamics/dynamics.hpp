// Forward dynamics of cable and body: the default O(n) recursion and the
// paper's dense Lagrange formulation (docs/theory.md §2-5).
#pragma once

#include <cstddef>

#include "towsim/dynamics/fork.hpp"
#include "towsim/dynamics/state.hpp"

namespace towsim {

/// Default formulation: accelerations, tow force, link force and every joint
/// force at cost O(n), by a backward pass of articulated joint inertias
/// (f_k = K_k a_{P_k} + b_k) from the body up to the tow point and a forward
/// pass of accelerations down the chain. In Motion mode the tow point follows
/// the tow law (s.r0, s.v0 must match it) and F_R is computed; in Force mode
/// F_R is imposed and the tow point's acceleration is computed.
/// Results in ws.acc. Also fills ws's kinematics and loads. With a fork,
/// the elements' loads run in two halves at once (compute_loads):
/// bit-identical to fork = nullptr.
void forward_dynamics(const Model& model, const PhysicalState& s, double t, Workspace& ws, Fork* fork = nullptr);

/// forward_dynamics(model, s, t, ws) at the directions and lengths of the
/// last forward_dynamics on `inertias` (the caller's guarantee; its time,
/// tow point and rates may differ): the rigid elements' articulated
/// inertias (K, T, G T, Phi, H; state-only) are taken from there, the rest
/// (kinematics, loads, biases, forward pass) recomputed. Bit-identical to
/// forward_dynamics: the same operations on the same values (W's time
/// column f_t, docs/performance.md). `inertias` may be ws itself. `fork`
/// as for forward_dynamics.
void forward_dynamics_time_shift(const Model& model, const PhysicalState& s, double t, const Workspace& inertias,
                                 Workspace& ws, Fork* fork = nullptr);
/// Impulsive response to a jump dv of the tow point's velocity (a tow law
/// that is only C0 in position, e.g. a heave starting at full speed): the
/// jumps of every element's and the body's angular velocity that the
/// inextensible chain must take, from the same recursion with the impulse in
/// place of the acceleration and no finite loads (they give no impulse).
/// Results: ws.acc.alpha (d omega_k), ws.acc.length_acc (d l_k' of elastic
/// elements) and ws.acc.alpha_b (d omega_B).
void tow_velocity_jump(const Model& model, const PhysicalState& s, const Vec3& dv, Workspace& ws);

/// Loads and inertias of every element and of the body for the current
/// kinematics (shared by both formulations). With a fork and at least
/// kSplitLoadsElements elements, the elements' loads (each independent of
/// the others) run in two halves of the chain at once; the same arithmetic
/// per element, so bit-identical to fork = nullptr.
void compute_loads(const Model& model, const PhysicalState& s, double t, Workspace& ws, Fork* fork = nullptr);

/// Elements from which compute_loads hands half of them to its fork [-]
/// (docs/performance.md "Loads on two threads"): below, the
/// hand-off costs about what the half saves.
constexpr std::size_t kSplitLoadsElements = 200;

}  // namespace towsim
