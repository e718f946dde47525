// Checking `waves:` and `vessel:` and building the WaveField and Vessel
// (INTERFACE.md "Ship motion from waves").
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "checks.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim::scenario {
namespace {

constexpr long long kMaxComponents = 100000;  // waves.spectrum.components
const char* const kDofNames[6] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};

/// A heading in [0, 360): -90 -> 270, 360 -> 0 [deg].
double normal_heading(double h) {
  double n = std::fmod(h, 360.0);
  if (n < 0) n += 360;
  return n == 360 ? 0.0 : n;
}

/// The rows that make the table: headings normalised to [0, 360); a row
/// written at another turn of the same heading (360 for 0, -90 for 270) is
/// dropped when that heading is also given as such.
std::vector<RaoRowSpec> table_rows(const VesselSpec& v) {
  std::vector<RaoRowSpec> out;
  std::map<std::tuple<int, double, double>, bool> plain;
  for (const auto& r : v.raos)
    if (normal_heading(r.heading) == r.heading) plain[std::make_tuple(r.dof, r.period, r.heading)] = true;
  for (RaoRowSpec r : v.raos) {
    const double n = normal_heading(r.heading);
    if (n != r.heading && plain.count(std::make_tuple(r.dof, r.period, n))) continue;
    r.heading = n;
    out.push_back(r);
  }
  return out;
}

/// Sorted distinct values.
std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

void check_raos(const VesselSpec& v, Diagnostics& d) {
  bool rows_ok = true;
  for (const auto& r : v.raos) {
    const std::string& p = r.where.path;
    if (!(r.period > 0)) d.error(r.where.loc, p, "period must be > 0 (got " + fmt_num(r.period) + ")"), rows_ok = false;
    if (!(r.heading >= -360 && r.heading <= 360))
      d.error(r.where.loc, p, "heading_deg must be in [-360, 360] (got " + fmt_num(r.heading) + ")"), rows_ok = false;
    if (!(r.amplitude >= 0))
      d.error(r.where.loc, p, "amplitude must be >= 0 (got " + fmt_num(r.amplitude) + ")"), rows_ok = false;
  }
  if (!rows_ok || v.raos.empty()) return;
  // A full grid of periods x headings for every dof given, no duplicates.
  std::map<std::tuple<int, double, double>, const RaoRowSpec*> seen;
  std::vector<double> periods, headings;
  std::vector<bool> dofs(6, false);
  const std::vector<RaoRowSpec> rows = table_rows(v);
  for (const auto& r : rows) {
    periods.push_back(r.period), headings.push_back(r.heading), dofs[static_cast<std::size_t>(r.dof)] = true;
    if (!seen.emplace(std::make_tuple(r.dof, r.period, r.heading), &r).second)
      d.error(r.where.loc, r.where.path,
              std::string("duplicate row for ") + kDofNames[r.dof] + " at period " + fmt_num(r.period) + ", heading " +
                  fmt_num(r.heading));
  }
  periods = distinct(periods), headings = distinct(headings);
  for (int k = 0; k < 6; ++k) {
    if (!dofs[static_cast<std::size_t>(k)]) continue;
    for (double p : periods)
      for (double h : headings)
        if (!seen.count(std::make_tuple(k, p, h))) {
          d.error(v.raos_where.loc, v.raos_where.path,
                  std::string("no row for ") + kDofNames[k] + " at period " + fmt_num(p) + ", heading " + fmt_num(h) +
                      " (each dof given needs every period x heading of the table)");
          return;
        }
  }
}

RaoTable build_raos(const VesselSpec& v) {
  RaoTable t;
  const std::vector<RaoRowSpec> rows = table_rows(v);
  for (const auto& r : rows) t.periods.push_back(r.period), t.headings.push_back(r.heading);
  t.periods = distinct(t.periods), t.headings = distinct(t.headings);
  t.amplitude.assign(6 * t.periods.size() * t.headings.size(), 0.0);  // a dof not given is zero
  t.phase_deg.assign(t.amplitude.size(), 0.0);
  for (const auto& r : rows) {
    const auto p = static_cast<std::size_t>(std::lower_bound(t.periods.begin(), t.periods.end(), r.period) -
                                            t.periods.begin());
    const auto h = static_cast<std::size_t>(std::lower_bound(t.headings.begin(), t.headings.end(), r.heading) -
                                            t.headings.begin());
    t.amplitude[t.index(r.dof, h, p)] = r.amplitude;
    t.phase_deg[t.index(r.dof, h, p)] = r.phase;
  }
  return t;
}

}  // namespace

