// Run outputs: the columns, the number format, the writers and summary.json.
#include "towsim/output/output.hpp"
#include "towsim/waves/vessel.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "towsim/dynamics/bending.hpp"
#include "towsim/dynamics/elastic.hpp"
#include "towsim/version.hpp"

namespace towsim::output {

nlohmann::ordered_json json_of(const Extreme& e) {
  nlohmann::ordered_json j;
  j["value"] = std::isnan(e.value) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(tidy(e.value));
  j["time"] = std::isnan(e.time) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(tidy_time(e.time));
  return j;
}

nlohmann::ordered_json num(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

namespace {

/// v rounded to two significant digits.
double two_digits(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1e", v);
  return std::strtod(b, nullptr);
}

/// The end body's sample, or nullptr.
const BodySample* end_sample(const Model& model, const Sample& s) {
  return end_body(model) != nullptr && !s.bodies.empty() ? &s.bodies.back() : nullptr;
}

/// The point whose depth and layback users read: the end body's origin, or the cable's end.
Vec3 reference_point(const Model& model, const Sample& s) {
  if (const BodySample* b = end_sample(model, s)) return b->pos;
  return s.node_pos.empty() ? Vec3::Constant(std::nan("")) : s.node_pos.back();
}

/// Breaking load of the section each node belongs to (the element above it;
/// below it at a section's top) [N], 0 where none is given.
std::vector<double> node_breaking_loads(const Model& model) {
  std::vector<double> out;
  const auto& els = model.cable.elements;
  auto of = [&](std::size_t el) {
    const auto sec = static_cast<std::size_t>(els[el].section);
    return sec < model.cable.sections.size() ? model.cable.sections[sec].breaking_load : 0.0;
  };
  const std::size_t n = els.size();
  std::vector<bool> inline_at(n + 1, false);
  for (const Body& b : model.bodies)
    if (b.inline_body) inline_at[static_cast<std::size_t>(body_joint(model, b))] = true;
  for (std::size_t k = 0; k <= n; ++k) {
    out.push_back(of(k == 0 ? 0 : k - 1));
    if (inline_at[k]) out.push_back(of(k));
  }
  return out;
}

/// summary.json `elastic`: peak element tension and slack episodes.
nlohmann::ordered_json elastic_json(const SlackRecord& r) {
  nlohmann::ordered_json j;
  j["max_element_tension"] = {{"value", num(tidy(r.max_tension))},
                              {"time", num(tidy_time(r.max_tension_time))},
                              {"element", r.max_tension_element}};
  j["slack_episodes"] = r.episodes;
  j["slack_time"] = num(tidy_time(r.slack_time));
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SlackEvent& ev : r.events()) {
    nlohmann::ordered_json e;
    e["start"] = num(tidy_time(ev.start));
    e["end"] = num(tidy_time(ev.end));
    e["duration"] = num(tidy_time(ev.end - ev.start));
    e["ended"] = ev.ended;
    e["elements"] = {ev.first_element, ev.last_element};
    e["from"] = num(tidy(ev.from));
    e["to"] = num(tidy(ev.to));
    e["min_strain"] = num(ev.min_strain);
    e["snap_tension"] = ev.ended ? num(tidy(ev.snap_tension)) : nlohmann::ordered_json(nullptr);
    e["snap_time"] = ev.ended ? num(tidy_time(ev.snap_time)) : nlohmann::ordered_json(nullptr);
    e["snap_element"] = ev.snap_element;
    list.push_back(e);
  }
  j["slack"] = list;  // the first SlackRecord::kMaxEvents episodes
  return j;
}

}  // namespace

namespace {

/// 10^p, exact in double for p = 0..22.
constexpr double kPow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/// |v| rounded to 12 significant digits as m 10^(X - 11), 10^11 <= m < 10^12
/// (X: the decimal exponent after rounding), exactly as "%.12g" rounds: m is
/// the integer nearest to |v| 10^p with p = 11 - floor(log10 |v|), one
/// correctly rounded product (exact powers of ten, p <= 22) whose error
/// (< 6.2e-5 of a unit below 2^40) can only matter within 1e-3 of a half
/// unit. False there, and outside 1e-11 <= |v| < 1e12 (or not finite):
/// the caller then asks the standard library.
bool round12(double v, std::uint64_t& m, int& X) {
  const double a = std::abs(v);
  if (!(a >= 1e-11 && a < 1e12)) return false;
  // Decimal exponent X: an estimate from the binary one, then corrected.
  const int E = static_cast<int>((std::bit_cast<std::uint64_t>(a) >> 52) & 0x7ff) - 1023;  // 2^E <= a < 2^(E+1)
  X = std::max(-11, (E * 78913) >> 18);  // floor(E log10 2): floor(log10 a), or one below
  double m_real = a * kPow10[11 - X];    // 11 - X in 0..22 here
  if (m_real >= 1e12 && X < 11) {        // the estimate was one below
    ++X;
    m_real = a * kPow10[11 - X];
  }
  if (!(m_real >= 1e11 - 0.5 && m_real < 1e12 - 0.5)) return false;
  m = static_cast<std::uint64_t>(m_real);               // floor
  const double frac = m_real - static_cast<double>(m);  // exact
  if (std::abs(frac - 0.5) < 1e-3) return false;
  if (frac > 0.5) ++m;
  if (m == 1000000000000ULL) m = 100000000000ULL, ++X;  // 9.99..95 rounds up to 10
  return true;
}

/// Room for one formatted number (put_g12's fixed-size copies included) [bytes].
constexpr std::size_t kNumberRoom = 40;

/// v as std::to_chars(general, 12) writes it ("%.12g": 12 significant
/// digits, trailing zeros dropped, scientific below 1e-4 and from 1e12),
/// the same bytes, several times faster (round12, then the digits). Writes
/// up to 40 bytes from b (fixed-size copies past the end), returns the end.
char* put_g12(char* b, double v) {
  std::uint64_t m = 0;
  int X = 0;
  if (!round12(v, m, X)) return std::to_chars(b, b + kNumberRoom, v, std::chars_format::general, 12).ptr;
  // The 12 digits (two halves of 6, two digits at a time), zero-padded to 24
  // bytes so that fixed 12-byte copies from any digit stay inside d.
  char d[24] = "00000000000000000000000";
  auto six = [](char* out, std::uint32_t x) {
    static constexpr char kPairs[] =
        "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
        "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
        "8081828384858687888990919293949596979899";
    const std::uint32_t hi = x / 10000, lo = x % 10000;  // x < 10^6: digits hi | lo/100 | lo%100
    std::memcpy(out, kPairs + 2 * hi, 2);
    std::memcpy(out + 2, kPairs + 2 * (lo / 100), 2);
    std::memcpy(out + 4, kPairs + 2 * (lo % 100), 2);
  };
  six(d, static_cast<std::uint32_t>(m / 1000000));
  six(d + 6, static_cast<std::uint32_t>(m % 1000000));
  int nd = 12;  // digits up to the last non-zero one
  while (nd > 1 && d[nd - 1] == '0') --nd;
  char* p = b;
  if (v < 0) *p++ = '-';
  if (X >= -4 && X < 12) {
    if (X >= 0) {
      // Fixed: X + 1 digits before the point (the digits past nd are '0').
      std::memcpy(p, d, 12);
      p += X + 1;
      if (nd > X + 1) {
        *p = '.';
        std::memcpy(p + 1, d + X + 1, 12);
        p += nd - X;
      }
    } else {
      // "0.000" (-X - 1 zeros after the point), then the digits.
      static constexpr char kLead[5] = {'0', '.', '0', '0', '0'};
      std::memcpy(p, kLead, sizeof kLead);
      p += 1 - X;
      std::memcpy(p, d, 12);
      p += nd;
    }
    return p;
  }
  // Scientific: d.ddde-XX (at least two exponent digits).
  *p++ = d[0];
  if (nd > 1) {
    *p = '.';
    std::memcpy(p + 1, d + 1, 12);
    p += nd;
  }
  *p++ = 'e';
  *p++ = X < 0 ? '-' : '+';
  const int ax = X < 0 ? -X : X;
  if (ax >= 100) *p++ = static_cast<char>('0' + ax / 100);
  *p++ = static_cast<char>('0' + ax / 10 % 10);
  *p++ = static_cast<char>('0' + ax % 10);
  return p;
}

}  // namespace

double tidy(double v) {
  if (!std::isfinite(v)) return v;
  if (std::abs(v) < kZeroBelow) return 0.0;  // also turns -0 into 0
  // m 10^(X - 11) with m < 2^53 and an exact power of ten: one correctly
  // rounded product or quotient, the double nearest to the 12 digits, as
  // from_chars gives it (Clinger's fast path).
  std::uint64_t m = 0;
  int X = 0;
  if (round12(v, m, X)) {
    const double a = X >= 11 ? static_cast<double>(m) * kPow10[X - 11] : static_cast<double>(m) / kPow10[11 - X];
    return v < 0 ? -a : a;
  }
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, 12);
  double out = v;
  std::from_chars(b, r.ptr, out);
  return out;
}

