// A body's balance in the steady tow (docs/theory.md §7 "Sweeps",
// "Equilibria of a body"): Newton on its attitude, the trim starts, and the
// classification of its balances by their restoring stiffness.
#include <algorithm>
#include <cmath>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim::statics {

/// A body's steady kinematics and loads at attitude q hanging from Q, all
/// moving at V without rotating (as compute_kinematics and compute_loads).
void steady_body(const Model& m, const Body& body, const Quat& q, const Vec3& Q, const Vec3& V, BodyWork& bw) {
  bw.R = q.toRotationMatrix();
  bw.w.setZero();
  bw.Q = Q;
  bw.vQ = V;
  bw.rQ = bw.R * body.link_point;
  bw.O = Q - bw.rQ;
  bw.vO = V;
  bw.rQ2 = bw.R * body.lower_link_point;
  body_inertia(m.fluid, body, bw, 0.0);
  body_loads(m.fluid, body, 0.0, bw);
}

/// The body's moment balance about its link Q with the cable below pulling
/// f2 at Q2 (in-line bodies): the recursion's rhs at zero acceleration [N m].
Vec3 body_moment(const Body& body, const BodyWork& bw, const Vec3& f2) {
  const Vec3 hl = bw.hw.head<3>(), ha = bw.hw.tail<3>();
  Vec3 r = bw.Mb - bw.rQ.cross(bw.Fb) - ha + bw.rQ.cross(hl);
  if (body.inline_body) r += bw.rQ.cross(f2) - bw.rQ2.cross(f2);
  return r;
}

/// The size of the moments in the body's balance at bw: of each load's moment about Q [N m].
double body_moment_scale(const BodyWork& bw, const Vec3& f2) {
  return bw.Mb.norm() + bw.rQ.norm() * (bw.Fb.norm() + bw.hw.head<3>().norm() + f2.norm()) + bw.hw.tail<3>().norm() +
         bw.rQ2.norm() * f2.norm() + 1e-300;
}

/// Body attitude balancing its moments about Q, from q: Newton with
/// minimum-norm steps (a sphere's rotation about its link line is neutral).
/// On return bw holds the body at q; false when no balance was found.
bool newton_body(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2, Quat& q,
                 BodyWork& bw) {
  BodyWork tmp = bw;
  auto rotated = [&q](const Vec3& x) {
    return x.norm() > 0 ? Quat((Quat(Eigen::AngleAxisd(x.norm(), x.normalized())) * q).normalized()) : q;
  };
  for (int it = 0; it < 100; ++it) {
    steady_body(m, body, q, Q, V, bw);
    const Vec3 g = body_moment(body, bw, f2);
    const double scale = body_moment_scale(bw, f2);
    if (g.norm() <= kLocalTolerance * scale) return true;
    constexpr double h = 1e-7;  // [rad]
    Mat3 J;
    for (int j = 0; j < 3; ++j) {
      steady_body(m, body, rotated(h * Vec3::Unit(j)), Q, V, tmp);
      const Vec3 gp = body_moment(body, tmp, f2);
      steady_body(m, body, rotated(-h * Vec3::Unit(j)), Q, V, tmp);
      J.col(j) = (gp - body_moment(body, tmp, f2)) / (2 * h);
    }
    // Damped least squares: a neutral rotation (J's null space) takes no step.
    Mat3 A = J.transpose() * J;
    A.diagonal().array() += 1e-10 * A.diagonal().maxCoeff() + 1e-300;
    Vec3 dx = A.ldlt().solve(-J.transpose() * g);
    if (!dx.allFinite()) return false;
    if (dx.norm() > 0.3) dx *= 0.3 / dx.norm();
    bool better = false;
    for (int ls = 0; ls < 30 && !better; ++ls, dx *= 0.5) {
      steady_body(m, body, rotated(dx), Q, V, tmp);
      if (body_moment(body, tmp, f2).norm() < g.norm()) q = rotated(dx), better = true;
    }
    if (!better) {
      steady_body(m, body, q, Q, V, bw);
      return g.norm() <= 1e3 * kLocalTolerance * scale;
    }
  }
  steady_body(m, body, q, Q, V, bw);  // bw at the best attitude found
  return false;
}

constexpr double kStiffnessStep = 1e-5;  // [rad] central differences of the moment about Q: truncation
                                         // ~1e-10, round-off ~1e-11 of its scale
constexpr double kNeutral = 1e-6;        // an eigenvalue of K's symmetric part below -kNeutral times the
                                         // moment scale (per radian) is unstable; above, zero to round-off

/// The body's balance at q classified: its restoring stiffness K = -dM/dtheta
/// (rotations theta in R_g, central differences), the diagonal of K in body
/// axes and the smallest eigenvalue of K's symmetric part; stable when that
/// eigenvalue is not below -kNeutral of the moment scale. bw: a copy of the
/// body's work (its control surfaces' state). `neutral` (may be null): the
/// rotation axes (R_g) of eigenvalues within that band.
BodyEquilibrium classify_balance(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2,
                                 const Quat& q, BodyWork bw, std::vector<Vec3>* neutral) {
  steady_body(m, body, q, Q, V, bw);
  const double scale = body_moment_scale(bw, f2);
  Mat3 K;
  for (int j = 0; j < 3; ++j) {
    steady_body(m, body, Quat(Eigen::AngleAxisd(kStiffnessStep, Vec3::Unit(j)) * q).normalized(), Q, V, bw);
    const Vec3 gp = body_moment(body, bw, f2);
    steady_body(m, body, Quat(Eigen::AngleAxisd(-kStiffnessStep, Vec3::Unit(j)) * q).normalized(), Q, V, bw);
    K.col(j) = -(gp - body_moment(body, bw, f2)) / (2 * kStiffnessStep);
  }
  const Mat3 R = q.toRotationMatrix();
  const Mat3 Kb = R.transpose() * K * R;  // in body axes
  const Eigen::SelfAdjointEigenSolver<Mat3> sym(0.5 * (K + K.transpose()));
  BodyEquilibrium e;
  e.q = q;
  e.rpy_deg = roll_pitch_yaw(q) * (180.0 / M_PI);
  e.stiffness = Kb.diagonal();
  e.min_stiffness = sym.eigenvalues()[0];
  e.stable = e.min_stiffness >= -kNeutral * scale;
  if (neutral != nullptr)
    for (int i = 0; i < 3; ++i)
      if (std::abs(sym.eigenvalues()[i]) < kNeutral * scale) neutral->push_back(sym.eigenvectors().col(i));
  return e;
}

