// Vessel motion from RAOs or a measured record, and the tow point it carries
// (docs/theory.md "Ship motion").
#include "towsim/waves/vessel.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "towsim/model/spline.hpp"
#include "towsim/waves/vector_math.hpp"

namespace towsim {

std::atomic<std::uint64_t> Vessel::next_id_{0};

namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kRestSpeed = 1e-3;  // below this horizontal speed the course is course0 [m/s]

/// cross_matrix(a) b = a x b.
Mat3 cross_matrix(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

/// Phase difference b - a wrapped into (-180, 180] [deg].
double wrap180(double d) {
  d = std::fmod(d, 360.0);
  if (d > 180) d -= 360;
  if (d <= -180) d += 360;
  return d;
}

/// Bracketing interval and weight of x in increasing xs, held at the ends.
void bracket(const std::vector<double>& xs, double x, std::size_t& i0, std::size_t& i1, double& w) {
  if (xs.size() == 1 || !(x > xs.front())) {  // NaN too
    i0 = i1 = 0, w = 0;
    return;
  }
  if (x >= xs.back()) {
    i0 = i1 = xs.size() - 1, w = 0;
    return;
  }
  i1 = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  i0 = i1 - 1;
  w = (x - xs[i0]) / (xs[i1] - xs[i0]);
}

/// One variant per instruction set, chosen at start-up (GNU ifunc).
#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define TOWSIM_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define TOWSIM_VECTOR_CLONES
#endif

/// A long-crested sea's RAO terms at one heading weight (a straight course
/// keeps it), per dof j and harmonic i at index j nc + i: the amplitude
/// sign (A0 (1 - w) + A1 w) [m/m or rad/m times the wave's amplitude], its step
/// sign (A1 - A0) to the next heading, the lag step to it (0 at one heading)
/// [rad], the lag's cos and sin [-]; for the RAO vessel `id`.
struct RaoTerms {
  std::uint64_t id = 0;
  std::size_t h0 = 0, h1 = 0;
  double w = 0;
  std::vector<double> A, dA, dL, lc, ls;
};

/// The six motions x [m, rad], their rates v and accelerations a of the
/// terms T over harmonics comps[0..nc) at time t [s], the origin at distance
/// dx [m], speed dv [m/s] and acceleration da [m/s^2] along the waves, the
/// heading weight's rate wd [1/s]: per harmonic and dof the terms of
/// Vessel::motion, summed per dof in vecmath::kLanes lanes (this file is
/// compiled without fused multiply-adds: the same bits in every variant).
TOWSIM_VECTOR_CLONES void rao_sums(const RaoTerms& T, const WaveComponent* comps, std::size_t nc, double t, double dx,
                                   double dv, double da, double wd, double* x, double* v, double* a) {
  constexpr std::size_t kC = 32;  // harmonics per pass [-], a multiple of the lanes
  static_assert(kC % vecmath::kLanes == 0);
  // Phase [rad], its sin and cos, its rate [rad/s] and second rate [rad/s^2], the terms of x, v, a.
  std::array<double, kC> th, sth, cth, thd, thdd, tx, tv, ta;
  std::array<vecmath::Lanes, 6> X{}, V{}, A{};
  for (std::size_t b = 0; b < nc; b += kC) {
    const std::size_t m = std::min(kC, nc - b);
    const WaveComponent* c = comps + b;
    for (std::size_t l = 0; l < m; ++l) {
      th[l] = c[l].omega * t - c[l].k * dx - c[l].phase;
      thd[l] = c[l].omega - c[l].k * dv, thdd[l] = -c[l].k * da;
    }
    vecmath::sincos_n(m, th.data(), sth.data(), cth.data());
    for (std::size_t j = 0; j < 6; ++j) {
      const double *Aj = &T.A[j * nc + b], *dA = &T.dA[j * nc + b], *dL = &T.dL[j * nc + b];
      const double *Lc = &T.lc[j * nc + b], *Ls = &T.ls[j * nc + b];
      // cos(th - lag), sin(th - lag) by the angle sums.
      for (std::size_t l = 0; l < m; ++l) {
        const double Ad = wd * dA[l], phd = thd[l] - wd * dL[l];
        const double cs = cth[l] * Lc[l] + sth[l] * Ls[l], sn = sth[l] * Lc[l] - cth[l] * Ls[l];
        tx[l] = Aj[l] * cs;
        tv[l] = Ad * cs - Aj[l] * sn * phd;
        ta[l] = -2 * Ad * sn * phd - Aj[l] * (cs * phd * phd + sn * thdd[l]);
      }
      vecmath::accumulate(X[j], tx.data(), m), vecmath::accumulate(V[j], tv.data(), m);
      vecmath::accumulate(A[j], ta.data(), m);
    }
  }
  for (std::size_t j = 0; j < 6; ++j)
    x[j] = vecmath::total(X[j]), v[j] = vecmath::total(V[j]), a[j] = vecmath::total(A[j]);
}

}  // namespace

Vessel::Vessel(const Vec3& tow_point, double initial_course, std::shared_ptr<const WaveField> waves,
               const RaoTable& raos)
    : sheave_(tow_point),
      course0_(initial_course),
      waves_(std::move(waves)),
      headings_(raos.headings),
      id_(++next_id_) {
  mirror_ = raos.headings.back() <= 180;
  const std::size_t nh = raos.headings.size();
  const auto& comps = waves_->components;
  amp_.assign(comps.size() * nh * 6, 0.0);
  lag_.assign(amp_.size(), 0.0);
  for (std::size_t i = 0; i < comps.size(); ++i) {
    // Interpolate in the component's wave period, amplitude and (shortest-arc) phase.
    std::size_t p0, p1;
    double w;
    bracket(raos.periods, 2 * std::numbers::pi / comps[i].omega, p0, p1, w);
    for (std::size_t h = 0; h < nh; ++h)
      for (int d = 0; d < 6; ++d) {
        const double a = (1 - w) * raos.amp(d, h, p0) + w * raos.amp(d, h, p1);
        const double ph0 = raos.phase(d, h, p0);
        const double ph = ph0 + w * wrap180(raos.phase(d, h, p1) - ph0);
        const std::size_t j = (i * nh + h) * 6 + static_cast<std::size_t>(d);
        amp_[j] = a * comps[i].amplitude * (d >= 3 ? kDeg : 1.0);  // rotations to rad
        lag_[j] = ph * kDeg;
      }
  }
  // Lag differences to the next heading (the last one's: to the first, a periodic table).
  dlag_.assign(lag_.size(), 0.0);
  for (std::size_t i = 0; i < comps.size(); ++i)
    for (std::size_t h = 0; h < nh; ++h)
      for (std::size_t d = 0; d < 6; ++d) {
        const std::size_t j0 = (i * nh + h) * 6 + d, j1 = (i * nh + (h + 1) % nh) * 6 + d;
        dlag_[j0] = std::remainder(lag_[j1] - lag_[j0], 2 * std::numbers::pi);
      }
}

Vessel::Vessel(const Vec3& tow_point, double initial_course, std::shared_ptr<const WaveField> waves,
               std::vector<double> time, std::vector<Vec6> motions)
    : sheave_(tow_point),
      course0_(initial_course),
      waves_(std::move(waves)),
      time_(std::move(time)),
      rec_(std::move(motions)) {
  curv_ = natural_spline_curvatures(time_, rec_);
}

const Vessel::LagTable& Vessel::lag_table(std::size_t h0, std::size_t h1, double w) const {
  // One table per thread, for the last vessel and heading weight asked: a
  // straight course keeps its weight, so the table is computed once.
  thread_local LagTable table;
  if (table.id == id_ && table.h0 == h0 && table.h1 == h1 && table.w == w) return table;
  const std::size_t nh = headings_.size(), nc = amp_.size() / (6 * nh);
  table.cos.resize(nc * 6), table.sin.resize(nc * 6);
  for (std::size_t i = 0; i < nc; ++i)
    for (std::size_t j = 0; j < 6; ++j) {
      const std::size_t k = (i * nh + h0) * 6 + j;
      const double lag = lag_[k] + w * (h1 == h0 ? 0.0 : dlag_[k]);
      table.cos[i * 6 + j] = std::cos(lag), table.sin[i * 6 + j] = std::sin(lag);
    }
  table.id = id_, table.h0 = h0, table.h1 = h1, table.w = w;
  return table;
}

VesselMotion Vessel::motion(const TowKinematics& origin, double t, bool with_elevation) const {
  VesselMotion m;
  // Course from the horizontal velocity of the RAO origin; its rate (the
  // course's second derivative is not used, see tow_point).
  const double vx = origin.vel.x(), vy = origin.vel.y(), vh2 = vx * vx + vy * vy;
  m.course = course0_;
  if (vh2 > kRestSpeed * kRestSpeed) {
    m.course = std::atan2(vy, vx);
    m.course_rate = (vx * origin.acc.y() - vy * origin.acc.x()) / vh2;
  }
  if (waves_ && with_elevation) m.elevation = waves_->elevation(origin.pos, t);
  if (!time_.empty()) {  // measured record: natural cubic spline, held at the ends
    if (time_.size() == 1 || t <= time_.front()) {
      m.x = rec_.front();
    } else if (t >= time_.back()) {
      m.x = rec_.back();
    } else {
      const std::size_t i = static_cast<std::size_t>(std::upper_bound(time_.begin(), time_.end(), t) - time_.begin()) -
                            1;
      const double h = time_[i + 1] - time_[i], A = (time_[i + 1] - t) / h, B = 1 - A;
      const Vec6 &y0 = rec_[i], &y1 = rec_[i + 1], &M0 = curv_[i], &M1 = curv_[i + 1];
      m.x = A * y0 + B * y1 + ((A * A * A - A) * M0 + (B * B * B - B) * M1) * h * h / 6;
      m.v = (y1 - y0) / h - (3 * A * A - 1) / 6 * h * M0 + (3 * B * B - 1) / 6 * h * M1;
      m.a = A * M0 + B * M1;
    }
    return m;
  }
  // RAO superposition at the moving origin: Theta_i = omega_i t - k_i d.x_o - eps_i,
  // whose rate omega_i - k_i d.v_o is the encounter frequency.
  const WaveField& wf = *waves_;
  const Vec3& d = wf.direction;
  const double dx = d.x() * origin.pos.x() + d.y() * origin.pos.y();
  const double dv = d.x() * origin.vel.x() + d.y() * origin.vel.y();
  const double da = d.x() * origin.acc.x() + d.y() * origin.acc.y();
  // RAO heading weights for a travel direction dir: relative heading = wave
  // direction minus course, in [0, 360); mirrored into [0, 180] with sway,
  // roll and yaw reversed when the table is one-sided. Its rate beta' = -psi'.
  struct Weights {
    std::size_t h0 = 0, h1 = 0;
    double w = 0, wd = 0;  // interpolation weight in heading and its rate [1/s]
    double sign[6] = {1, 1, 1, 1, 1, 1};
  };
  const std::size_t nh = headings_.size();
  const auto weights = [&](double dir_x, double dir_y) {
    Weights q;
    double beta = std::fmod((std::atan2(dir_y, dir_x) - m.course) / kDeg, 360.0);
    if (beta < 0) beta += 360;
    double beta_rate = -m.course_rate / kDeg;  // [deg/s]
    if (mirror_ && beta > 180) {
      beta = 360 - beta;
      beta_rate = -beta_rate;
      q.sign[1] = q.sign[3] = q.sign[5] = -1;
    }
    if (!mirror_ && nh > 1 && (beta < headings_.front() || beta > headings_.back())) {
      // Periodic table: between the last heading and the first + 360.
      q.h0 = nh - 1, q.h1 = 0;
      const double span = headings_.front() + 360 - headings_.back();
      q.w = (beta < headings_.front() ? beta + 360 - headings_.back() : beta - headings_.back()) / span;
      q.wd = beta_rate / span;
    } else {
      bracket(headings_, beta, q.h0, q.h1, q.w);
      if (q.h1 != q.h0) q.wd = beta_rate / (headings_[q.h1] - headings_[q.h0]);
    }
    return q;
  };
  const Weights common = weights(d.x(), d.y());  // long-crested: one heading for all components
  const auto& comps = wf.components;
  constexpr std::size_t kChunk = 32, kTerms = kChunk * 6;  // harmonics, terms per pass [-]
  if (!wf.spread) {
    // Long-crested: one heading weight for every harmonic, so the lags' cos and
    // sin come from this thread's table for it (rao_sums: one sin and cos per harmonic).
    const LagTable& L = lag_table(common.h0, common.h1, common.w);
    // This thread's terms at the heading weight, for the last vessel and weight asked.
    thread_local RaoTerms T;
    const std::size_t nc = comps.size();
    if (!(T.id == id_ && T.h0 == common.h0 && T.h1 == common.h1 && T.w == common.w)) {
      for (auto* v : {&T.A, &T.dA, &T.dL, &T.lc, &T.ls}) v->resize(6 * nc);
      for (std::size_t i = 0; i < nc; ++i)
        for (std::size_t j = 0; j < 6; ++j) {
          const double A0 = amp_[(i * nh + common.h0) * 6 + j], A1 = amp_[(i * nh + common.h1) * 6 + j];
          const std::size_t k = j * nc + i;
          T.A[k] = common.sign[j] * ((1 - common.w) * A0 + common.w * A1);
          T.dA[k] = common.sign[j] * (A1 - A0);
          T.dL[k] = common.h1 == common.h0 ? 0.0 : dlag_[(i * nh + common.h0) * 6 + j];
          T.lc[k] = L.cos[i * 6 + j], T.ls[k] = L.sin[i * 6 + j];
        }
      T.id = id_, T.h0 = common.h0, T.h1 = common.h1, T.w = common.w;
    }
    rao_sums(T, comps.data(), nc, t, dx, dv, da, common.wd, m.x.data(), m.v.data(), m.a.data());
  }

  // Short-crested: per harmonic and motion the phase th - lag, its rate and the
  // amplitudes; the sin and cos of the phases in one vectorised pass per
  // chunk, summed in the order harmonic, then dof.
  std::array<double, kTerms> ph, sn, cs, A, Ad, phd, thdd;
  std::array<int, kTerms> dof;
  for (std::size_t b = 0; wf.spread && b < comps.size(); b += kChunk) {
    const std::size_t nc = std::min(kChunk, comps.size() - b);
    std::size_t n = 0;  // terms with a motion
    for (std::size_t i = b; i < b + nc; ++i) {
      const auto& c = comps[i];
      // Short-crested: each component at its own direction and relative heading.
      const Weights q = wf.spread ? weights(c.dx, c.dy) : common;
      const double cx = wf.spread ? c.dx * origin.pos.x() + c.dy * origin.pos.y() : dx;
      const double cv = wf.spread ? c.dx * origin.vel.x() + c.dy * origin.vel.y() : dv;
      const double ca = wf.spread ? c.dx * origin.acc.x() + c.dy * origin.acc.y() : da;
      const double th = c.omega * t - c.k * cx - c.phase, thd = c.omega - c.k * cv;
      const double* A0 = &amp_[(i * nh + q.h0) * 6];
      const double* A1 = &amp_[(i * nh + q.h1) * 6];
      const double* L0 = &lag_[(i * nh + q.h0) * 6];
      const double* D = &dlag_[(i * nh + q.h0) * 6];
      const double w = q.w, wd = q.wd;
      for (int j = 0; j < 6; ++j) {
        // A and the lag are linear in the heading weight w (A'' = lag'' = 0
        // within a table interval; beta'' = -psi'' is taken as 0, see tow_point).
        const double Aj = q.sign[j] * ((1 - w) * A0[j] + w * A1[j]);
        const double Adj = q.sign[j] * wd * (A1[j] - A0[j]);
        if (Aj == 0 && Adj == 0) continue;
        const double dL = q.h1 == q.h0 ? 0.0 : D[j];  // lag difference to the next heading, shorter arc
        ph[n] = th - (L0[j] + w * dL), phd[n] = thd - wd * dL, A[n] = Aj, Ad[n] = Adj, thdd[n] = -c.k * ca;
        dof[n++] = j;
      }
    }
    vecmath::sincos_n(n, ph.data(), sn.data(), cs.data());
    for (std::size_t e = 0; e < n; ++e) {
      const auto j = static_cast<Eigen::Index>(dof[e]);
      m.x[j] += A[e] * cs[e];
      m.v[j] += Ad[e] * cs[e] - A[e] * sn[e] * phd[e];
      m.a[j] += -2 * Ad[e] * sn[e] * phd[e] - A[e] * (cs[e] * phd[e] * phd[e] + sn[e] * thdd[e]);
    }
  }
  // Build-up: r xi, (r xi)' and (r xi)''.
  double r, rd, rdd;
  wf.ramp(t, r, rd, rdd);
  if (r != 1) {
    m.a = r * m.a + 2 * rd * m.v + rdd * m.x;
    m.v = r * m.v + rd * m.x;
    m.x = r * m.x;
  }
  return m;
}

TowKinematics Vessel::tow_point(const TowKinematics& origin, double t) const {
  const VesselMotion m = motion(origin, t, false);
  // Sheave in vessel axes: s = r_s + xi + theta x r_s (small angles, linear in
  // the motions), theta = (roll, -pitch, yaw) about (x, y, z): pitch + = bow up.
  const auto theta = [](const Vec6& x) { return Vec3(x[3], -x[4], x[5]); };
  Vec3 s = sheave_ + m.x.head<3>() + theta(m.x).cross(sheave_);
  Vec3 sd = m.v.head<3>() + theta(m.v).cross(sheave_);
  Vec3 sdd = m.a.head<3>() + theta(m.a).cross(sheave_);
  if (exact_) {
    // R = A B C = Rz(q2) Ry(q1) Rx(q0), q = theta; each factor E about axis e:
    // dE/dt = [e]x E q', d2E/dt2 = ([e]x^2 q'^2 + [e]x q'') E.
    const Vec3 q = theta(m.x), qd = theta(m.v), qdd = theta(m.a);
    Mat3 E[3], Ed[3], Edd[3];
    for (int i = 0; i < 3; ++i) {
      const Mat3 S = cross_matrix(Vec3::Unit(i));
      E[i] = Eigen::AngleAxisd(q[i], Vec3::Unit(i)).toRotationMatrix();
      Ed[i] = S * E[i] * qd[i];
      Edd[i] = (S * S * qd[i] * qd[i] + S * qdd[i]) * E[i];
    }
    const Mat3 R = E[2] * E[1] * E[0];
    const Mat3 Rd = Ed[2] * E[1] * E[0] + E[2] * Ed[1] * E[0] + E[2] * E[1] * Ed[0];
    const Mat3 Rdd = Edd[2] * E[1] * E[0] + E[2] * Edd[1] * E[0] + E[2] * E[1] * Edd[0] +
                     2 * (Ed[2] * Ed[1] * E[0] + Ed[2] * E[1] * Ed[0] + E[2] * Ed[1] * Ed[0]);
    s = m.x.head<3>() + R * sheave_;
    sd = m.v.head<3>() + Rd * sheave_;
    sdd = m.a.head<3>() + Rdd * sheave_;
  }
  // Turned to the course psi about z; with psi' the course rate (psi'' = 0:
  // exact on straight legs and steady turns, see docs/theory.md).
  const Mat3 Rz = Eigen::AngleAxisd(m.course, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 W(0, 0, m.course_rate);
  const Vec3 r = Rz * s, rd = Rz * sd;
  TowKinematics k;
  k.pos = origin.pos + r;
  k.vel = origin.vel + W.cross(r) + rd;
  k.acc = origin.acc + W.cross(W.cross(r)) + 2 * W.cross(rd) + Rz * sdd;
  return k;
}

double initial_course(const Tow& tow) {
  for (double t : {1e-6, 1.0}) {
    const Vec3 v = tow_law_kinematics(tow, t).vel;
    if (std::hypot(v.x(), v.y()) > 0) return std::atan2(v.y(), v.x());
  }
  return 0;
}

TowKinematics tow_kinematics(const Tow& tow, double t) {
  const TowKinematics k = tow_law_kinematics(tow, t);
  return tow.vessel ? tow.vessel->tow_point(k, t) : k;
}

TowKinematics tow_kinematics(const Tow& tow, double t, CourseCursor& cursor) {
  TowKinematics k = tow_law_kinematics(tow, t, cursor);  // not const: returned as is without a vessel
  if (!tow.vessel) return k;
  // The same vessel, time and law as the last call: the same tow point.
  const auto same = [](const TowKinematics& a, const TowKinematics& b) {
    return a.pos == b.pos && a.vel == b.vel && a.acc == b.acc;
  };
  if (cursor.vessel.get() == tow.vessel.get() && cursor.vessel_t == t && same(cursor.vessel_law, k))
    return cursor.vessel_point;
  cursor.vessel_point = tow.vessel->tow_point(k, t);
  if (cursor.vessel.get() != tow.vessel.get()) cursor.vessel = tow.vessel;
  cursor.vessel_t = t, cursor.vessel_law = k;
  return cursor.vessel_point;
}

}  // namespace towsim

namespace towsim {

void sea_sample(const Model& model, double t, Sample& out) {
  out.has_waves = true;
  const Vessel* v = model.tow.vessel.get();
  if (v == nullptr || model.tow.mode != Tow::Mode::Motion) {
    out.wave_elevation = model.fluid.waves ? model.fluid.waves->elevation(out.tow_pos, t) : 0.0;
    return;
  }
  const TowKinematics law = tow_law_kinematics(model.tow, t);
  const VesselMotion m = v->motion(law, t);
  out.wave_elevation = m.elevation;
  out.tow_wave = out.tow_pos - (law.pos + Eigen::AngleAxisd(m.course, Vec3::UnitZ()) * v->sheave());
}

}  // namespace towsim