double tidy_time(double t) {
  if (!std::isfinite(t)) return t;
  const double r = std::round(t * 1e9) / 1e9;  // nanoseconds
  return r == 0 ? 0.0 : r;
}

namespace {

/// v at p as put_number writes it (at most kNumberRoom bytes); returns the end.
char* put_value(char* p, double v) {
  if (std::abs(v) < kZeroBelow) {  // 0, as to_chars writes it (many columns are zero)
    *p = '0';
    return p + 1;
  }
  return put_g12(p, v);
}

}  // namespace

void put_number(std::string& out, double v) {
  char b[kNumberRoom];
  // 12 significant digits (the shortest form of tidy(v)), the bytes of
  // std::to_chars(general, 12), formatted directly (put_g12).
  const char* end = put_value(b, v);
  out.append(b, static_cast<std::size_t>(end - b));
}

void put_time(std::string& out, double t) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, tidy_time(t));  // shortest round-trip form
  out.append(b, r.ptr);
}

double layback(const Model& model, const Sample& s) {
  const Vec3 p = reference_point(model, s);
  return std::hypot(p.x() - s.tow_pos.x(), p.y() - s.tow_pos.y());
}

double utilisation(const Model& model, const Sample& s) {
  const std::vector<double> limit = node_breaking_loads(model);
  double u = 0;
  // Nodes counted from the bottom: a winch adds or removes them at the top,
  // in the top section (whose limit the extra top nodes take).
  const std::size_t n = s.tension.size(), m = limit.size();
  for (std::size_t k = 0; k < n && m > 0; ++k) {
    const std::size_t j = n - k <= m ? m - (n - k) : 0;
    if (limit[j] > 0) u = std::max(u, s.tension[k] / limit[j]);
  }
  return u;
}

