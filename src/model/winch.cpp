// The winch's imposed deployed-length schedule (docs/theory.md "Winch").
#include "towsim/model/winch.hpp"

#include <algorithm>
#include <cmath>

namespace towsim {

WinchKinematics winch_kinematics(const Winch& w, double t) {
  if (w.schedule.empty()) return {};
  // The last piece starting at or before t.
  auto it = std::upper_bound(w.schedule.begin(), w.schedule.end(), t,
                             [](double x, const WinchPiece& p) { return x < p.t0; });
  const WinchPiece& p = it == w.schedule.begin() ? *it : *(it - 1);
  const double tau = std::max(0.0, t - p.t0);
  return {p.L0 + p.rate * tau + 0.5 * p.acc * tau * tau, p.rate + p.acc * tau, p.acc};
}

WinchKinematics winch_kinematics_before(const Winch& w, double t) {
  if (w.schedule.empty()) return {};
  // The last piece starting strictly before t.
  auto it = std::lower_bound(w.schedule.begin(), w.schedule.end(), t,
                             [](const WinchPiece& p, double x) { return p.t0 < x; });
  const WinchPiece& p = it == w.schedule.begin() ? *it : *(it - 1);
  const double tau = std::max(0.0, t - p.t0);
  return {p.L0 + p.rate * tau + 0.5 * p.acc * tau * tau, p.rate + p.acc * tau, p.acc};
}

std::vector<double> winch_breakpoints(const Winch& w) {
  std::vector<double> out;
  if (w.mode != Winch::Mode::Imposed) return out;
  for (const WinchPiece& p : w.schedule)
    if (p.t0 > 0) out.push_back(p.t0);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

/// Smallest tau in (0, tmax) where L0 + r tau + s tau^2 / 2 = target, or -1.
double first_hit(double L0, double r, double s, double target, double tmax) {
  const double c = L0 - target;
  double best = -1;
  auto consider = [&](double tau) {
    if (tau > 1e-12 && tau < tmax && (best < 0 || tau < best)) best = tau;
  };
  if (s == 0) {
    if (r != 0) consider(-c / r);
    return best;
  }
  const double disc = r * r - 2 * s * c;
  if (disc < 0) return best;
  const double sq = std::sqrt(disc);
  consider((-r - sq) / s);
  consider((-r + sq) / s);
  return best;
}

}  // namespace

std::vector<WinchPiece> schedule_from_rate(const std::vector<double>& t, const std::vector<double>& rate, double L0,
                                           double min_length, double max_length) {
  // Segments of linear rate: [start, end), rate r_a at start, slope s.
  struct Segment {
    double start, end, r, s;
  };
  std::vector<Segment> segs;
  const double inf = std::numeric_limits<double>::infinity();
  if (t.size() <= 1) {
    segs.push_back({0, inf, rate.front(), 0});
  } else {
    if (t.front() > 0) segs.push_back({0, t.front(), rate.front(), 0});
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
      if (t[i + 1] <= 0) continue;
      const double s = (rate[i + 1] - rate[i]) / (t[i + 1] - t[i]);
      const double a = std::max(0.0, t[i]);
      segs.push_back({a, t[i + 1], rate[i] + s * (a - t[i]), s});
    }
    segs.push_back({std::max(0.0, t.back()), inf, rate.back(), 0});
  }
  // Walk the segments: free pieces follow the rate; at a limit the winch
  // stops until the rate turns back.
  std::vector<WinchPiece> out;
  double L = L0;
  int stopped = 0;  // -1 at min_length, +1 at max_length, 0 free
  for (const Segment& g : segs) {
    double a = g.start;
    double r = g.r;
    while (a < g.end) {
      if (stopped != 0) {
        // Resume where the rate points back inside.
        const bool back = stopped > 0 ? (r < 0 || (r == 0 && g.s < 0)) : (r > 0 || (r == 0 && g.s > 0));
        if (!back) {
          const double tau0 = g.s != 0 ? -r / g.s : -1;
          if (!(tau0 > 0 && a + tau0 < g.end)) break;  // stopped through this segment
          r = 0;
          a += tau0;
          if (!((stopped > 0 && g.s < 0) || (stopped < 0 && g.s > 0))) break;
        }
        stopped = 0;
      }
      // At a limit with the rate pointing out: stop there.
      const bool out_max = L >= max_length - 1e-9 && (r > 0 || (r == 0 && g.s > 0));
      const bool out_min = L <= min_length + 1e-9 && (r < 0 || (r == 0 && g.s < 0));
      if (out_max || out_min) {
        stopped = out_max ? 1 : -1;
        out.push_back({a, L, 0, 0});
        continue;
      }
      out.push_back({a, L, r, g.s});
      // Does the length reach a limit on this segment?
      const double span = g.end - a;
      double hit = -1;
      int which = 0;
      for (int side : {-1, 1}) {
        const double lim = side < 0 ? min_length : max_length;
        if (!std::isfinite(lim)) continue;
        const double h = first_hit(L, r, g.s, lim, span);
        if (h > 0 && (hit < 0 || h < hit)) hit = h, which = side;
      }
      if (hit < 0) {
        if (std::isfinite(span)) L += r * span + 0.5 * g.s * span * span, r += g.s * span;
        a = g.end;
        break;
      }
      a += hit;
      r += g.s * hit;
      L = which < 0 ? min_length : max_length;
      stopped = which;
      out.push_back({a, L, 0, 0});
    }
    if (stopped != 0 && (out.empty() || out.back().rate != 0 || out.back().acc != 0))
      out.push_back({std::max(a, g.start), L, 0, 0});
  }
  // Drop pieces of zero duration (keep the later one).
  std::vector<WinchPiece> clean;
  for (const WinchPiece& p : out) {
    if (!clean.empty() && p.t0 <= clean.back().t0 + 1e-12) clean.pop_back();
    clean.push_back(p);
  }
  return clean;
}

std::vector<WinchPiece> schedule_from_length(const std::vector<double>& t, const std::vector<double>& L) {
  std::vector<WinchPiece> out;
  if (t.size() <= 1) return {{0, L.front(), 0, 0}};
  if (t.front() > 0) out.push_back({0, L.front(), 0, 0});
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i + 1] <= 0) continue;
    const double rate = (L[i + 1] - L[i]) / (t[i + 1] - t[i]);
    const double a = std::max(0.0, t[i]);
    out.push_back({a, L[i] + rate * (a - t[i]), rate, 0});
  }
  out.push_back({std::max(0.0, t.back()), L.back(), 0, 0});
  return out;
}

}  // namespace towsim
