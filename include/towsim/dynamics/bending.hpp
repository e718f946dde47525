// Bending stiffness: a joint part, the discrete elastica (docs/theory.md
// §5.6 "Bending stiffness"; shared MODEL.md §10).
//
// Joint k between elements k-1 and k (k = 1..n-1, no body there: a body's
// links are ball joints) carries a rotational spring
//   M_k = kappa_k beta_k,  kappa_k = 2 / (L_{k-1} / EI_{k-1} + L_k / EI_k),
// beta_k the rotation vector that turns e_{k-1} into e_k (angle about
// e_{k-1} x e_k). For equal elements kappa_k = EI / l_kk, l_kk = (L_{k-1} + L_k)/2;
// between two sections the two halves act in series (and a section without
// bending stiffness makes the joint a hinge). The element above takes +M_k,
// the element below -M_k: a pair of couples, so the spring adds nothing to
// the joint forces' balance and its energy kappa |beta|^2 / 2 is conserved.
//
// The part supplies its loads (bending_loads, into the elements' couples)
// and its local Jacobian (bending_local_stiffness: each element's rotation
// against its neighbours held, kappa_k + kappa_{k+1}); the recursion and the
// stage solve take both unchanged.
#pragma once

#include <vector>

#include "towsim/dynamics/state.hpp"

namespace towsim {

/// True when some element has bending stiffness.
bool has_bending(const Model& model);

/// Stiffness of the spring between two adjacent elements [N m/rad]: the two
/// half-elements in series, 0 when either has no bending stiffness.
double joint_bending_stiffness(const Element& upper, const Element& lower);

/// Rotation vector turning unit vector a into unit vector b: the angle
/// between them about a x b [rad] (0 for parallel vectors; for opposite
/// ones the axis is undefined and the angle pi is put about a's tangent t1).
Vec3 bending_angle(const Vec3& a, const Vec3& b);

/// The bending springs' couples at the state whose kinematics ws holds
/// (compute_kinematics: the winch's current top element): ws.bend[k] for
/// every joint, and +bend[k] added to ws.Mom[k-1], -bend[k] to ws.Mom[k].
/// Nothing (ws.bend stays zero) without bending stiffness (ws.bending).
void bending_loads(const Model& model, const PhysicalState& s, Workspace& ws);

/// Element k's (0-based) bending self-stiffness kappa_k + kappa_{k+1}: the
/// springs at its two joints, turning it with its neighbours held [N m/rad].
double element_bending_stiffness(const Model& model, const Workspace& ws, std::size_t k);

/// Adds each element's bending self-stiffness kappa_k + kappa_{k+1} (its
/// rotation with its neighbours held) to `element_stiffness` [N m/rad], the
/// local Jacobian's rocking stiffness of the stage solve.
void bending_local_stiffness(const Model& model, const Workspace& ws, std::vector<double>& element_stiffness);

/// The springs the stage solve couples exactly (docs/theory.md §6.3): kappa_j
/// at each joint j = 0..n between two rigid elements, 0 elsewhere (ends,
/// bodies, hinges, and joints next to an elastic element, whose springs stay
/// in the local self-stiffness only) [N m/rad]. `kappa` is resized to n+1.
void bending_stage_couplings(const Model& model, const Workspace& ws, std::vector<double>& kappa);

}  // namespace towsim