/// The trims newton_body restarts from: pitched -75..75 deg in steps of 15 deg, level in the tow's heading.
std::vector<Quat> trim_starts(const Vec3& V) {
  const Quat heading(Eigen::AngleAxisd(std::hypot(V.x(), V.y()) > 0 ? std::atan2(V.y(), V.x()) : 0.0, Vec3::UnitZ()));
  std::vector<Quat> out;
  for (int deg = -75; deg <= 75; deg += 15)
    out.push_back((heading * Quat(Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitY()))).normalized());
  return out;
}

/// newton_body from q, else from several trims (trim_starts). Newton from
/// the attitude a body held may not reach a balance far from it
/// (two-part-tow's depressor flies nose up below about 560 kg, 24 deg at
/// 500 kg, from a level start), or may reach a statically unstable one: a
/// stable balance from q is kept; otherwise the stable balance from the
/// trims nearest q, or when none is stable, the (unstable) balance from q,
/// or when Newton from q found none, the balance from the trims nearest q.
bool solve_body(const Model& m, const Body& body, const Vec3& Q, const Vec3& V, const Vec3& f2, Quat& q, BodyWork& bw) {
  const Quat start = q;
  const bool held = newton_body(m, body, Q, V, f2, q, bw);
  if (held && classify_balance(m, body, Q, V, f2, q, bw).stable) return true;
  const Quat from_start = q;
  const BodyWork at_start = bw;  // the best attitude from q, kept when no start balances
  bool found = held, found_stable = false;
  double nearest = held ? q.angularDistance(start) : 0.0;  // angle from q to the balance kept [rad]
  BodyWork trial = bw;
  for (Quat t : trim_starts(V)) {
    if (!newton_body(m, body, Q, V, f2, t, trial)) continue;
    const bool stable = classify_balance(m, body, Q, V, f2, t, trial).stable;
    const double angle = t.angularDistance(start);
    // A stable balance beats an unstable one; then the nearer.
    if (!found || (stable && !found_stable) || (stable == found_stable && angle < nearest)) {
      found = true;
      found_stable = stable;
      nearest = angle;
      q = t;
      bw = trial;
    }
  }
  if (!found || (held && !found_stable)) {
    q = from_start;
    bw = at_start;
  }
  return found;
}

/// The balances of each body at the equilibrium `state` of `m` (waves off,
/// the steady tow), its links' places in ws (forward_dynamics at state) and
/// the in-line bodies' forces on the cable below `below` (StaticsResult's
/// equilibria).
std::vector<BodyEquilibria> find_equilibria(const Model& m, const PhysicalState& state, const Workspace& ws,
                                            const Vec3& V, const std::vector<Vec3>& below) {
  std::vector<BodyEquilibria> out(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    const Vec3 Q = ws.body[b].Q;
    const Vec3 f2 = body.inline_body ? below[b] : Vec3::Zero();
    const Quat solved = state.bodies[b].q;
    if (m.seabed &&
        m.seabed->gap(Q) < body_drop(*m.seabed, body, solved.toRotationMatrix(), Q, m.seabed->normal(Q.x())))
      continue;  // on the bottom: the contact is not part of steady_body's balance
    BodyEquilibria& eq = out[b];
    eq.analysed = true;
    std::vector<std::vector<Vec3>> neutral;  // each balance's neutral rotation axes
    auto add = [&](const Quat& q) {
      for (std::size_t i = 0; i < eq.balances.size(); ++i) {
        Eigen::AngleAxisd d(q * eq.balances[i].q.conjugate());
        Vec3 r = d.angle() * d.axis();
        if (d.angle() > M_PI) r = (d.angle() - 2 * M_PI) * d.axis();
        for (const Vec3& a : neutral[i]) r -= a.dot(r) * a;  // rotations along a neutral axis: the same balance
        if (r.norm() <= kDistinctBalance) return;
      }
      neutral.emplace_back();
      eq.balances.push_back(classify_balance(m, body, Q, V, f2, q, ws.body[b], &neutral.back()));
    };
    add(solved);  // the balance of the equilibrium solved: index 0 until sorted
    BodyWork bw = ws.body[b];
    for (Quat t : trim_starts(V))
      if (newton_body(m, body, Q, V, f2, t, bw)) add(t);
    std::vector<std::size_t> order(eq.balances.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
      return eq.balances[i].rpy_deg.y() > eq.balances[j].rpy_deg.y();
    });
    std::vector<BodyEquilibrium> sorted;
    for (std::size_t i = 0; i < order.size(); ++i) {
      sorted.push_back(eq.balances[order[i]]);
      if (order[i] == 0) eq.chosen = static_cast<int>(i);
    }
    eq.balances = std::move(sorted);
  }
  return out;
}

}  // namespace towsim::statics
