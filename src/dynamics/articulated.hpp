// The passes over one chain of the forward dynamics (fast.cpp) and of the
// stage solve (implicit.cpp), for the algorithms that compose chains: a tree
// of lines (tree.cpp) runs them line by line, joining the lines at their
// nodes (docs/theory.md §5.7).
#pragma once

#include "towsim/dynamics/implicit.hpp"
#include "towsim/dynamics/state.hpp"

namespace towsim::chain {

/// The pass up: (K_k, b_k) at every joint from the loads and kinematics ws
/// holds, with the lines hanging from the cable's end (ws.end_K, ws.end_b)
/// and from the bodies' points (BodyWork::children) taken in. With
/// inertias_known, the rigid elements' inertia part is the workspace's already.
void articulate(const Model& model, const PhysicalState& s, Workspace& ws, bool inertias_known);

/// The pass down: every acceleration and joint force from the top joint's
/// acceleration (the tow law's, or imposed_a0 when given: an impulse, or the
/// node of the line above), giving the bodies' points' accelerations
/// (BodyWork::children) and the cable end's (ws.acc.end_acc).
void accelerate(const Model& model, const PhysicalState& s, double t, Workspace& ws, const Vec3* imposed_a0);

}  // namespace towsim::chain

namespace towsim::stage {

// The Rosenbrock stage solve's passes over one chain (implicit.cpp), after
// implicit_factor: implicit_stage_solve is loads, bias, increments. A line
// hanging from a node reads its top's increments from iw.top_dv, top_dx
// (loads) and top_a (increments); the lines below a junction enter through
// iw.end, those below a body's points through iw.body_children; each pass
// leaves the cable end's increments in iw.end.

/// The right-hand side as loads, down the chain.
void loads(const Model& model, const PhysicalState& s, const Workspace& ws, double hg, const StageRhs& r,
           ImplicitWorkspace& iw);
/// The bias, up the chain.
void bias(const Model& model, const PhysicalState& s, const Workspace& ws, ImplicitWorkspace& iw);
/// The increments z, down the chain.
void increments(const Model& model, const PhysicalState& s, const Workspace& ws, ImplicitWorkspace& iw);

}  // namespace towsim::stage
