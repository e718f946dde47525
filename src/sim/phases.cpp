// The manoeuvre phases of a run (include/towsim/sim/phases.hpp).
#include "towsim/sim/phases.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace towsim {

namespace {

/// Below this the winch's pay-out speed is taken as zero (a stop) [m/s]: the
/// output's own zero (output::kZeroBelow); schedule round-off is far smaller.
constexpr double kStoppedBelow = 1e-9;

/// The tow law's activities, in piece order.
void tow_activities(const Tow& tow, std::vector<Phase>& out) {
  if (tow.mode == Tow::Mode::Force) {
    // Linear between rows, held outside them: a change wherever two rows differ.
    for (std::size_t i = 0; i + 1 < tow.force_time.size(); ++i) {
      if (tow.force_value[i] == tow.force_value[i + 1]) continue;
      Phase p{Phase::Kind::ForceChange};
      p.start = tow.force_time[i];
      p.end = tow.force_time[i + 1];
      if (!out.empty() && out.back().end == p.start)  // one change over consecutive spans
        out.back().end = p.end;
      else
        out.push_back(p);
    }
    return;
  }
  // The course replaces the offsets' horizontal motion from the first manoeuvre on.
  bool course = false;
  double t_first = CourseState::kNever;  // [s]
  if (tow.plan != nullptr) course = tow.plan->course, t_first = tow.plan->t_first;
  for (std::size_t i = 0; i < tow.pieces.size(); ++i) {
    Phase p;
    p.piece = static_cast<int>(i);
    if (const auto* r = std::get_if<Ramp>(&tow.pieces[i])) {
      if (!(r->ramp_time > 0) || r->speed == 0) continue;
      p.kind = Phase::Kind::Accelerate;
      p.start = 0;
      p.end = r->ramp_time;
      // A horizontal ramp stops mattering where the course takes over.
      if (course && t_first < p.end && r->direction.z() == 0) p.end = t_first;
    } else if (const auto* h = std::get_if<Heave>(&tow.pieces[i])) {
      if (h->amplitude == 0) continue;
      p.kind = Phase::Kind::Heave;
      p.start = h->start_time;
      p.end = CourseState::kNever;
    } else if (const auto* tr = std::get_if<Track>(&tow.pieces[i])) {
      if (tr->time.size() < 2) continue;
      p.kind = Phase::Kind::Track;
      p.start = tr->time.front();
      p.end = tr->time.back();
    } else {
      continue;  // manoeuvres: below, from the course
    }
    out.push_back(p);
  }
  for (const ManoeuvreSpan& s : manoeuvre_spans(tow)) {
    Phase p;
    p.piece = static_cast<int>(s.piece);
    p.kind = std::holds_alternative<Turn>(tow.pieces[s.piece]) ? Phase::Kind::Turn : Phase::Kind::SpeedChange;
    p.start = s.start;
    p.end = s.end;
    out.push_back(p);
  }
}

/// The winch's activities: spans of pay-out and of haul-in of an imposed schedule.
void winch_activities(const Winch& w, std::vector<Phase>& out) {
  if (w.mode != Winch::Mode::Imposed) return;
  const auto& sc = w.schedule;
  // Each piece, split where its (linear) speed changes sign: stop, pay-out or haul-in.
  struct Span {
    double a, b;
    Phase::Kind kind;
    bool stop;
  };
  std::vector<Span> spans;
  for (std::size_t i = 0; i < sc.size(); ++i) {
    const WinchPiece& p = sc[i];
    double t1 = CourseState::kNever;  // the piece's end [s]
    if (i + 1 < sc.size()) t1 = sc[i + 1].t0;
    const double tz = p.acc != 0 ? p.t0 - p.rate / p.acc : CourseState::kNever;  // speed crosses zero
    const double cuts[3] = {p.t0, tz > p.t0 && tz < t1 ? tz : t1, t1};
    for (int k = 0; k < 2; ++k) {
      const double a = cuts[k], b = cuts[k + 1];
      if (!(b > a)) continue;
      // The speed at both ends (an endless last piece: its sign from the acceleration once moving).
      const double at_a = p.rate + p.acc * (a - p.t0);
      const double at_b = std::isfinite(b) ? p.rate + p.acc * (b - p.t0) : (p.acc != 0 ? p.acc : at_a);
      const bool stop = std::abs(at_a) <= kStoppedBelow && std::abs(at_b) <= kStoppedBelow;
      spans.push_back({a, b, at_a + at_b > 0 ? Phase::Kind::PayOut : Phase::Kind::HaulIn, stop});
    }
  }
  for (const Span& s : spans) {
    if (s.stop) continue;
    if (!out.empty() && out.back().winch && out.back().kind == s.kind && out.back().end == s.a) {
      out.back().end = s.b;  // one pay-out (or haul-in) over consecutive pieces
      continue;
    }
    Phase p{s.kind};
    p.winch = true;
    p.start = s.a;
    p.end = s.b;
    out.push_back(p);
  }
}

}  // namespace

const char* phase_kind_name(Phase::Kind kind) {
  switch (kind) {
    case Phase::Kind::Steady:
      return "steady";
    case Phase::Kind::Accelerate:
      return "accelerate";
    case Phase::Kind::SpeedChange:
      return "speed_change";
    case Phase::Kind::Turn:
      return "turn";
    case Phase::Kind::Heave:
      return "heave";
    case Phase::Kind::Track:
      return "track";
    case Phase::Kind::ForceChange:
      return "force_change";
    case Phase::Kind::PayOut:
      return "pay_out";
    case Phase::Kind::HaulIn:
      return "haul_in";
  }
  return "steady";
}

std::vector<Phase> run_phases(const Model& model) {
  const double D = model.sim.duration;
  std::vector<Phase> act;
  tow_activities(model.tow, act);
  winch_activities(model.winch, act);
  // Within the run: clipped to [0, D], empty ones left out.
  for (Phase& p : act) {
    p.start = std::max(p.start, 0.0);
    p.end = std::min(p.end, D);
  }
  std::erase_if(act, [](const Phase& p) { return !(p.end > p.start); });
  std::stable_sort(act.begin(), act.end(), [](const Phase& a, const Phase& b) { return a.start < b.start; });
  // Steady: the gaps between the activities.
  std::vector<Phase> out;
  double covered = 0;  // the activities so far cover up to here [s]
  for (const Phase& p : act) {
    if (p.start > covered) out.push_back(Phase{Phase::Kind::Steady, -1, false, covered, p.start, 0});
    covered = std::max(covered, p.end);
  }
  if (D > covered) out.push_back(Phase{Phase::Kind::Steady, -1, false, covered, D, 0});
  out.insert(out.end(), act.begin(), act.end());
  std::stable_sort(out.begin(), out.end(), [](const Phase& a, const Phase& b) {
    return a.start < b.start || (a.start == b.start && a.end < b.end);
  });
  // The settling window: up to where another activity starts, or runs, at or after the end.
  for (std::size_t i = 0; i < out.size(); ++i) {
    Phase& p = out[i];
    p.settle_end = D;
    for (std::size_t j = 0; j < out.size(); ++j) {
      const Phase& q = out[j];
      if (j == i || q.kind == Phase::Kind::Steady || !(q.end > p.end)) continue;
      p.settle_end = std::min(p.settle_end, std::max(q.start, p.end));
    }
  }
  return out;
}

}  // namespace towsim