void remove_run_outputs(const std::string& dir) {
  namespace fs = std::filesystem;
  // Only regular files, never what else may bear a name of towsim's (a
  // user's folder called summary.json): that is refused, left as it is.
  const auto remove_file = [](const fs::path& p) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (st.type() == fs::file_type::not_found) return;
    if (!ec && st.type() != fs::file_type::regular)
      throw std::runtime_error(p.string() + " is not a file of towsim's (" +
                               (st.type() == fs::file_type::directory ? "a directory" : "not a regular file") +
                               "): move it away or choose another output directory");
    if (!ec) fs::remove(p, ec);
    if (ec) throw std::runtime_error("cannot remove the previous run's " + p.string() + ": " + ec.message());
  };
  for (const char* name :
       {"timeseries.csv", "nodes.csv", "summary.json", "summary.json.part", "spectra.csv", "report.html"})
    remove_file(fs::path(dir) / name);
  // plots/ (towsim plot's folder): its regular files, then the folder if that empties it.
  const fs::path plots = fs::path(dir) / "plots";
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(plots, ec))) return;
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(plots, ec))
    if (e.is_regular_file() && !e.is_symlink()) files.push_back(e.path());
  if (ec) throw std::runtime_error("cannot read the previous run's " + plots.string() + ": " + ec.message());
  for (const fs::path& f : files) remove_file(f);
  if (fs::is_empty(plots, ec)) fs::remove(plots, ec);
}

void Extreme::max(double v, double t) {
  if (std::isnan(value) || v > value) {
    value = v;
    time = t;
  }
}

void Extreme::min(double v, double t) {
  if (std::isnan(value) || v < value) {
    value = v;
    time = t;
  }
}

void Extremes::add(const Model& model, const Sample& s) {
  max_tow_tension.max(s.tow_force.norm(), s.t);
  for (double T : s.tension) max_cable_tension.max(T, s.t);
  for (double A : s.axial) min_axial_force.min(A, s.t);
  if (!s.node_pos.empty()) max_end_depth.max(-s.node_pos.back().z(), s.t);
  // What users read: layback and depth of the end body (or the cable's end).
  max_layback.max(tidy(layback(model, s)), tidy_time(s.t));
  const double depth = -reference_point(model, s).z();
  if (!std::isnan(depth)) {
    min_depth.min(tidy(depth), tidy_time(s.t));
    max_depth.max(tidy(depth), tidy_time(s.t));
  }
  if (std::any_of(model.cable.sections.begin(), model.cable.sections.end(),
                  [](const Section& sec) { return sec.breaking_load > 0; }))
    max_utilisation.max(utilisation(model, s), s.t);
  // The first crossings of 1/3 and 1, at the most utilised node.
  if (!s.utilisation.empty() && !cable_failure.happened()) {
    const auto top = std::max_element(s.utilisation.begin(), s.utilisation.end());
    const double u = *top;
    for (Crossing* c : {&utilisation_warning, &cable_failure}) {
      const double limit = c == &cable_failure ? kUtilisationFailure : kUtilisationWarning;
      if (c->happened() || !(u > limit)) continue;
      c->time = s.t;
      c->node = top - s.utilisation.begin();
      c->arc_length = node_arc_lengths(model)[static_cast<std::size_t>(c->node)];
      c->utilisation = u;
    }
  }
  if (model.seabed) {
    max_contact_length.max(s.contact_length, s.t);
    max_seabed_normal.max(s.seabed_normal, s.t);
    max_seabed_friction.max(s.seabed_friction, s.t);
  }
  // Each body: its own extremes.
  inline_bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size() && b < s.bodies.size(); ++b) {
    const BodySample& bs = s.bodies[b];
    BodyExtremes& e = model.bodies[b].inline_body ? inline_bodies[b] : end_body_extremes;
    e.max_link_force.max(bs.link_force.norm(), s.t);
    e.max_lower_link_force.max(bs.lower_link_force.norm(), s.t);
    e.max_depth.max(-bs.pos.z(), s.t);
    for (int i = 0; i < 3; ++i) {
      e.min_deg[i].min(bs.rpy_deg[i], s.t);
      e.max_deg[i].max(bs.rpy_deg[i], s.t);
    }
  }
  add_controls(model, s);
}

