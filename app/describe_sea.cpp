#include "describe_sea.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "towsim/scenario/diagnostics.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
namespace {

void line(std::ostream& out, const std::string& label, const std::string& value) {
  out << "  " << label << std::string(label.size() < 28 ? 28 - label.size() : 1, ' ') << value << "\n";
}

}  // namespace

void describe_sea(const Model& m, std::ostream& out) {
  const WaveField* w = m.fluid.waves.get();
  if (w != nullptr) {
    out << "waves\n";
    line(out, "harmonics", std::to_string(w->components.size()));
    line(out, "Hs = 4 sqrt(variance)", scenario::fmt_num(4 * std::sqrt(w->variance())) + " m");
    double lo = 1e300, hi = 0, deepest = 0;
    for (const auto& c : w->components) {
      lo = std::min(lo, c.omega), hi = std::max(hi, c.omega);
      if (std::isfinite(c.z_cut)) deepest = std::min(deepest, c.z_cut);
    }
    const double two_pi = 2 * std::numbers::pi;
    line(out, "periods", scenario::fmt_num(two_pi / hi) + " .. " + scenario::fmt_num(two_pi / lo) + " s");
    line(out, "travel direction (R_g)",
         "[" + scenario::fmt_num(w->direction.x()) + ", " + scenario::fmt_num(w->direction.y()) + ", 0]");
    line(out, "water depth", std::isfinite(w->depth) ? scenario::fmt_num(w->depth) + " m" : std::string("deep"));
    line(out, "kinematics cut off below",
         scenario::fmt_num(-deepest) + " m depth (harmonics < 0.1 % of their surface value)");
    line(out, "kinematics up to",
         w->wheeler ? std::string("the wave surface (Wheeler stretching)")
                    : std::string("the still water level z = 0 (no stretching)"));
  }
  if (const Vessel* v = m.tow.vessel.get()) {
    out << "vessel\n";
    const Vec3& s = v->sheave();
    line(out, "tow point (sheave)",
         "[" + scenario::fmt_num(s.x()) + ", " + scenario::fmt_num(s.y()) + ", " + scenario::fmt_num(s.z()) +
             "] m from the RAO origin (vessel axes)");
    line(out, "motion", v->measured() ? "measured record (cubic spline)" : "RAOs at the encounter frequency");
    line(out, "statistics from", scenario::fmt_num(statistics_start(m)) + " s");
  }
}

}  // namespace towsim::cli
