#include <cmath>

#include "checks.hpp"

namespace towsim::io {
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
  } else if (t == "track" && !p.track.empty()) {
    if (p.track.size() < 2)
      d.error(p.track_where.loc, p.track_where.path, "a track needs at least 2 rows (got 1)");
    check_increasing(p.track, "times", d);
  }
}

/// A turn starts from the horizontal speed the other pieces give at its start.
void check_turn_speed(const TowSpec& t, const PieceSpec& turn, Diagnostics& d) {
  const Tow straight = build_tow(t, false);
  const Vec3 v = tow_kinematics(straight, turn.start_time.value).vel;
  const double horizontal = std::hypot(v.x(), v.y());
  if (!(horizontal > 1e-9))
    d.error(turn.where.loc, turn.where.path,
            "a turn needs a non-zero horizontal tow speed at its start time (got " + fmt_num(horizontal) +
                " m/s at t = " + fmt_num(turn.start_time.value) + " s)");
}

TowPiece build_piece(const PieceSpec& p) {
  TowPiece piece{};
  const std::string& t = p.type.value;
  piece.type = t == "ramp"    ? TowPiece::Type::Ramp
               : t == "heave" ? TowPiece::Type::Heave
               : t == "turn"  ? TowPiece::Type::Turn
                              : TowPiece::Type::Track;
  if (p.direction.given) piece.direction = p.direction.value.normalized();
  piece.speed = p.speed.value;
  piece.ramp_time = p.ramp_time.value;
  piece.amplitude = p.amplitude.value;
  piece.period = p.period.value;
  piece.start_time = p.start_time.value;
  piece.radius = p.radius.value;
  piece.port = p.side.value != "starboard";
  for (const auto& row : p.track) {
    piece.track_time.push_back(row.values[0]);
    piece.track_pos.emplace_back(row.values[1], row.values[2], row.values[3]);
  }
  prepare_track(piece);
  return piece;
}

/// True when every piece can be evaluated (known type, tracks of >= 2 rows).
bool evaluable(const TowSpec& t) {
  for (const auto& p : t.motion)
    if (!p.type.given || (p.type.value == "track" && p.track.size() < 2) ||
        (p.type.value == "ramp" && !(p.direction.given && p.speed.given && p.ramp_time.given)))
      return false;
  return true;
}

}  // namespace

void check_tow(const TowSpec& t, Diagnostics& d) {
  const std::size_t before = d.size();
  const PieceSpec* turn = nullptr;
  for (const auto& p : t.motion) {
    check_piece(p, d);
    if (p.type.value != "turn") continue;
    if (turn != nullptr)
      d.error(p.where.loc, p.where.path, "at most one turn piece is allowed (the first is " + turn->where.path + ")");
    else
      turn = &p;
  }
  check_increasing(t.force, "times", d);
  const bool force_mode = t.mode.value == "force";
  if (force_mode && !t.force_given)
    d.error(t.where.loc, "tow.force", "missing required key (with mode: force)");
  if (!force_mode && turn != nullptr && d.size() == before && evaluable(t)) check_turn_speed(t, *turn, d);
}

Tow build_tow(const TowSpec& t, bool include_turns) {
  Tow tow;
  tow.mode = t.mode.value == "force" ? Tow::Mode::Force : Tow::Mode::Motion;
  tow.start = t.start.value;
  for (const auto& p : t.motion)
    if (include_turns || p.type.value != "turn") tow.pieces.push_back(build_piece(p));
  for (const auto& row : t.force) {
    tow.force_time.push_back(row.values[0]);
    tow.force_value.emplace_back(row.values[1], row.values[2], row.values[3]);
  }
  return tow;
}

}  // namespace towsim::io