void Extremes::add_controls(const Model& model, const Sample& s) {
  std::size_t i = 0;
  for (std::size_t b = 0; b < model.bodies.size() && b < s.bodies.size(); ++b) {
    std::size_t c = 0;
    for (const LiftingSurface& ls : model.bodies[b].surfaces) {
      if (!ls.depth_control || c >= s.bodies[b].controls.size()) continue;
      const ControlSample& cs = s.bodies[b].controls[c++];
      if (controls.size() <= i) controls.resize(i + 1);
      ControlExtremes& e = controls[i++];
      e.max_abs_deflection.max(std::abs(cs.deflection_deg), s.t);
      e.max_abs_rate.max(std::abs(cs.rate_deg_s), s.t);
      e.max_abs_error.max(std::abs(cs.depth_error), s.t);
      // Settling: the band is the given one, or 1 % of the first error (at least 1 cm).
      if (std::isnan(e.first_error)) {
        e.first_error = cs.depth_error;
        e.band = ls.depth_control->settling_band > 0 ? ls.depth_control->settling_band
                                                     : std::max(0.01 * std::abs(cs.depth_error), 0.01);
      }
      if (std::abs(cs.depth_error) > e.band)
        e.settled_since = std::numeric_limits<double>::quiet_NaN();
      else if (std::isnan(e.settled_since))
        e.settled_since = s.t;
      e.final_error = cs.depth_error;
    }
  }
}

std::vector<std::string> timeseries_columns(const Model& model) {
  const bool has_body = end_body(model) != nullptr;
  std::vector<std::string> c{"time",        "tow_x",       "tow_y", "tow_z", "tow_force_x",
                             "tow_force_y", "tow_force_z", "end_x", "end_y", "end_z"};
  if (has_body)
    c.insert(c.end(), {"body_x", "body_y", "body_z", "body_roll_deg", "body_pitch_deg", "body_yaw_deg", "link_force_x",
                       "link_force_y", "link_force_z"});
  c.insert(c.end(), {"tow_tension", "end_depth", "tow_vx", "tow_vy", "tow_vz"});
  if (has_body) c.insert(c.end(), {"body_depth", "link_tension"});
  c.insert(c.end(), {"layback", "deployed_length"});
  if (model.winch.active()) c.push_back("payout_speed");
  if (model.winch.active() && model.winch.rating > 0) c.push_back("winch_load_ratio");
  // In-line bodies, by name.
  for (const Body& b : model.bodies) {
    if (!b.inline_body) continue;
    for (const char* s : {"_x", "_y", "_z", "_roll_deg", "_pitch_deg", "_yaw_deg", "_link_force_x", "_link_force_y",
                          "_link_force_z", "_lower_link_force_x", "_lower_link_force_y", "_lower_link_force_z",
                          "_depth", "_link_tension", "_lower_link_tension"})
      c.push_back(b.name + s);
  }
  if (has_sea(model)) c.insert(c.end(), {"wave_elevation", "tow_wave_x", "tow_wave_y", "tow_wave_z"});
  if (model.seabed)
    c.insert(c.end(), {"contact_length", "seabed_normal_force", "seabed_friction_force", "touchdown_arc_length",
                       "touchdown_x", "touchdown_y", "touchdown_z", "lying_length"});
  // Depth controllers: <body>_surface<j>_... (j: the surface's index in its body's list).
  for (const Body& b : model.bodies)
    for (std::size_t j = 0; j < b.surfaces.size(); ++j) {
      if (!b.surfaces[j].depth_control) continue;
      const std::string p = (b.inline_body ? b.name : std::string("body")) + "_surface" + std::to_string(j);
      c.insert(c.end(), {p + "_deflection_deg", p + "_deflection_rate_deg_s", p + "_depth_error"});
    }
  return c;
}

std::string timeseries_header(const Model& model) {
  std::string h;
  for (const auto& c : timeseries_columns(model)) h += (h.empty() ? "" : ",") + c;
  return h;
}

