// The tow point's imposed motion and force (include/towsim/tow/tow.hpp):
// offsets added up, then the vessel course once manoeuvres steer it.
#include "towsim/tow/tow.hpp"

#include <algorithm>
#include <cmath>
#include <concepts>
#include <memory>
#include <type_traits>
#include <utility>

#include "towsim/model/table.hpp"

namespace towsim {

namespace {

/// A law with a displacement of its own (an offset law).
template <class L>
concept OffsetLaw = requires(const L& law, double t) {
  { law.at(t) } -> std::same_as<TowKinematics>;
};

/// Start plus the sum of the offset laws at t; manoeuvres add zeros.
TowKinematics offsets(const Tow& tow, double t) {
  TowKinematics k{tow.start, Vec3::Zero(), Vec3::Zero()};
  for (const auto& piece : tow.pieces) {
    const TowKinematics d = std::visit(
        [t](const auto& law) -> TowKinematics {
          if constexpr (OffsetLaw<std::decay_t<decltype(law)>>)
            return law.at(t);
          else
            return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
        },
        piece);
    k.pos += d.pos;
    k.vel += d.vel;
    k.acc += d.acc;
  }
  return k;
}

enum class Event { Begin, TurnEnd, SpeedEnd };
using CourseSegment = std::pair<double, CourseState>;  // end [s], state at the start
constexpr std::size_t kNone = static_cast<std::size_t>(-1);

/// Walk the course from the first manoeuvre up to time t, event by event
/// (a manoeuvre begins, a turn or a speed change ends), calling
/// on_event(time, event, piece index, course) at each one before t; leave c
/// at the segment containing t. False when there is no course at t: no
/// manoeuvre, t not after the first one, or no horizontal speed then (no heading).
/// `segments`, when given, receives each segment's end and starting state.
template <class OnEvent>
bool walk(const Tow& tow, double t, CourseState& c, OnEvent&& on_event,
          std::vector<CourseSegment>* segments = nullptr) {
  const auto& ps = tow.pieces;
  std::size_t i = 0;
  while (i < ps.size() && !is_manoeuvre(ps[i])) ++i;
  if (i == ps.size()) return false;
  const double t_first = start_time(ps[i]);
  if (!(t > t_first)) return false;
  // The course starts from the offsets' horizontal position and velocity.
  const TowKinematics s = offsets(tow, t_first);
  const Vec3 vh(s.vel.x(), s.vel.y(), 0);
  const double V = vh.norm();
  if (V <= 0) return false;
  c = CourseState{};
  c.t0 = t_first;
  c.p = Vec3(s.pos.x(), s.pos.y(), 0);
  c.h = vh / V;
  c.U = V;
  std::size_t turn_piece = kNone, speed_piece = kNone;
  while (true) {
    // Begin the manoeuvres due now (they are in time order).
    for (; i < ps.size(); ++i) {
      if (!is_manoeuvre(ps[i])) continue;
      if (start_time(ps[i]) > c.t0) break;
      on_event(c.t0, Event::Begin, i, c);
      if (const auto* turn = std::get_if<Turn>(&ps[i])) {
        turn->begin(c);
        turn_piece = i;
      } else if (const auto* speed = std::get_if<SpeedChange>(&ps[i])) {
        speed->begin(c);
        speed_piece = i;
      }
    }
    // The next event; t inside this segment: done.
    const double t_next = i < ps.size() ? start_time(ps[i]) : CourseState::kNever;
    const double t_turn = turn_end_time(c);
    const double te = std::min({t_next, c.a_end, t_turn});
    if (segments != nullptr) segments->push_back({te, c});
    if (!(te < t)) return true;
    const bool turn_ends = t_turn == te, speed_ends = c.a_end == te;
    advance(c, te, turn_ends);
    if (speed_ends) {  // land exactly on the new speed
      c.U = c.U_end;
      c.a = 0;
      c.a_end = CourseState::kNever;
      on_event(te, Event::SpeedEnd, speed_piece, c);
    }
    if (turn_ends) on_event(te, Event::TurnEnd, turn_piece, c);
  }
}

}  // namespace

bool is_manoeuvre(const TowLaw& law) {
  return std::holds_alternative<Turn>(law) || std::holds_alternative<SpeedChange>(law);
}

double start_time(const TowLaw& law) {
  if (const auto* turn = std::get_if<Turn>(&law)) return turn->start_time;
  if (const auto* speed = std::get_if<SpeedChange>(&law)) return speed->start_time;
  return 0;
}

TowKinematics tow_law_kinematics(const Tow& tow, double t) {
  TowKinematics k = offsets(tow, t);
  CourseState c;
  if (!walk(tow, t, c, [](double, Event, std::size_t, const CourseState&) {})) return k;
  // The course replaces the horizontal motion; the offsets keep the vertical.
  const TowKinematics h = course_at(c, t);
  k.pos = Vec3(h.pos.x(), h.pos.y(), k.pos.z());
  k.vel = Vec3(h.vel.x(), h.vel.y(), k.vel.z());
  k.acc = Vec3(h.acc.x(), h.acc.y(), k.acc.z());
  return k;
}

void finalize_tow(Tow& tow) {
  auto plan = std::make_shared<CoursePlan>();
  plan->pieces = tow.pieces.size();
  plan->start = tow.start;
  // The walk to the end records every segment; t_first as in walk.
  std::vector<CourseSegment> seg;
  CourseState c;
  plan->course = walk(
      tow, CourseState::kNever, c, [](double, Event, std::size_t, const CourseState&) {}, &seg);
  for (const auto& [end, state] : seg) plan->segments.push_back({end, state});
  const auto& ps = tow.pieces;
  const auto first = std::find_if(ps.begin(), ps.end(), [](const TowLaw& p) { return is_manoeuvre(p); });
  plan->t_first = first == ps.end() ? CourseState::kNever : start_time(*first);
  tow.plan = std::move(plan);
  tow.plan_pieces = std::make_shared<const std::vector<TowLaw>>(tow.pieces);
}

TowKinematics tow_law_kinematics(const Tow& tow, double t, CourseCursor& cursor) {
  // The plan is checked against the pieces once per cursor (a Workspace:
  // once per run), its piece count and start at every call; no plan, or one
  // built for other pieces: walked as without it.
  const CoursePlan* plan = tow.plan.get();
  if (cursor.checked != plan) {
    cursor.checked = plan;
    cursor.usable = plan != nullptr && tow.plan_pieces && *tow.plan_pieces == tow.pieces;
  }
  if (!cursor.usable || plan->pieces != tow.pieces.size() || plan->start != tow.start)
    return tow_law_kinematics(tow, t);
  if (cursor.plan == tow.plan && t == cursor.last_t && std::signbit(t) == std::signbit(cursor.last_t))
    return cursor.last;  // -0 is not 0 here
  TowKinematics k = offsets(tow, t);
  // As walk: a course only after the first manoeuvre; then the segment
  // containing t, the first that does not end before it.
  if (plan->course && t > plan->t_first) {
    const auto seg = std::partition_point(plan->segments.begin(), plan->segments.end(),
                                          [t](const CoursePlan::Segment& s) { return s.end < t; });
    const TowKinematics h = course_at(seg->state, t);
    k.pos = Vec3(h.pos.x(), h.pos.y(), k.pos.z());
    k.vel = Vec3(h.vel.x(), h.vel.y(), k.vel.z());
    k.acc = Vec3(h.acc.x(), h.acc.y(), k.acc.z());
  }
  if (cursor.plan != tow.plan) cursor.plan = tow.plan;
  cursor.last_t = t;
  cursor.last = k;
  return k;
}

std::vector<double> tow_breakpoints(const Tow& tow) {
  std::vector<double> out;
  for (const auto& piece : tow.pieces)
    std::visit(
        [&](const auto& law) {
          if constexpr (OffsetLaw<std::decay_t<decltype(law)>>)
            law.breakpoints(out);
          else
            out.push_back(law.start_time);
        },
        piece);
  // Ends of turns and speed changes (found by running the course).
  CourseState c;
  walk(tow, CourseState::kNever, c, [&](double te, Event, std::size_t, const CourseState&) { out.push_back(te); });
  if (tow.mode == Tow::Mode::Force) out.insert(out.end(), tow.force_time.begin(), tow.force_time.end());
  std::erase_if(out, [](double t) { return !(t > 0); });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<ManoeuvreSpan> manoeuvre_spans(const Tow& tow) {
  std::vector<ManoeuvreSpan> spans;
  CourseState c;
  walk(tow, CourseState::kNever, c, [&](double te, Event ev, std::size_t piece, const CourseState& now) {
    if (ev == Event::Begin) {
      spans.push_back({piece, te, CourseState::kNever, now.U});
      return;
    }
    for (auto& s : spans)
      if (s.piece == piece) s.end = te;
  });
  // A turn cut short by a later one (refused by compile): its end without the later turns.
  for (auto& s : spans) {
    const auto* turn = std::get_if<Turn>(&tow.pieces[s.piece]);
    if (turn == nullptr || std::isfinite(s.end) || !std::isfinite(turn->angle)) continue;
    Tow alone = tow;
    alone.pieces.clear();
    for (std::size_t j = 0; j < tow.pieces.size(); ++j)
      if (j <= s.piece || !std::holds_alternative<Turn>(tow.pieces[j])) alone.pieces.push_back(tow.pieces[j]);
    walk(alone, CourseState::kNever, c, [&](double te, Event ev, std::size_t piece, const CourseState&) {
      if (ev == Event::TurnEnd && piece == s.piece) s.end = te;
    });
  }
  return spans;
}

bool final_course(const Tow& tow, CourseState& out) {
  return walk(tow, CourseState::kNever, out, [](double, Event, std::size_t, const CourseState&) {});
}

Vec3 tow_force(const Tow& tow, double t) {
  if (tow.force_value.empty()) return Vec3::Zero();
  return interpolate(tow.force_time, tow.force_value, t);
}

}  // namespace towsim
