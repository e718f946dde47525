// The touchdown joint: a steady tow over a flat seabed with a joint where
// the cable meets the bottom (docs/theory.md §3.2 "The touchdown joint").
//
// A chain of rigid elements over a flat bottom touches down with one
// element across it: from a joint above the bottom to one lying on it. A
// straight element hangs half its weight on its upper joint whatever its
// slope, so the top tension is off by up to half an element's weight
// (w (L/2 - d), d the upper joint's height). Splitting that element where
// the cable meets the bottom puts a joint there: the part above hangs, the
// part below lies, and the tension is the continuous cable's.
#pragma once

#include <vector>

#include "towsim/model/model.hpp"
#include "towsim/sim/statics.hpp"

namespace towsim {

/// `model` with its elements [first, first + count) (one section's rigid
/// cable, nothing at their inner joints) replaced by elements of the given
/// lengths [m] (their sum theirs): every per-length property of the first
/// (scaled_element), the section, attachments and bodies below moved down.
Model remesh(const Model& model, int first, int count, const std::vector<double>& lengths);

/// A steady tow and the model it belongs to.
struct TouchdownStatics {
  Model model;             // the given model, or the one remeshed with a joint at its touchdown
  StaticsResult statics;   // model's steady tow at V (solve_statics)
  int split_element = -1;  // the given model's element the cable touches down on (0-based); -1: none
  double split_arc = 0;    // where, from its top [m]
};

/// The steady tow at V of `model` (solve_statics) and, at rest (V = 0) over
/// a flat seabed with contact along elements, the same with a joint at the
/// touchdown: the
/// element that reaches from above the bottom to it is split where the
/// joint that ends the hanging part lands on the bottom (the shortest upper
/// part whose lower joint lies, to 1e-6 of the element's length). The
/// element's run (the elements of its section joined by joints that carry
/// nothing) is remeshed as equal elements above the touchdown and equal
/// elements below it, as many in all as it had (one more when the
/// touchdown is in the run's first or last element): the mesh stays even,
/// each element within half an element's length shared among its part's.
/// No split:
/// no seabed, a sloping bottom, contact at joints, an active winch, an
/// elastic or a body's element, a cable that does not reach the bottom or
/// already has a joint at its touchdown, or a steady tow that does not
/// converge.
TouchdownStatics touchdown_statics(const Model& model, const Vec3& V, const volatile int* stop_flag = nullptr);

/// touchdown_statics given model's steady tow at V already solved (`first`).
TouchdownStatics with_touchdown_joint(const Model& model, const Vec3& V, StaticsResult first,
                                      const volatile int* stop_flag = nullptr);

/// The run's steady start (steady_state) with the touchdown joint: a run
/// from it runs the returned model.
TouchdownStatics steady_touchdown_state(const Model& model, const volatile int* stop_flag = nullptr);

}  // namespace towsim