namespace {

/// timeseries_values() before tidy (the time already rounded): put_number
/// writes v and tidy(v) alike.
void raw_timeseries_values(const Model& model, const Sample& s, std::vector<double>& v) {
  const Vec3 end = s.node_pos.empty() ? Vec3::Constant(std::nan("")) : s.node_pos.back();
  const BodySample* eb = end_sample(model, s);
  v.clear();
  auto add3 = [&v](const Vec3& a) { v.insert(v.end(), {a.x(), a.y(), a.z()}); };
  v.push_back(tidy_time(s.t));
  add3(s.tow_pos);
  add3(s.tow_force);
  add3(end);
  if (eb) {
    add3(eb->pos);
    add3(eb->rpy_deg);
    add3(eb->link_force);
  }
  v.push_back(s.tow_force.norm());
  v.push_back(-end.z());
  add3(s.tow_vel);
  if (eb) {
    v.push_back(-eb->pos.z());
    v.push_back(eb->link_force.norm());
  }
  v.push_back(layback(model, s));
  v.push_back(s.deployed_length);
  if (model.winch.active()) v.push_back(s.payout_speed);
  if (model.winch.active() && model.winch.rating > 0) v.push_back(s.tow_force.norm() / model.winch.rating);
  for (std::size_t b = 0; b < model.bodies.size() && b < s.bodies.size(); ++b) {
    if (!model.bodies[b].inline_body) continue;
    const BodySample& bs = s.bodies[b];
    add3(bs.pos);
    add3(bs.rpy_deg);
    add3(bs.link_force);
    add3(bs.lower_link_force);
    v.insert(v.end(), {-bs.pos.z(), bs.link_force.norm(), bs.lower_link_force.norm()});
  }
  if (has_sea(model)) {  // sea-state columns
    v.push_back(s.wave_elevation);
    add3(s.tow_wave);
  }
  if (model.seabed) {
    v.insert(v.end(), {s.contact_length, s.seabed_normal, s.seabed_friction, s.touchdown_arc_length});
    add3(s.touchdown);
    v.push_back(s.lying_length);
  }
  for (std::size_t b = 0; b < model.bodies.size() && b < s.bodies.size(); ++b)  // depth controllers
    for (const ControlSample& c : s.bodies[b].controls)
      v.insert(v.end(), {c.deflection_deg, c.rate_deg_s, c.depth_error});
}

}  // namespace

void timeseries_values(const Model& model, const Sample& s, std::vector<double>& v) {
  raw_timeseries_values(model, s, v);
  for (std::size_t i = 1; i < v.size(); ++i) v[i] = tidy(v[i]);
}

const std::vector<std::string>& node_columns() {
  static const std::vector<std::string> c{"x", "y", "z", "vx", "vy", "vz", "tension", "axial_force", "strain"};
  return c;
}

namespace {

/// Node k's values unrounded, appended in the order of node_columns(model)
/// (without a model: of node_columns()). put_number writes v and tidy(v) alike.
void raw_node_values(const Model* model, const Sample& s, std::size_t k, std::vector<double>& out) {
  const double nan = std::nan("");
  const Vec3 v = k < s.node_vel.size() ? s.node_vel[k] : Vec3::Constant(nan);
  out.insert(out.end(), {s.node_pos[k].x(), s.node_pos[k].y(), s.node_pos[k].z(), v.x(), v.y(), v.z(),
                         k < s.tension.size() ? s.tension[k] : nan, k < s.axial.size() ? s.axial[k] : nan,
                         k < s.strain.size() ? s.strain[k] : nan});
  if (model == nullptr) return;
  if (!s.utilisation.empty()) out.push_back(k < s.utilisation.size() ? s.utilisation[k] : nan);
  if (model->seabed) out.push_back(k < s.node_seabed.size() ? s.node_seabed[k].norm() : nan);
  if (!s.bending.empty()) out.push_back(k < s.bending.size() ? s.bending[k] : nan);  // make_sample: with bending
}

}  // namespace

void node_values(const Sample& s, std::size_t k, std::vector<double>& out) {
  const std::size_t from = out.size();
  raw_node_values(nullptr, s, k, out);
  for (std::size_t i = from; i < out.size(); ++i) out[i] = tidy(out[i]);  // as written
}

std::vector<std::string> node_columns(const Model& model) {
  std::vector<std::string> c = node_columns();
  if (std::any_of(model.cable.sections.begin(), model.cable.sections.end(),
                  [](const Section& sec) { return sec.breaking_load > 0; }))
    c.push_back("utilisation");
  if (model.seabed) c.push_back("seabed_force");
  if (has_bending(model)) c.push_back("bending_moment");
  return c;
}

void node_values(const Model& model, const Sample& s, std::size_t k, std::vector<double>& out) {
  const std::size_t from = out.size();
  raw_node_values(&model, s, k, out);
  for (std::size_t i = from; i < out.size(); ++i) out[i] = tidy(out[i]);  // as written
}

std::vector<double> node_arc_lengths(const Model& model) {
  std::vector<double> out{0.0};
  const auto& els = model.cable.elements;
  double arc = 0;  // [m]
  for (std::size_t k = 1; k <= els.size(); ++k) {
    arc += els[k - 1].length;
    out.push_back(arc);
    // An in-line body's joint gives a second node (Q2) at the same arc length.
    for (const Body& body : model.bodies)
      if (body.inline_body && static_cast<std::size_t>(body_joint(model, body)) == k) out.push_back(arc);
  }
  return out;
}

