// Tow law `track` (include/towsim/tow/track.hpp).
#include "towsim/tow/track.hpp"

#include <algorithm>

#include "towsim/model/spline.hpp"

namespace towsim {

Track Track::make(std::vector<double> time, std::vector<Vec3> pos) {
  Track tr;
  tr.time = std::move(time);
  tr.pos = std::move(pos);
  tr.prepare();
  return tr;
}

void Track::prepare() {
  if (time.size() >= 2) curv = natural_spline_curvatures(time, pos);
}

TowKinematics Track::at(double t) const {
  const auto& ts = time;
  const auto& xs = pos;
  const std::size_t m = ts.size();
  TowKinematics k{xs.front(), Vec3::Zero(), Vec3::Zero()};
  if (m < 2) return k;
  const std::vector<Vec3> local = curv.size() == m ? std::vector<Vec3>{} : natural_spline_curvatures(ts, xs);
  const std::vector<Vec3>& M = curv.size() == m ? curv : local;
  auto segment = [&](std::size_t i, double tt) {
    const double h = ts[i + 1] - ts[i];
    const double a = (ts[i + 1] - tt) / h, b = (tt - ts[i]) / h;
    TowKinematics s;
    s.pos = a * xs[i] + b * xs[i + 1] + ((a * a * a - a) * M[i] + (b * b * b - b) * M[i + 1]) * h * h / 6;
    s.vel = (xs[i + 1] - xs[i]) / h + ((1 - 3 * a * a) * M[i] + (3 * b * b - 1) * M[i + 1]) * h / 6;
    s.acc = a * M[i] + b * M[i + 1];
    return s;
  };
  // Outside the table: straight on at the end velocity.
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

void Track::breakpoints(std::vector<double>& out) const {
  if (time.empty()) return;
  out.push_back(time.front());
  out.push_back(time.back());
}

}  // namespace towsim
