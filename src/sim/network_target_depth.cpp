// The length of a network's line from the vessel for a target depth
// (towsim/sim/network_target_depth.hpp).
#include "towsim/sim/network_target_depth.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "towsim/sim/statics.hpp"

namespace towsim {

namespace {

constexpr double kDepthTolerance = 1e-3;  // [m]
constexpr int kMaxBracket = 8;            // halvings or doublings of the length
constexpr int kMaxIterations = 40;        // regula falsi steps

/// One steady tow at length L of line `line`: the depth's miss (> 0: too deep).
struct Miss {
  const Network& net;
  int line;   // the line whose length varies
  int below;  // the depth of what hangs below this line only (-1: the whole network's)
  double depth;
  const volatile int* stop_flag;
  NetworkTargetDepth& out;
  double operator()(double L) {
    Network n = net;
    n.tree.lines[static_cast<std::size_t>(line)] = with_deployed_length(net.tree.lines[static_cast<std::size_t>(line)],
                                                                        L);
    NetworkSteady st = network_statics(n, stop_flag);
    ++out.evaluations;
    const double d = deepest_depth(n, st, below);
    out.length = L, out.depth = d, out.network = std::move(n), out.steady = std::move(st);
    return d - depth;
  }
};

}  // namespace

double deepest_depth(const Network& net, const NetworkSteady& st, int below) {
  NetworkMemorySink mem;
  write_network_steady(net, st, mem);
  const NetworkSample& s = mem.samples.front();
  // Each line's line from the vessel (lines come after the line they hang from).
  const TreeModel& tree = net.tree;
  std::vector<int> root(tree.lines.size());
  for (std::size_t i = 0; i < root.size(); ++i)
    root[i] = tree.tops[i].line < 0 ? static_cast<int>(i) : root[static_cast<std::size_t>(tree.tops[i].line)];
  const auto counted = [&](int line) { return below < 0 || root[static_cast<std::size_t>(line)] == below; };
  double d = -1e300;
  bool body = false;
  for (const NetworkBody& b : net.bodies)
    if (counted(b.line)) {
      body = true;
      d = std::max(d, -s.lines[static_cast<std::size_t>(b.line)].bodies[static_cast<std::size_t>(b.body)].pos.z());
    }
  if (!body)
    for (std::size_t i = 0; i < s.lines.size(); ++i)
      if (counted(static_cast<int>(i))) d = std::max(d, -s.lines[i].node_pos.back().z());
  return d;
}

NetworkTargetDepth network_length_for_depth(const Network& net, double depth, const volatile int* stop_flag, int line) {
  NetworkTargetDepth r;
  r.line = line;
  for (std::size_t i = 0; i < net.tree.tops.size() && line < 0; ++i)
    if (net.tree.tops[i].line < 0) {
      if (r.line >= 0) {
        r.message =
            "the network has more than one line from the vessel (choose the one whose length varies: --line NAME)";
        return r;
      }
      r.line = static_cast<int>(i);
    }
  if (r.line < 0 || static_cast<std::size_t>(r.line) >= net.tree.lines.size() ||
      net.tree.tops[static_cast<std::size_t>(r.line)].line >= 0)
    throw std::invalid_argument("network_length_for_depth: the line varied must hang from the vessel");
  const Model& top = net.tree.lines[static_cast<std::size_t>(r.line)];
  const double L0 = top.cable.total_length();
  const double below = top.cable.sections.empty() ? 0.0 : L0 - top.cable.sections.front().length;
  Miss miss{net, r.line, line, depth, stop_flag, r};
  try {
    // Bracket: halve (towards the sections below) or double the length.
    double a = L0, fa = miss(a), b = a, fb = fa;
    for (int k = 0; k < kMaxBracket && fa * fb > 0; ++k) {
      b = fa > 0 ? below + 0.5 * (b - below) : 2 * b;
      fb = miss(b);
      if (fa * fb > 0) a = b, fa = fb;
    }
    if (fa * fb > 0) {
      r.message = "out of reach: the depth is " + std::to_string(r.depth) + " m at a length of " +
                  std::to_string(r.length) + " m";
      return r;
    }
    // Illinois: regula falsi, the retained end's value halved when it stays.
    int side = 0;
    for (int it = 0; it < kMaxIterations; ++it) {
      const double c = (a * fb - b * fa) / (fb - fa), fc = miss(c);
      if (std::abs(fc) < kDepthTolerance) {
        r.found = true;
        return r;
      }
      if (fc * fb > 0) {
        b = c, fb = fc;
        if (side == -1) fa *= 0.5;
        side = -1;
      } else {
        a = c, fa = fc;
        if (side == 1) fb *= 0.5;
        side = 1;
      }
    }
    r.message = "the search did not reach 1 mm of depth in " + std::to_string(kMaxIterations) + " steps";
  } catch (const std::exception& e) {
    r.message = e.what();
  }
  return r;
}

}  // namespace towsim