std::vector<std::string> strength_warnings(const Extremes& ex) {
  std::vector<std::string> out;
  auto fmt_num = [](double v) {  // as in messages ("%.10g")
    char b[40];
    std::snprintf(b, sizeof b, "%.10g", v);
    return std::string(b);
  };
  auto text = [&](const Crossing& c) {
    return fmt_num(tidy(c.utilisation)) + " at t = " + fmt_num(tidy_time(c.time)) + " s, node " +
           std::to_string(c.node) + ", " + fmt_num(tidy(c.arc_length)) + " m from the tow point";
  };
  if (ex.utilisation_warning.happened())
    out.push_back("utilisation above 1/3 (a safety factor below 3 on the breaking load): first " +
                  text(ex.utilisation_warning) + "; see utilisation in nodes.csv");
  if (ex.cable_failure.happened())
    out.push_back("utilisation above 1 (tension above the breaking load: the cable would break): first " +
                  text(ex.cable_failure) + "; the run went on as if it held");
  return out;
}

std::string compression_warning(const Model& model, const Extremes& ex) {
  const Extreme& comp = ex.min_axial_force;
  const auto& els = model.cable.elements;
  if (!(comp.value < 0) || std::all_of(els.begin(), els.end(), is_elastic)) return {};
  char force[40], time[40];  // as in messages ("%.10g")
  std::snprintf(force, sizeof force, "%.10g", comp.value);
  std::snprintf(time, sizeof time, "%.10g", comp.time);
  const char* where = model.sim.write_nodes ? " s; see axial_force in nodes.csv"
                                            : " s; see min_axial_force in summary.json: nodes.csv was not written, "
                                              "simulation.write_nodes is false";
  return std::string("the cable was in compression (axial force ") + force + " N at t = " + time + where +
         "): a real cable would go slack there";
}

RunRecord::RunRecord(const Model& model)
    : model_(model),
      sea_(statistics_start(model)),
      transients_(run_phases(model), model.sim.duration, end_body(model) != nullptr) {}

void RunRecord::write(const Sample& s) {
  extremes_.add(model_, s);
  // The phases' figures from the values as written (timeseries.csv's tow_tension,
  // body_depth or end_depth, link_tension).
  const BodySample* eb = end_sample(model_, s);
  transients_.add(tidy_time(s.t), tidy(s.tow_force.norm()), tidy(-reference_point(model_, s).z()),
                  eb != nullptr ? tidy(eb->link_force.norm()) : std::nan(""));
  if (has_sea(model_)) sea_.add(model_, s);
  ++samples_;
  raw_timeseries_values(model_, s, raw_row_);
  row_tidied_ = false;
}

const std::vector<double>& RunRecord::last_row() const {
  if (!row_tidied_) {  // tidied on demand: the writer formats the raw row
    last_row_ = raw_row_;
    for (std::size_t i = 1; i < last_row_.size(); ++i) last_row_[i] = tidy(last_row_[i]);
    row_tidied_ = true;
  }
  return last_row_;
}

nlohmann::ordered_json RunRecord::final_row() const {
  const std::vector<double>& row = last_row();
  if (row.empty()) return nullptr;
  nlohmann::ordered_json j;
  const auto names = timeseries_columns(model_);
  for (std::size_t i = 0; i < names.size() && i < row.size(); ++i) j[names[i]] = num(row[i]);
  return j;
}

RunWriter::RunWriter(const std::string& dir, const Model& model, bool write_nodes) : RunRecord(model) {
  // The rows arrive in large batches, each one write(2).
  series_ = std::make_unique<RowFile>((std::filesystem::path(dir) / "timeseries.csv").string());
  series_->append(timeseries_header(model) + "\n");
  node_ids_ = model.winch.active();
  if (write_nodes) {
    nodes_ = std::make_unique<RowFile>((std::filesystem::path(dir) / "nodes.csv").string());
    std::string h = node_ids_ ? "time,node,node_id" : "time,node";
    for (const auto& c : node_columns(model)) h += "," + c;
    nodes_->append(h + "\n");
  }
  last_write_ = std::chrono::steady_clock::now();
}

RunWriter::~RunWriter() { flush(); }

std::string RunWriter::error() const {
  if (!series_->error().empty()) return series_->error();
  return nodes_ != nullptr ? nodes_->error() : std::string();
}

void RunWriter::write(const Sample& s) {
  RunRecord::write(s);
  // timeseries.csv: the row just recorded, formatted in place (the buffer
  // grown first to room for every number, then cut to what was written).
  const auto& row = raw_row();
  std::size_t at = series_buf_.size();
  series_buf_.resize(at + (row.size() + 1) * kNumberRoom);
  char* p = series_buf_.data() + at;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) {
      *p++ = ',';
      p = put_value(p, row[i]);
    } else {
      p = std::to_chars(p, p + kNumberRoom, tidy_time(row[0])).ptr;  // as put_time writes it
    }
  }
  *p++ = '\n';
  series_buf_.resize(static_cast<std::size_t>(p - series_buf_.data()));
  if (nodes_ != nullptr) {
    // nodes.csv: one row per node, the time formatted once; the values
    // unrounded (put_number rounds them as tidy would).
    time_.clear();
    put_time(time_, s.t);
    at = nodes_buf_.size();
    for (std::size_t k = 0; k < s.node_pos.size(); ++k) {
      values_.clear();
      raw_node_values(&model(), s, k, values_);
      nodes_buf_.resize(at + time_.size() + (values_.size() + 3) * kNumberRoom);
      p = nodes_buf_.data() + at;
      std::memcpy(p, time_.data(), time_.size());
      p += time_.size();
      *p++ = ',';
      p = std::to_chars(p, p + kNumberRoom, static_cast<long>(k)).ptr;
      if (node_ids_) {
        *p++ = ',';
        p = std::to_chars(p, p + kNumberRoom, k < s.node_id.size() ? s.node_id[k] : static_cast<long>(k)).ptr;
      }
      for (double v : values_) {
        *p++ = ',';
        p = put_value(p, v);
      }
      *p++ = '\n';
      at = static_cast<std::size_t>(p - nodes_buf_.data());
    }
    nodes_buf_.resize(at);
  }
  // Whole rows to the files: when a buffer is large, or kWriteEvery after the last write.
  if (series_buf_.size() + nodes_buf_.size() >= kWriteBytes ||
      std::chrono::steady_clock::now() - last_write_ >= kWriteEvery)
    flush();
}