void check_waves(const ScenarioSpec& s, Diagnostics& d) {
  const WavesSpec& w = s.waves;
  if (w.present) {
    if (w.regular) {
      check_positive(w.height, d);
      check_positive(w.period, d);
    } else {
      check_positive(w.hs, d);
      check_positive(w.tp, d);
      if (w.gamma.given && !(w.gamma.value >= 1))
        d.error(w.gamma.where.loc, w.gamma.where.path, "must be >= 1 (got " + fmt_num(w.gamma.value) + ")");
      check_at_least(w.components, 1, d);
      check_at_most(w.components, kMaxComponents, d);
      check_at_least(w.seed, 0, d);
      if (w.spreading.given) check_positive(w.spreading, d);
    }
    if (w.water_depth.given) check_positive(w.water_depth, d);
    if (w.statistics_start.given) check_non_negative(w.statistics_start, d);
    check_non_negative(w.ramp_time, d);
  }
  const VesselSpec& v = s.vessel;
  if (!v.present) return;
  const std::string vp = v.where.path.empty() ? "vessel" : v.where.path;
  if (v.raos_given == v.motions_given) {
    d.error(v.where.loc, vp, "give exactly one of 'raos' or 'motions'");
    return;
  }
  if (s.tow.mode.value != "motion") d.error(v.where.loc, vp, "the vessel's wave motion needs tow.mode: motion");
  if (v.raos_given) {
    if (!w.present) d.error(v.raos_where.loc, v.raos_where.path, "RAOs need a waves: section");
    check_raos(v, d);
  }
  if (v.motions_given) check_increasing(v.motions, "times", d);
}

void attach_waves(const ScenarioSpec& s, Model& m) {
  std::shared_ptr<const WaveField> field;
  const double course0 = initial_course(m.tow);
  const WavesSpec& w = s.waves;
  if (w.present) {
    const double chi = course0 + w.heading_deg.value * std::numbers::pi / 180;  // travel direction in R_g
    const Vec3 dir(std::cos(chi), std::sin(chi), 0);
    // Finite depth: water_depth, else the seabed's below the tow's start, else deep water.
    const double depth = w.water_depth.given ? w.water_depth.value
                         : m.seabed          ? m.seabed->depth_at(m.tow.start.x())
                                             : std::numeric_limits<double>::infinity();
    WaveField built = w.regular ? make_regular_wave(w.height.value, w.period.value, dir, depth, m.fluid.g)
                                : make_irregular_sea(w.hs.value, w.tp.value,
                                                     w.type.value == "pierson_moskowitz" ? 1.0 : w.gamma.value,
                                                     static_cast<int>(w.components.value),
                                                     static_cast<std::uint64_t>(w.seed.value), dir, depth, m.fluid.g);
    if (!w.regular && w.spreading.given)
      spread_directions(built, w.spreading.value, static_cast<std::uint64_t>(w.seed.value));
    built.ramp_time = w.ramp_time.value;
    built.wheeler = w.stretching.value == "wheeler";
    field = std::make_shared<const WaveField>(std::move(built));
    if (m.fluid.rho > 0) m.fluid.waves = field;
    if (w.statistics_start.given) m.sim.statistics_start = w.statistics_start.value;
  }
  const VesselSpec& v = s.vessel;
  if (!v.present) return;
  std::shared_ptr<Vessel> vessel;
  if (v.raos_given) {
    vessel = std::make_shared<Vessel>(v.tow_point.value, course0, field, build_raos(v));
  } else {
    std::vector<double> t;
    std::vector<Vec6> x;
    const double deg = std::numbers::pi / 180;
    for (const auto& r : v.motions) {
      t.push_back(r.values[0]);
      Vec6 row;
      row << r.values[1], r.values[2], r.values[3], r.values[4] * deg, r.values[5] * deg, r.values[6] * deg;
      x.push_back(row);
    }
    vessel = std::make_shared<Vessel>(v.tow_point.value, course0, field, std::move(t), std::move(x));
  }
  vessel->set_exact_rotations(v.rotations.value == "exact");
  m.tow.vessel = vessel;
}

}  // namespace towsim::scenario
