// The touchdown joint (towsim/sim/touchdown.hpp).
#include "towsim/sim/touchdown.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace towsim {

namespace {

inline std::size_t idx(int i) { return static_cast<std::size_t>(i); }

// A joint this close to the bottom's level, relative to its element's
// length, lies on it (the contact's rest sink puts a lying axis on the
// level, to round-off) [-].
constexpr double kLyingHeight = 1e-7;
// Bisection of the split ends when its bracket is this short, relative to
// the element's length: the tension is then within w 1e-6 L of exact [-].
constexpr double kSplitBracket = 1e-6;
constexpr int kMaxSolves = 40;  // steady tows per touchdown, at most [-]
// Neither part of a split element shorter than this of its length: a
// joint this close above the bottom, or an element this close to lying
// along the slope above, is left as it is [-].
constexpr double kShortestPart = 1e-3;

/// Height of joint j of a steady tow above the flat bottom (its sample's node_pos) [m].
double height(const Seabed& sb, const StaticsResult& r, int j) {
  const Vec3& p = r.sample.node_pos[static_cast<std::size_t>(j)];
  return p.z() - sb.bottom_z(p.x());
}

/// The first element from the top of steady tow r that reaches from above
/// the bottom (by more than kLyingHeight of its length) to a joint lying
/// on it; -1: none.
int crossing_element(const Model& m, const StaticsResult& r) {
  for (int k = 0; k < m.cable.n(); ++k) {
    const double L = m.cable.elements[static_cast<std::size_t>(k)].length;
    if (height(*m.seabed, r, k) > kLyingHeight * L && height(*m.seabed, r, k + 1) <= kLyingHeight * L) return k;
  }
  return -1;
}

/// Whether element k may be split: rigid, no body at either of its joints.
bool splittable(const Model& m, int k) {
  if (m.cable.elements[static_cast<std::size_t>(k)].axial_stiffness > 0) return false;
  return std::none_of(m.bodies.begin(), m.bodies.end(),
                      [k](const Body& b) { return b.joint == k || b.joint == k + 1; });
}

/// What the split needs of the model: a flat bottom felt along elements, no winch.
bool applies(const Model& m) {
  if (!m.seabed || !m.seabed->along_elements || m.winch.active()) return false;
  const std::vector<double>& d = m.seabed->depth;
  return std::all_of(d.begin(), d.end(), [&](double v) { return v == d.front(); });
}

/// Elements [first, first + count) of the model remeshed into `lengths`,
/// the touchdown at joint `touchdown` of the result.
struct Remesh {
  int first = 0, count = 0, touchdown = 0;
  std::vector<double> lengths;  // [m]
};

/// Whether joint j (between elements j - 1 and j) carries nothing of its
/// own and both elements are the same section's rigid cable: the two may
/// be remeshed as one run.
bool mergeable(const Model& m, int j) {
  if (j < 1 || j >= m.cable.n()) return false;
  const auto at_j = [j](const auto& x) { return x.joint == j; };
  if (std::any_of(m.cable.attachments.begin(), m.cable.attachments.end(), at_j) ||
      std::any_of(m.bodies.begin(), m.bodies.end(), at_j))
    return false;
  for (const Section& sec : m.cable.sections)
    if (sec.first_element == j) return false;
  return m.cable.elements[static_cast<std::size_t>(j - 1)].axial_stiffness == 0 &&
         m.cable.elements[static_cast<std::size_t>(j)].axial_stiffness == 0;
}

/// The run of element k: the elements around it, k's own included, that
/// mergeable joints join (one section's rigid cable, nothing between them).
struct Run {
  int first = 0, last = 0;  // elements [first, last] [-]
};
Run run_of(const Model& m, int k) {
  Run r{k, k};
  while (mergeable(m, r.first)) --r.first;
  while (mergeable(m, r.last + 1)) ++r.last;
  return r;
}

/// The run's arc from its top to the touchdown at arc a along element k [m].
double arc_above(const Model& m, const Run& run, int k, double a) {
  double above = a;
  for (int i = run.first; i < k; ++i) above += m.cable.elements[idx(i)].length;
  return above;
}

/// How many elements the run holds above the touchdown at arc a along
/// element k: the nearest whole number to the run's arc above it, in
/// elements of k's length; at least 1.
int elements_above(const Model& m, const Run& run, int k, double a) {
  return std::max(1, static_cast<int>(std::lround(arc_above(m, run, k, a) / m.cable.elements[idx(k)].length)));
}

/// The touchdown at arc a along element k: k's run remeshed as `up` equal
/// elements above the touchdown and the rest of its count in equal
/// elements below it (at least one). The mesh stays as even as it was:
/// each element within 1 / (2 up) (above) or 1 / (2 down) (below) of the
/// run's length, where a split of k alone would leave a part as short as
/// the touchdown is close to a joint (and a fixed-step run of the dragged
/// cable goes unstable at a third of the step it takes on an even mesh).
Remesh plan(const Model& m, const Run& run, int k, double a, int up) {
  const double above = arc_above(m, run, k, a);        // [m]
  double below = m.cable.elements[idx(k)].length - a;  // [m]
  for (int i = k + 1; i <= run.last; ++i) below += m.cable.elements[idx(i)].length;
  const int count = run.last - run.first + 1, down = std::max(1, count - up);
  Remesh r{run.first, count, run.first + up, {}};
  r.lengths.assign(idx(up), above / up);
  r.lengths.insert(r.lengths.end(), idx(down), below / down);
  return r;
}

}  // namespace

