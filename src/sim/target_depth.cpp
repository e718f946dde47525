// The deployed length for a target depth at steady tow (docs/theory.md §6.5
// "Target depth"): a search on top of the statics driver, each step a whole
// solve_statics at a deployed length.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

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

/// The steady depth's miss as a function of the deployed length: each call
/// a whole statics solve, the last one's result kept.
struct DepthMiss {
  const Model& model;
  const Vec3& V;
  double depth;  // the target [m]
  const volatile int* stop_flag;
  StaticsResult last;  // the last solve

  /// Depth reached less the target at deployed length L [m]; NaN when the solve fails.
  double operator()(double L) {
    last = solve_statics(with_deployed_length(model, L), V, stop_flag);
    return last.converged ? reference_depth(model, last.sample) - depth : std::nan("");
  }
};

/// A bracket [a, b] of deployed lengths [m] and the misses there [m].
struct Bracket {
  double a, fa, b, fb;
  bool failed() const { return !std::isfinite(fa) || !std::isfinite(fb); }
  bool found() const { return !(fa * fb > 0); }
};

/// From the length L0: shorten towards the length below the top section
/// (halving what is above it) while too deep, lengthen (doubling it) while
/// too shallow, until the misses change sign, a solve fails, or 60 steps.
Bracket bracket(DepthMiss& miss, double L0, double below) {
  Bracket br{L0, miss(L0), L0, 0};
  br.fb = br.fa;
  for (int i = 0; i < 60 && !br.failed() && !br.found(); ++i) {
    if (br.fa > 0) {  // too deep: shorten
      br.b = br.a, br.fb = br.fa;
      br.a = below + 0.5 * (br.a - below);
      br.fa = miss(br.a);
    } else {  // too shallow: lengthen
      br.a = br.b, br.fa = br.fb;
      br.b = below + 2 * (br.b - below);
      br.fb = miss(br.b);
    }
  }
  return br;
}

/// Out of reach: how far the search got (the miss = reached depth - target).
std::string out_of_reach(const Model& model, double depth, double below, const Bracket& br) {
  const char* what = end_body(model) != nullptr ? "the body" : "the cable end";
  char buf[256];
  if (br.fa > 0)
    std::snprintf(buf, sizeof buf,
                  "depth %.7g m is shallower than this tow reaches: %s is at %.7g m with %.7g m deployed", depth, what,
                  depth + br.fa, std::abs(br.a - below) < 1e-9 * std::max(1.0, below) ? below : br.a);
  else
    std::snprintf(buf, sizeof buf, "depth %.7g m is deeper than this tow reaches: %s is at %.7g m with %.7g m deployed",
                  depth, what, depth + br.fb, br.b);
  return buf;
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
  const double below = below_top(model);
  DepthMiss miss{model, V, depth, stop_flag, {}};
  // Bracket the target depth.
  Bracket br = bracket(miss, model.cable.total_length(), below);
  if (br.failed()) {
    r.statics = miss.last;
    r.message = miss.last.interrupted ? "interrupted"
                                      : "the steady solve did not converge while searching (" + miss.last.message + ")";
    return r;
  }
  if (!br.found()) {
    r.message = out_of_reach(model, depth, below, br);
    return r;
  }
  // Illinois (regula falsi with halving): depth is smooth and monotone in L.
  int side = 0;
  double c = br.a, fc = br.fa;
  for (int i = 0; i < 100; ++i) {
    c = (br.a * br.fb - br.b * br.fa) / (br.fb - br.fa);
    fc = miss(c);
    if (!std::isfinite(fc)) {
      r.statics = miss.last;
      r.message = miss.last.interrupted
                      ? "interrupted"
                      : "the steady solve did not converge at " + std::to_string(c) + " m (" + miss.last.message + ")";
      return r;
    }
    if (std::abs(fc) < 1e-6) break;
    if (fc * br.fb > 0) {
      br.b = c, br.fb = fc;
      if (side == -1) br.fa /= 2;
      side = -1;
    } else {
      br.a = c, br.fa = fc;
      if (side == 1) br.fb /= 2;
      side = 1;
    }
  }
  // The length found, to 1e-6 m of depth.
  r.found = std::abs(fc) < 1e-6;
  if (!r.found) r.message = "the depth search did not converge";
  r.length = c;
  r.depth = fc + depth;
  r.statics = miss.last;
  return r;
}

}  // namespace towsim
