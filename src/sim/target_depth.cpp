// The deployed length for a target depth at steady tow (docs/theory.md "Winch").
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "towsim/sim/statics.hpp"

namespace towsim {

namespace {

/// Length below the top section [m].
double below_top(const Model& m) {
  const int n_top = m.cable.sections.empty() ? m.cable.n() : m.cable.sections.front().elements;
  double below = 0;
  for (int k = n_top; k < m.cable.n(); ++k) below += m.cable.elements[static_cast<std::size_t>(k)].length;
  return below;
}

/// Depth of the end body's origin, or of the cable end [m].
double reference_depth(const Model& m, const Sample& s) {
  if (end_body(m) != nullptr && !s.bodies.empty()) return -s.bodies.back().pos.z();
  return -s.node_pos.back().z();
}

}  // namespace

Model with_deployed_length(const Model& model, double L) {
  Model m = model;
  const int n_top = m.cable.sections.empty() ? m.cable.n() : m.cable.sections.front().elements;
  const double le = (L - below_top(model)) / n_top;  // new element length of the top section [m]
  for (int k = 0; k < n_top; ++k) {
    Element& el = m.cable.elements[static_cast<std::size_t>(k)];
    el = scaled_element(el, le);
  }
  if (!m.cable.sections.empty()) m.cable.sections.front().length = le * n_top;
  if (m.winch.active()) m.winch.nominal_length = le;
  return m;
}

TargetDepthResult length_for_depth(const Model& model, const Vec3& V, double depth, const volatile int* stop_flag) {
  TargetDepthResult r;
  const double below = below_top(model), L0 = model.cable.total_length();
  auto solve = [&](double L, StaticsResult& st) {
    st = solve_statics(with_deployed_length(model, L), V, stop_flag);
    return st.converged ? reference_depth(model, st.sample) - depth : std::nan("");
  };
  // Bracket: shorten towards the length below the top section, or lengthen by doubling.
  StaticsResult st;
  double a = L0, fa = solve(a, st);
  double b = L0, fb = fa;
  for (int i = 0; i < 60 && std::isfinite(fa) && std::isfinite(fb) && fa * fb > 0; ++i) {
    if (fa > 0) {  // too deep: shorten
      b = a, fb = fa;
      a = below + 0.5 * (a - below);
      fa = solve(a, st);
    } else {  // too shallow: lengthen
      a = b, fa = fb;
      b = below + 2 * (b - below);
      fb = solve(b, st);
    }
  }
  if (!std::isfinite(fa) || !std::isfinite(fb)) {
    r.statics = st;
    r.message = st.interrupted ? "interrupted"
                               : "the steady solve did not converge while searching (" + st.message + ")";
    return r;
  }
  if (fa * fb > 0) {
    // Out of reach: say how far the search got (f = reached depth - target).
    const char* what = end_body(model) != nullptr ? "the body" : "the cable end";
    char buf[256];
    if (fa > 0)
      std::snprintf(buf, sizeof buf,
                    "depth %.7g m is shallower than this tow reaches: %s is at %.7g m with %.7g m deployed", depth,
                    what, depth + fa, std::abs(a - below) < 1e-9 * std::max(1.0, below) ? below : a);
    else
      std::snprintf(buf, sizeof buf,
                    "depth %.7g m is deeper than this tow reaches: %s is at %.7g m with %.7g m deployed", depth, what,
                    depth + fb, b);
    r.message = buf;
    return r;
  }
  // Illinois (regula falsi with halving): depth is smooth and monotone in L.
  int side = 0;
  double c = a, fc = fa;
  for (int i = 0; i < 100; ++i) {
    c = (a * fb - b * fa) / (fb - fa);
    fc = solve(c, st);
    if (!std::isfinite(fc)) {
      r.statics = st;
      r.message = st.interrupted
                      ? "interrupted"
                      : "the steady solve did not converge at " + std::to_string(c) + " m (" + st.message + ")";
      return r;
    }
    if (std::abs(fc) < 1e-6) break;
    if (fc * fb > 0) {
      b = c, fb = fc;
      if (side == -1) fa /= 2;
      side = -1;
    } else {
      a = c, fa = fc;
      if (side == 1) fb /= 2;
      side = 1;
    }
  }
  r.found = std::abs(fc) < 1e-6;
  if (!r.found) r.message = "the depth search did not converge";
  r.length = c;
  r.depth = fc + depth;
  r.statics = st;
  return r;
}

}  // namespace towsim