Model remesh(const Model& model, int first, int count, const std::vector<double>& lengths) {
  Model m = model;
  auto& els = m.cable.elements;
  const Element like = els[static_cast<std::size_t>(first)];  // the section's element: its properties per metre
  els.erase(els.begin() + first, els.begin() + first + count);
  std::vector<Element> parts;
  parts.reserve(lengths.size());
  for (double l : lengths) parts.push_back(scaled_element(like, l));
  els.insert(els.begin() + first, parts.begin(), parts.end());
  // The section holding the run gets the difference; those below start later; so do the joints below.
  const int more = static_cast<int>(lengths.size()) - count, last = first + count - 1;
  for (Section& sec : m.cable.sections) {
    if (sec.first_element > last)
      sec.first_element += more;
    else if (first < sec.first_element + sec.elements)
      sec.elements += more;
  }
  for (Attachment& a : m.cable.attachments)
    if (a.joint > last) a.joint += more;
  for (Body& b : m.bodies)
    if (b.joint > last) b.joint += more;
  return m;
}

TouchdownStatics touchdown_statics(const Model& model, const Vec3& V, const volatile int* stop_flag) {
  return with_touchdown_joint(model, V, solve_statics(model, V, stop_flag), stop_flag);
}

TouchdownStatics steady_touchdown_state(const Model& model, const volatile int* stop_flag) {
  TouchdownStatics out = with_touchdown_joint(model, tow_law_kinematics(model.tow, 0.0).vel,
                                              steady_state(model, stop_flag), stop_flag);
  // As steady_state: the tow point where and as the tow law has it at t = 0.
  const TowKinematics k = tow_kinematics(model.tow, 0.0);
  out.statics.state.r0 = k.pos;
  out.statics.state.v0 = k.vel;
  return out;
}

TouchdownStatics with_touchdown_joint(const Model& model, const Vec3& V, StaticsResult first,
                                      const volatile int* stop_flag) {
  TouchdownStatics out{model, std::move(first)};
  // At rest only: the hanging part then meets the bottom vertically, where a
  // crossing element is furthest from the cable's shape. A moving tow's
  // catenary meets it at a shallow angle, the crossing element nearly along
  // it (its top tension converges at second order without the joint,
  // docs/validation.md §7), and each of its steady tows is a relaxation.
  if (V.norm() > 0 || !applies(model) || !out.statics.converged) return out;
  const PhysicalState& s = out.statics.state;
  const int k = crossing_element(model, out.statics);
  if (k < 0 || !splittable(model, k)) return out;
  const double L = model.cable.elements[static_cast<std::size_t>(k)].length;
  const double d = height(*model.seabed, out.statics, k);  // the upper joint's height [m]
  // First guess of the touchdown's arc along element k: down the slope of the element above.
  const Vec3 above = s.e[static_cast<std::size_t>(std::max(k - 1, 0))];
  const double lo_cap = kShortestPart * L, hi_cap = (1 - kShortestPart) * L;
  double a = d / std::max(-above.z(), 0.1);
  // Reaching the bottom along the slope above: the element's lower joint is the touchdown already.
  if (a >= hi_cap) return out;
  a = std::clamp(a, lo_cap, hi_cap);
  // The steady tow with the touchdown at arc a: hovering (above the bottom) or lying.
  struct Try {
    bool lying = false;
    double height = 0, slope = 0;  // the touchdown joint's height [m]; the part above's slope [-]
    Model model;
    StaticsResult statics;
  };
  // The run's count above the touchdown, from the first guess: fixed, so
  // that the mesh moves continuously with the arc in the search below.
  const Run run = run_of(model, k);
  const int up = elements_above(model, run, k, a);
  int solves = 1;
  const auto attempt = [&](double arc) {
    const Remesh r = plan(model, run, k, arc, up);
    Try t{false, 0.0, 0.0, remesh(model, r.first, r.count, r.lengths), {}};
    t.statics = solve_statics(t.model, V, stop_flag);
    ++solves;
    if (!t.statics.converged) return t;
    t.height = height(*model.seabed, t.statics, r.touchdown);
    t.slope = -t.statics.state.e[static_cast<std::size_t>(r.touchdown - 1)].z();
    t.lying = t.height <= kLyingHeight * L;
    return t;
  };
  // Newton on the hovering height down the slope of the part above while
  // it hovers; once one lies, just short of it (a hanging part that lands
  // exactly lies there), then bisection between the longest hovering and
  // the shortest lying part.
  double lo = 0, hi = L;    // hovering at arc 0 (joint k), lying at L (joint k + 1)
  std::optional<Try> best;  // the shortest lying part so far
  while (solves < kMaxSolves && !(stop_flag && *stop_flag)) {
    Try t = attempt(a);
    if (!t.statics.converged) return out;
    const bool lying = t.lying;
    const double step = t.slope > 0.1 ? t.height / t.slope : -1;
    if (lying) {
      hi = a;
      best = std::move(t);
    } else {
      lo = a;
    }
    if (hi - lo <= kSplitBracket * L) break;
    a = lying ? hi - 0.5 * kSplitBracket * L : step >= 0 ? a + step : 0.5 * (lo + hi);
    if (!(a > lo && a < hi)) a = 0.5 * (lo + hi);
    a = std::clamp(a, lo_cap, hi_cap);
  }
  if (!best || hi < lo_cap || hi > hi_cap) return out;
  out.model = std::move(best->model);
  out.statics = std::move(best->statics);
  out.split_element = k;
  out.split_arc = hi;
  return out;
}

}  // namespace towsim
