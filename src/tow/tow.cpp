// Imposed tow-point kinematics and tow force laws (docs/scenario.md "tow"; docs/theory.md §6.1).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "towsim/model/model.hpp"
#include "towsim/model/table.hpp"

namespace towsim {

namespace {

/// Ramp: speed grows linearly from 0 at t = 0 to `speed` at ramp_time, then constant.
TowKinematics ramp(const TowPiece& p, double t) {
  const Vec3 d = p.direction.normalized();
  const double T = p.ramp_time;
  TowKinematics k{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (t < 0) return k;
  if (T <= 0) {  // no ramp: at speed from the start
    k.vel = p.speed * d;
    k.pos = p.speed * t * d;
    return k;
  }
  if (t < T) {
    k.acc = p.speed / T * d;
    k.vel = p.speed * t / T * d;
    k.pos = p.speed * t * t / (2 * T) * d;
  } else {
    k.vel = p.speed * d;
    k.pos = p.speed * (t - T / 2) * d;
  }
  return k;
}

/// Heave: z += A sin(2 pi (t - t0) / T) after t0 (rising first).
TowKinematics heave(const TowPiece& p, double t) {
  TowKinematics k{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (t <= p.start_time) return k;
  const double w = 2 * std::numbers::pi / p.period;
  const double ph = w * (t - p.start_time);
  k.pos.z() = p.amplitude * std::sin(ph);
  k.vel.z() = p.amplitude * w * std::cos(ph);
  k.acc.z() = -p.amplitude * w * w * std::sin(ph);
  return k;
}

/// Second derivatives of the natural cubic spline through (ts, xs) (Thomas algorithm).
std::vector<Vec3> spline_curvatures(const std::vector<double>& ts, const std::vector<Vec3>& xs) {
  const std::size_t m = ts.size();
  std::vector<Vec3> M(m, Vec3::Zero());
  if (m <= 2) return M;
  std::vector<double> c(m, 0.0);
  std::vector<Vec3> d(m, Vec3::Zero());
  for (std::size_t i = 1; i + 1 < m; ++i) {
    const double h0 = ts[i] - ts[i - 1], h1 = ts[i + 1] - ts[i];
    const Vec3 rhs = 6 * ((xs[i + 1] - xs[i]) / h1 - (xs[i] - xs[i - 1]) / h0);
    const double diag = 2 * (h0 + h1) - h0 * c[i - 1];
    c[i] = h1 / diag;
    d[i] = (rhs - h0 * d[i - 1]) / diag;
  }
  for (std::size_t i = m - 2; i >= 1; --i) M[i] = d[i] - c[i] * M[i + 1];
  return M;
}

/// Track: natural cubic spline through (time, position), so velocity and
/// acceleration are continuous; straight-line extrapolation outside the table.
TowKinematics track(const TowPiece& p, double t) {
  const auto& ts = p.track_time;
  const auto& xs = p.track_pos;
  const std::size_t m = ts.size();
  TowKinematics k{xs.front(), Vec3::Zero(), Vec3::Zero()};
  if (m < 2) return k;
  const std::vector<Vec3> local = p.track_curv.size() == m ? std::vector<Vec3>{} : spline_curvatures(ts, xs);
  const std::vector<Vec3>& M = p.track_curv.size() == m ? p.track_curv : local;
  auto segment = [&](std::size_t i, double tt) {
    const double h = ts[i + 1] - ts[i];
    const double a = (ts[i + 1] - tt) / h, b = (tt - ts[i]) / h;
    TowKinematics s;
    s.pos = a * xs[i] + b * xs[i + 1] + ((a * a * a - a) * M[i] + (b * b * b - b) * M[i + 1]) * h * h / 6;
    s.vel = (xs[i + 1] - xs[i]) / h + ((1 - 3 * a * a) * M[i] + (3 * b * b - 1) * M[i + 1]) * h / 6;
    s.acc = a * M[i] + b * M[i + 1];
    return s;
  };
  if (t <= ts.front()) {
    TowKinematics s = segment(0, ts.front());
    return {s.pos + s.vel * (t - ts.front()), s.vel, Vec3::Zero()};
  }
  if (t >= ts.back()) {
    TowKinematics s = segment(m - 2, ts.back());
    return {s.pos + s.vel * (t - ts.back()), s.vel, Vec3::Zero()};
  }
  const std::size_t i = std::min<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin() - 1, m - 2);
  return segment(i, t);
}

/// Sum of every piece but the turn.
TowKinematics straight_path(const Tow& tow, double t) {
  TowKinematics k{tow.start, Vec3::Zero(), Vec3::Zero()};
  for (const auto& p : tow.pieces) {
    TowKinematics d{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    switch (p.type) {
      case TowPiece::Type::Ramp: d = ramp(p, t); break;
      case TowPiece::Type::Heave: d = heave(p, t); break;
      case TowPiece::Type::Track: d = track(p, t); break;
      case TowPiece::Type::Turn: break;
    }
    k.pos += d.pos;
    k.vel += d.vel;
    k.acc += d.acc;
  }
  return k;
}

}  // namespace

TowKinematics tow_kinematics(const Tow& tow, double t) {
  TowKinematics k = straight_path(tow, t);
  const auto turn = std::find_if(tow.pieces.begin(), tow.pieces.end(),
                                 [](const TowPiece& p) { return p.type == TowPiece::Type::Turn; });
  if (turn == tow.pieces.end() || t <= turn->start_time) return k;
  // Turn: leave the straight path tangentially on a circle at the horizontal
  // speed V reached at start_time; the vertical motion carries on unchanged.
  const TowKinematics s = straight_path(tow, turn->start_time);
  Vec3 vh(s.vel.x(), s.vel.y(), 0);
  const double V = vh.norm();
  if (V <= 0) return k;
  const Vec3 h = vh / V;                                            // heading
  const Vec3 n = turn->port ? Vec3(-h.y(), h.x(), 0) : Vec3(h.y(), -h.x(), 0);  // towards the centre
  const double R = turn->radius;
  const double phi = V * (t - turn->start_time) / R;
  const Vec3 ph = Vec3(s.pos.x(), s.pos.y(), 0) + R * (1 - std::cos(phi)) * n + R * std::sin(phi) * h;
  const Vec3 vv = V * (std::cos(phi) * h + std::sin(phi) * n);
  const Vec3 aa = V * V / R * (std::cos(phi) * n - std::sin(phi) * h);
  k.pos = Vec3(ph.x(), ph.y(), k.pos.z());
  k.vel = Vec3(vv.x(), vv.y(), k.vel.z());
  k.acc = Vec3(aa.x(), aa.y(), k.acc.z());
  return k;
}

void prepare_track(TowPiece& piece) {
  if (piece.type == TowPiece::Type::Track && piece.track_time.size() >= 2)
    piece.track_curv = spline_curvatures(piece.track_time, piece.track_pos);
}

std::vector<double> tow_breakpoints(const Tow& tow) {
  std::vector<double> out;
  for (const auto& p : tow.pieces) {
    if (p.type == TowPiece::Type::Ramp && p.ramp_time > 0) out.push_back(p.ramp_time);
    if (p.type == TowPiece::Type::Heave || p.type == TowPiece::Type::Turn) out.push_back(p.start_time);
    if (p.type == TowPiece::Type::Track && !p.track_time.empty()) {
      out.push_back(p.track_time.front());
      out.push_back(p.track_time.back());
    }
  }
  if (tow.mode == Tow::Mode::Force) out.insert(out.end(), tow.force_time.begin(), tow.force_time.end());
  std::erase_if(out, [](double t) { return !(t > 0); });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Vec3 tow_force(const Tow& tow, double t) {
  if (tow.force_value.empty()) return Vec3::Zero();
  return interpolate(tow.force_time, tow.force_value, t);
}

}  // namespace towsim