void RunWriter::flush() {
  if (!series_buf_.empty()) series_->append(series_buf_);
  if (nodes_ != nullptr && !nodes_buf_.empty()) nodes_->append(nodes_buf_);
  series_buf_.clear();
  nodes_buf_.clear();
  last_write_ = std::chrono::steady_clock::now();
}

nlohmann::ordered_json run_json(const std::string& model_name, const RunStats& stats) {
  nlohmann::ordered_json j;
  j["model"] = model_name;
  j["version"] = kVersion;  // of the program that wrote the file
  j["status"] = stats.status;
  j["message"] = stats.message;
  j["end_time"] = num(tidy_time(stats.end_time));
  j["wall_seconds"] = num(std::round(stats.wall_seconds * 1e3) / 1e3);  // ms: the clock's useful resolution
  j["steps"] = stats.steps;
  j["rejected_steps"] = stats.rejected_steps;
  j["rhs_evaluations"] = stats.rhs_evaluations;
  j["max_element_drift"] = num(stats.max_element_drift);  // kept unrounded: it is a round-off measure
  j["integrator"] = stats.integrator;
  j["threads"] = stats.threads;  // 2: step-end evaluations on a worker thread (simulation.threads)
  // rosenbrock: largest local error estimate of an accepted step (relative,
  // state and tow/link forces) and its force part; null for the others.
  j["integration_error_estimate"] = stats.error_estimate >= 0 ? num(stats.error_estimate)
                                                              : nlohmann::ordered_json(nullptr);
  j["force_error_estimate"] = stats.force_error_estimate >= 0 ? num(stats.force_error_estimate)
                                                              : nlohmann::ordered_json(nullptr);
  // The element count's share of the tow tension's error (relative, two
  // significant digits: an estimate); null when none was made.
  j["discretisation_error_estimate"] = stats.discretisation_error_estimate >= 0
                                           ? num(two_digits(stats.discretisation_error_estimate))
                                           : nlohmann::ordered_json(nullptr);
  // rk4: smallest estimated stability limit of the step over the samples [s].
  j["rk4_stability_limit"] = stats.rk4_step_limit > 0 ? num(stats.rk4_step_limit) : nlohmann::ordered_json(nullptr);
  j["warnings"] = stats.warnings;
  return j;
}

nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const RunRecord& record, bool write_nodes) {
  const Model& model = record.model();
  const Extremes& ex = record.extremes();
  nlohmann::ordered_json j = run_json(model_name, stats);
  j["samples"] = record.samples();
  j["files"] = {{"timeseries", "timeseries.csv"},
                {"nodes", write_nodes ? nlohmann::ordered_json("nodes.csv") : nlohmann::ordered_json(nullptr)}};
  nlohmann::ordered_json e;
  e["max_tow_tension"] = json_of(ex.max_tow_tension);
  e["max_cable_tension"] = json_of(ex.max_cable_tension);
  e["max_end_depth"] = json_of(ex.max_end_depth);
  e["min_axial_force"] = json_of(ex.min_axial_force);  // < 0: compression (a real cable would go slack)
  e["min_depth"] = json_of(ex.min_depth);              // of the end body's origin, or of the cable end
  e["max_depth"] = json_of(ex.max_depth);
  e["max_layback"] = json_of(ex.max_layback);
  // The end body under today's names, in-line bodies under their own.
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const Body& body = model.bodies[b];
    const BodyExtremes& be = body.inline_body && b < ex.inline_bodies.size() ? ex.inline_bodies[b]
                                                                             : ex.end_body_extremes;
    const std::string name = body.inline_body ? body.name : "body";
    const std::string p = body.inline_body ? body.name + "_" : "";
    e["max_" + p + "link_force"] = json_of(be.max_link_force);
    if (body.inline_body) e["max_" + p + "lower_link_force"] = json_of(be.max_lower_link_force);
    e["max_" + name + "_depth"] = json_of(be.max_depth);
    const char* names[3] = {"_roll_deg", "_pitch_deg", "_yaw_deg"};
    for (int i = 0; i < 3; ++i) e[name + names[i]] = {{"min", json_of(be.min_deg[i])}, {"max", json_of(be.max_deg[i])}};
  }
  if (model.seabed) {
    e["max_contact_length"] = json_of(ex.max_contact_length);
    e["max_seabed_normal_force"] = json_of(ex.max_seabed_normal);
    e["max_seabed_friction_force"] = json_of(ex.max_seabed_friction);
  }
  j["extremes"] = e;
  // Depth controllers: settling and the fins' extremes.
  if (!ex.controls.empty()) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    std::size_t i = 0;
    for (const Body& body : model.bodies)
      for (std::size_t k = 0; k < body.surfaces.size(); ++k) {
        const auto& dc = body.surfaces[k].depth_control;
        if (!dc || i >= ex.controls.size()) continue;
        const ControlExtremes& c = ex.controls[i++];
        nlohmann::ordered_json o;
        o["body"] = body.inline_body ? body.name : "body";
        o["surface"] = k;
        o["target_depth"] = num(dc->target_depth);
        o["initial_error"] = num(tidy(c.first_error));
        o["settling_band"] = num(tidy(c.band));
        o["settling_time"] = num(tidy_time(c.settled_since));  // null: not settled at the end
        o["final_error"] = num(tidy(c.final_error));
        o["max_abs_error"] = json_of(c.max_abs_error);
        o["max_abs_deflection_deg"] = json_of(c.max_abs_deflection);
        o["max_abs_deflection_rate_deg_s"] = json_of(c.max_abs_rate);
        list.push_back(o);
      }
    j["depth_control"] = list;
  }
  // With breaking loads: the largest tension / breaking load anywhere, and when;
  // the first crossings of 1/3 (warning) and 1 (failure), null when never.
  if (!std::isnan(ex.max_utilisation.value)) {
    j["max_utilisation"] = num(tidy(ex.max_utilisation.value));
    j["max_utilisation_time"] = num(tidy_time(ex.max_utilisation.time));
    auto crossing = [](const Crossing& c) {
      if (!c.happened()) return nlohmann::ordered_json(nullptr);
      nlohmann::ordered_json o;
      o["time"] = num(tidy_time(c.time));
      o["node"] = c.node;
      o["arc_length"] = num(tidy(c.arc_length));
      o["utilisation"] = num(tidy(c.utilisation));
      return o;
    };
    j["utilisation_warning"] = crossing(ex.utilisation_warning);
    j["cable_failure"] = crossing(ex.cable_failure);
  }
  // With a winch: its events and the largest tow tension against its rating.
  if (model.winch.active()) {
    nlohmann::ordered_json w;
    w["splits"] = stats.winch_splits;
    w["removals"] = stats.winch_removals;
    // [J] the kinetic energy change at removals: lost (kinks straightened) or
    // gained (the impulse bringing the pay-out speed back did positive work).
    w["energy_lost"] = num(tidy(std::max(0.0, stats.winch_energy_lost)));
    w["energy_gained"] = num(tidy(std::max(0.0, -stats.winch_energy_lost)));
    w["rating"] = model.winch.rating > 0 ? num(model.winch.rating) : nlohmann::ordered_json(nullptr);
    w["max_load_ratio"] = model.winch.rating > 0 ? num(tidy(ex.max_tow_tension.value / model.winch.rating))
                                                 : nlohmann::ordered_json(nullptr);
    j["winch"] = w;
  }
  if (lengths_in_state(model)) j["elastic"] = elastic_json(stats.slack);
  for (const std::string& w : strength_warnings(ex)) j["warnings"].push_back(w);
  if (const std::string w = compression_warning(model, ex); !w.empty()) j["warnings"].push_back(w);
  // The manoeuvre phases: extremes within each, settling of the response.
  j["phases"] = record.transients().json(stats.end_time);
  j["final"] = record.final_row();  // the last timeseries.csv row by column name
  j["scenario"] = scenario;
  return j;
}

bool write_summary(const std::string& dir, const nlohmann::ordered_json& summary, std::string* error) {
  namespace fs = std::filesystem;
  // Invalid UTF-8 in the scenario echo (e.g. a `name:` in another encoding)
  // becomes U+FFFD instead of throwing after the whole run.
  const std::string text = summary.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
  // Whole or not at all: written beside, then renamed over summary.json.
  const fs::path path = fs::path(dir) / "summary.json";
  const fs::path part = fs::path(dir) / "summary.json.part";
  std::string why;
  try {
    RowFile f(part.string());
    if (!f.append(text)) why = f.error();
  } catch (const std::runtime_error& e) {
    why = e.what();
  }
  std::error_code ec;
  if (why.empty()) fs::rename(part, path, ec);
  if (why.empty() && ec) why = "cannot write " + path.string() + ": " + ec.message();
  if (why.empty()) return true;
  fs::remove(part, ec);
  if (error != nullptr) *error = why;
  return false;
}

}  // namespace towsim::output
