#include <cmath>
#include <numbers>

#include "checks.hpp"

namespace towsim::scenario {
namespace {

void check_piece(const PieceSpec& p, Diagnostics& d) {
  const std::string& t = p.type.value;
  if (t == "ramp") {
    check_nonzero(p.direction, d);
    check_non_negative(p.speed, d);
    check_non_negative(p.ramp_time, d);
  } else if (t == "heave") {
    check_positive(p.period, d);
    check_non_negative(p.start_time, d);
  } else if (t == "turn") {
    check_positive(p.radius, d);
    check_non_negative(p.start_time, d);
    if (p.angle_deg.given) check_positive(p.angle_deg, d);
  } else if (t == "speed") {
    check_non_negative(p.speed, d);
    check_non_negative(p.start_time, d);
    check_positive(p.ramp_time, d);
  } else if (t == "track") {
    check_positive(p.speed_scale, d);
    if (p.track.empty()) return;
    if (p.track.size() < 2) d.error(p.track_where.loc, p.track_where.path, "a track needs at least 2 rows (got 1)");
    check_increasing(p.track, "times", d);
  }
}

/// Manoeuvres in time order; no turn during a turn that never ends, no speed
/// change during another one (both known without running the course).
void check_manoeuvre_order(const TowSpec& t, Diagnostics& d) {
  const PieceSpec* prev = nullptr;     // the previous manoeuvre
  const PieceSpec* endless = nullptr;  // a turn without angle_deg
  const PieceSpec* speed = nullptr;    // the previous speed change
  for (const auto& p : t.motion) {
    if (!p.manoeuvre()) continue;
    const double t0 = p.start_time.value;
    if (prev != nullptr && t0 < prev->start_time.value) {
      d.error(p.where.loc, p.where.path,
              "starts at t = " + fmt_num(t0) + " s, before " + prev->where.path +
                  " (t = " + fmt_num(prev->start_time.value) + " s): list turns and speed changes in time order");
    } else if (p.type.value == "turn" && endless != nullptr) {
      d.error(p.where.loc, p.where.path,
              "a turn cannot start while the turn " + endless->where.path +
                  " goes on (it has no angle_deg: it never ends)");
    } else if (p.type.value == "speed" && speed != nullptr && t0 < speed->start_time.value + speed->ramp_time.value) {
      d.error(p.where.loc, p.where.path,
              "a speed change cannot start while the speed change " + speed->where.path +
                  " goes on (until t = " + fmt_num(speed->start_time.value + speed->ramp_time.value) + " s)");
    }
    prev = &p;
    if (p.type.value == "turn" && !p.angle_deg.given) endless = &p;
    if (p.type.value == "speed") speed = &p;
  }
}

/// The course starts at the first manoeuvre with the heading of the other
/// pieces' horizontal velocity; every turn needs the course moving at its start,
/// and turns must not overlap (their ends depend on the speed: run the course).
void check_course(const TowSpec& t, const PieceSpec& first, Diagnostics& d) {
  const Tow straight = build_tow(t, false);
  const double t0 = first.start_time.value;
  const Vec3 v = tow_kinematics(straight, t0).vel;
  const double horizontal = std::hypot(v.x(), v.y());
  if (!(horizontal > 1e-9)) {
    const std::string what = first.type.value == "turn" ? "a turn" : "a speed change";
    d.error(first.where.loc, first.where.path,
            what + " needs a non-zero horizontal tow speed at its start time (got " + fmt_num(horizontal) +
                " m/s at t = " + fmt_num(t0) + " s)");
    return;
  }
  const std::vector<ManoeuvreSpan> spans = manoeuvre_spans(build_tow(t));
  const ManoeuvreSpan* prev_turn = nullptr;
  for (const auto& s : spans) {
    const PieceSpec& p = t.motion[s.piece];
    if (p.type.value != "turn") continue;
    if (prev_turn != nullptr && s.start < prev_turn->end) {
      d.error(p.where.loc, p.where.path,
              "a turn cannot start while the turn " + t.motion[prev_turn->piece].where.path +
                  " goes on (until t = " + fmt_num(prev_turn->end) + " s)");
    } else if (!(s.speed > 1e-9)) {
      d.error(p.where.loc, p.where.path,
              "a turn needs a non-zero horizontal tow speed at its start time (got " + fmt_num(s.speed) +
                  " m/s at t = " + fmt_num(s.start) + " s)");
    }
    prev_turn = &s;
  }
}

TowLaw build_piece(const PieceSpec& p) {
  const std::string& t = p.type.value;
  if (t == "ramp") {
    Ramp r;
    if (p.direction.given) r.direction = p.direction.value.normalized();
    r.speed = p.speed.value;
    r.ramp_time = p.ramp_time.value;
    return r;
  }
  if (t == "heave") return Heave{p.amplitude.value, p.period.value, p.start_time.value};
  if (t == "turn") {
    Turn turn{p.radius.value, p.start_time.value, p.side.value != "starboard", CourseState::kNever};
    if (p.angle_deg.given) turn.angle = p.angle_deg.value * std::numbers::pi / 180;
    return turn;
  }
  if (t == "speed") return SpeedChange{p.speed.value, p.start_time.value, p.ramp_time.value};
  // track: times divided by speed_scale (1 keeps them bit for bit)
  Track track;
  for (const auto& row : p.track) {
    track.time.push_back(row.values[0] / p.speed_scale.value);
    track.pos.emplace_back(row.values[1], row.values[2], row.values[3]);
  }
  track.prepare();
  return track;
}

/// True when every piece can be evaluated (known type, tracks of >= 2 rows).
bool evaluable(const TowSpec& t) {
  for (const auto& p : t.motion)
    if (!p.type.given || (p.type.value == "track" && p.track.size() < 2) ||
        (p.type.value == "ramp" && !(p.direction.given && p.speed.given && p.ramp_time.given)) ||
        (p.type.value == "speed" && !(p.speed.given && p.ramp_time.given)))
      return false;
  return true;
}

}  // namespace

void check_tow(const TowSpec& t, Diagnostics& d) {
  const std::size_t before = d.size();
  const PieceSpec* first = nullptr;  // the first manoeuvre
  for (const auto& p : t.motion) {
    check_piece(p, d);
    if (first == nullptr && p.manoeuvre()) first = &p;
  }
  check_manoeuvre_order(t, d);
  check_increasing(t.force, "times", d);
  const bool force_mode = t.mode.value == "force";
  if (force_mode && !t.force_given) d.error(t.where.loc, "tow.force", "missing required key (with mode: force)");
  if (!force_mode && first != nullptr && d.size() == before && evaluable(t)) check_course(t, *first, d);
}

Tow build_tow(const TowSpec& t, bool include_manoeuvres) {
  Tow tow;
  tow.mode = t.mode.value == "force" ? Tow::Mode::Force : Tow::Mode::Motion;
  tow.start = t.start.value;
  for (const auto& p : t.motion)
    if (include_manoeuvres || !p.manoeuvre()) tow.pieces.push_back(build_piece(p));
  for (const auto& row : t.force) {
    tow.force_time.push_back(row.values[0]);
    tow.force_value.emplace_back(row.values[1], row.values[2], row.values[3]);
  }
  finalize_tow(tow);  // the course worked out once
  return tow;
}

}  // namespace towsim::scenario
