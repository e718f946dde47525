// Why towsim and the earlier formulation (bench/baseline) differ on paper
// 5.1 law B (docs/performance.md, "tow laws with a velocity jump").
//
// Law B's `heave` piece starts at t = 15 s with its full vertical speed, so the
// tow point's velocity jumps. Three versions of the same heave, each run by
// towsim (dopri5, tol 1e-10, Morison added mass) and by the baseline (central
// differences, h = 1e-3 s); the tow-force difference is printed:
//   1. the `heave` piece (velocity jump at 15 s);
//   2. the same sine through a `track` piece (a natural cubic spline through
//      samples every 0.25 s: the corner at 15 s is rounded, velocity continuous);
//   3. a C1 heave, A (1 - cos), through a `track` piece.
// If the two agree in 2 and 3 but not in 1, the difference is the handling of
// the velocity jump, not the dynamics.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "baseline/cartesian.hpp"
#include "towsim/sim/simulate.hpp"

namespace {

using namespace towsim;

enum class HeaveKind { Piece, TrackSine, TrackOneMinusCos };

Model model(HeaveKind kind) {
  Model m;
  m.cable.added_mass_model = AddedMassModel::Morison;
  for (int i = 0; i < 5; ++i)
    m.cable.elements.push_back(make_element(20.0, 1.5, 0.019, 1.8, 0.0, TangentialLaw::Pode, 1.0, m.fluid));
  m.bodies.emplace_back();
  Body& b = m.bodies.back();
  b.mass = 134.1721862471;
  b.inertia_cg = Vec3(3.354304656, 78.82615942, 78.82615942).asDiagonal();
  b.cg = Vec3(-0.75, 0, 0);
  b.link_point = Vec3::Zero();
  b.spheres.push_back({Vec3(0, 0, 0), 0.25, 0.5, 0.5});
  b.spheres.push_back({Vec3(-1.5, 0, 0), 0.25, 0.5, 0.5});
  finalize_body(b, m.fluid);
  m.tow.pieces.push_back(Ramp{Vec3(1, 0, 0), 2.0, 15.0});
  if (kind == HeaveKind::Piece) {
    m.tow.pieces.push_back(Heave{1.0, 10.0, 15.0});
  } else {
    Track tr;
    for (double t = 0; t <= 121; t += 0.25) {
      const double ph = 2 * std::numbers::pi * (t - 15) / 10;
      const double z = t <= 15 ? 0 : (kind == HeaveKind::TrackSine ? std::sin(ph) : 1 - std::cos(ph));
      tr.time.push_back(t);
      tr.pos.push_back(Vec3(0, 0, z));
    }
    m.tow.pieces.push_back(tr);
  }
  m.sim.duration = 120;
  m.sim.write_nodes = false;
  m.sim.integrator = Integrator::DOPRI5;
  m.sim.tolerance = 1e-10;
  m.sim.output_interval = 0.5;
  return m;
}

}  // namespace

int main() {
  const char* names[] = {"heave piece (velocity jump at 15 s)", "sine through a track (spline, C2)",
                         "1 - cos through a track (C2)"};
  std::printf(
      "tow force, baseline (h = 1e-3 s) vs towsim (dopri5 1e-10), relative to max |F_ref|, t = 0.5 ... "
      "119.5 s except 15 s\n");
  for (HeaveKind kind : {HeaveKind::Piece, HeaveKind::TrackSine, HeaveKind::TrackOneMinusCos}) {
    const Model m = model(kind);
    MemorySink sink;
    simulate(m, sink, {});
    baseline::Chain c = baseline::cable_chain(m);
    baseline::add_dumbbell(c, 134.1721862471 / 2, 0.25, 0.5, 0.5, 1.5);
    std::vector<Vec3> x(c.joints(), Vec3::Zero());
    for (int k = 1; k <= 5; ++k) x[k] = x[k - 1] - 20 * Vec3::UnitZ();
    x[6] = x[5] + Vec3(-1.5, 0, 0);
    const double h = 1e-3;
    baseline::CentralDifference cd(c, h);
    cd.start(x);
    double emax = 0, fmax = 0, e30 = 0, e60 = 0, tmax = 0;
    std::size_t j = 0;
    for (long k = 0; k < 120000; ++k) {
      cd.step();  // tow force at t_k
      if (k % 500 != 0) continue;
      const double t = k * h;
      const Vec3 fr = sink.samples[j++].tow_force;
      fmax = std::max(fmax, fr.norm());
      if (k == 0 || std::abs(t - 15) < 1e-9) continue;
      const double e = (cd.tow_force() - fr).norm();
      if (e > emax) emax = e, tmax = t;
      if (t >= 30) e30 = std::max(e30, e);
      if (t >= 60) e60 = std::max(e60, e);
    }
    std::printf("%-38s max %.2e at t = %.1f s; t >= 30 s: %.2e; t >= 60 s: %.2e\n", names[static_cast<int>(kind)],
                emax / fmax, tmax, e30 / fmax, e60 / fmax);
  }
  return 0;
}
