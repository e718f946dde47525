// The one traversal of the articulated recursion (docs/theory.md §5.6
// "Parts and the sweep").
//
// Every algorithm of the default formulation is a pair of passes over the
// same parts: up, from the cable's end to the tow point, each part
// eliminating its own coordinates into the articulated inertia and bias seen
// at the joint above it; down, from the tow point, each part recovering its
// accelerations from its top joint's. Forward dynamics (fast.cpp) and the
// Rosenbrock stage solves (implicit.cpp: factor, right-hand side, bias,
// increments) are visitors of these two passes, with one step per part kind.
// The traversal is the only code that knows the topology: which part hangs
// below which joint.
#pragma once

#include <cstddef>

#include "towsim/dynamics/state.hpp"

namespace towsim::sweep {

/// The kinds of element part the passes dispatch on.
enum class ElementKind : unsigned char {
  Rigid,           // inextensible element of fixed length (the paper's)
  Elastic,         // elastic element: its length is a coordinate (docs/theory.md §5.4)
  PaidOut,         // the winch's top element, rigid: its length moves with the drum
  PaidOutElastic,  // the winch's top element over an elastic cable: unstretched length paid out
};

/// Element k's (0-based) kind in the model whose kinematics ws holds.
inline ElementKind element_kind(const Model& model, const Workspace& ws, std::size_t k) {
  const bool paid_out = k == 0 && ws.winch;
  if (is_elastic(model.cable.elements[k])) return paid_out ? ElementKind::PaidOutElastic : ElementKind::Elastic;
  return paid_out ? ElementKind::PaidOut : ElementKind::Rigid;
}

/// Body index as a size_t.
inline std::size_t body_index(int i) { return static_cast<std::size_t>(i); }

/// Element k's step of a pass, by its kind: visitor.rigid, .elastic,
/// .paid_out or .paid_out_elastic with (k, args...).
template <class Visitor, class... Args>
void element_step(ElementKind kind, Visitor& visitor, std::size_t k, Args... args) {
  switch (kind) {
    case ElementKind::Rigid:
      return visitor.rigid(k, args...);
    case ElementKind::Elastic:
      return visitor.elastic(k, args...);
    case ElementKind::PaidOut:
      return visitor.paid_out(k, args...);
    case ElementKind::PaidOutElastic:
      return visitor.paid_out_elastic(k, args...);
  }
}

/// Up the chain: visitor.end(n) at the cable's end; then for each element k
/// from the bottom, what hangs at its bottom joint (visitor.body(b, k + 1)
/// for a body there, which takes in the part below it), the element's own
/// step (visitor.rigid, .elastic, .paid_out or .paid_out_elastic, with
/// whether a body hangs below it), and its top joint's (visitor.joint(k)).
template <class Visitor>
void up(const Model& model, const Workspace& ws, Visitor& visitor) {
  const std::size_t n = model.cable.elements.size();
  const int* body_at = ws.body_at.data();
  visitor.end(n);
  for (std::size_t k = n; k-- > 0;) {
    const int bi = body_at[k + 1];
    if (bi >= 0) visitor.body(body_index(bi), k + 1);
    element_step(element_kind(model, ws, k), visitor, k, bi >= 0);
    visitor.joint(k);
  }
}

/// Down the chain: visitor.top() at the tow point; then for each element k
/// from the top, its step (as in `up`), and at its bottom joint either the
/// body hanging there (visitor.body(b, k + 1), which hands the part below
/// its lower link's acceleration) or the joint (visitor.joint(k + 1)).
template <class Visitor>
void down(const Model& model, const Workspace& ws, Visitor& visitor) {
  const std::size_t n = model.cable.elements.size();
  const int* body_at = ws.body_at.data();
  visitor.top();
  for (std::size_t k = 0; k < n; ++k) {
    element_step(element_kind(model, ws, k), visitor, k);
    const int bi = body_at[k + 1];
    if (bi >= 0)
      visitor.body(body_index(bi), k + 1);
    else
      visitor.joint(k + 1);
  }
}

}  // namespace towsim::sweep
