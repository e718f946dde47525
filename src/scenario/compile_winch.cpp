// Checking and building winch: (docs/scenario.md "winch").
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "towsim/dynamics/state.hpp"

#include "checks.hpp"

namespace towsim::scenario {

namespace {

void report_at(const Where& w, Diagnostics& d, const std::string& msg) { d.error(w.loc, w.path, msg); }

/// Rows' values in column 0 (times) and 1.
void columns(const std::vector<RowSpec>& rows, std::vector<double>& t, std::vector<double>& v) {
  for (const RowSpec& r : rows) t.push_back(r.values[0]), v.push_back(r.values[1]);
}

/// Every row's speed within max_speed, and (rate table) every slope within max_acceleration.
void check_speeds(const WinchSpec& w, Diagnostics& d) {
  const std::vector<RowSpec>& rows = w.rate_given ? w.rate : w.length;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bool last = i + 1 == rows.size();
    const double dt = last ? 0 : rows[i + 1].values[0] - rows[i].values[0];
    if (w.rate_given) {
      const double v = rows[i].values[1];
      if (w.max_speed.given && std::abs(v) > w.max_speed.value * (1 + 1e-12))
        report_at(rows[i].where, d,
                  "pay-out speed " + fmt_num(v) + " m/s exceeds winch.max_speed (" + fmt_num(w.max_speed.value) +
                      " m/s)");
      if (!last && dt > 0 && w.max_acceleration.given) {
        const double a = (rows[i + 1].values[1] - v) / dt;
        if (std::abs(a) > w.max_acceleration.value * (1 + 1e-12))
          report_at(rows[i + 1].where, d,
                    "pay-out acceleration " + fmt_num(a) + " m/s^2 exceeds winch.max_acceleration (" +
                        fmt_num(w.max_acceleration.value) + " m/s^2)");
      }
    } else if (!last && dt > 0 && w.max_speed.given) {
      const double v = (rows[i + 1].values[1] - rows[i].values[1]) / dt;
      if (std::abs(v) > w.max_speed.value * (1 + 1e-12))
        report_at(rows[i + 1].where, d,
                  "pay-out speed " + fmt_num(v) + " m/s exceeds winch.max_speed (" + fmt_num(w.max_speed.value) +
                      " m/s)");
    }
  }
}

/// v to 3 significant digits, rounded down (a bound users can copy).
std::string down3(double v) {
  const double p = std::pow(10.0, std::floor(std::log10(v)) - 2);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", std::floor(v / p) * p);
  return buf;
}

}  // namespace

void check_winch_rk4(const ScenarioSpec& s, const Model& m, Diagnostics& d) {
  if (!elastic_winch(m) || s.simulation.integrator.value != "rk4") return;
  // The top element at its shortest: (split_at - 1) L_e after a split,
  // remove_at L_e before a removal (when the winch can haul in), its
  // initial length.
  const Winch& win = m.winch;
  bool hauls_in = win.mode == Winch::Mode::Tension;
  for (const WinchPiece& p : win.schedule) hauls_in = hauls_in || p.rate < 0 || p.acc < 0;
  double shortest = std::min(m.cable.elements.front().length, (win.split_at - 1) * win.nominal_length);
  if (hauls_in) shortest = std::min(shortest, win.remove_at * win.nominal_length);
  const Element el = scaled_element(m.cable.elements.front(), shortest);
  const double h_max = rk4_axial_step_limit(el);
  if (s.simulation.time_step.value > h_max)
    report_at(s.simulation.time_step.where, d,
              "with integrator: rk4 and a winch on an elastic cable, the top element shortens to " + fmt_num(shortest) +
                  " m (split_at, remove_at): its axial wave needs simulation.time_step <= " + down3(h_max) +
                  " s; use integrator: rosenbrock or a smaller step");
}

void check_winch(const ScenarioSpec& s, Diagnostics& d) {
  const WinchSpec& w = s.winch;
  // Exactly one mode.
  const int modes = int(w.rate_given) + int(w.length_given) + int(w.tension.given);
  if (modes == 0) report_at(w.where, d, "give one of rate, length or tension");
  if (modes > 1) {
    const Where& second = w.tension.given ? w.tension.where : w.length_where;
    report_at(second, d, "give only one of rate, length or tension");
  }
  if (w.rate_given) check_increasing(w.rate, "times", d);
  if (w.length_given) {
    check_increasing(w.length, "times", d);
    for (const RowSpec& r : w.length)
      if (!(r.values[1] > 0)) report_at(r.where, d, "length must be > 0 (got " + fmt_num(r.values[1]) + ")");
  }
  if (w.tension.given) check_non_negative(w.tension, d);
  for (const Field<double>* f : {&w.max_speed, &w.max_acceleration, &w.max_length, &w.rating, &w.remove_at})
    check_positive(*f, d);
  for (const Field<double>* f : {&w.min_length, &w.drum_inertia, &w.damping}) check_non_negative(*f, d);
  if (w.split_at.value <= 1 + w.remove_at.value)
    report_at(w.split_at.given ? w.split_at.where : w.where, d,
              "split_at (" + fmt_num(w.split_at.value) + ") must be above 1 + remove_at (" +
                  fmt_num(w.remove_at.value) + ") so that a split element is not removed at once");
  if (w.min_length.given && w.max_length.given && w.max_length.value < w.min_length.value)
    report_at(w.max_length.where, d, "must be >= min_length (" + fmt_num(w.min_length.value) + ")");
  check_speeds(w, d);
  // What the winch does not do in this version.
  if (s.simulation.formulation.value == "paper")
    report_at(s.simulation.formulation.where, d,
              "the paper formulation has a fixed cable length: winch: needs formulation: default");
  // An elastic cable: the winch pays out into an elastic top element (its
  // unstretched length L_1 is the winch's coordinate). A rigid top section
  // over elastic ones is not supported (its l_1 would be both).
  const bool top_elastic = s.cable.axial_stiffness.given ||
                           (!s.cable.sections.empty() && s.cable.sections.front().axial_stiffness.given);
  if (!top_elastic)
    for (const SectionSpec& sec : s.cable.sections)
      if (sec.axial_stiffness.given)
        report_at(w.where, d,
                  "the top section must be elastic when another section is (axial_stiffness at " +
                      sec.axial_stiffness.where.path + ")");
  if (w.tension.given && s.tow.mode.value == "force")
    report_at(w.tension.where, d, "a tension-controlled winch needs tow.mode: motion (tow.mode is force)");
  if (s.initial.kind.value == "steady" && w.rate_given && !w.rate.empty() && w.rate.front().values[1] != 0 &&
      w.rate.front().values[0] <= 0)
    report_at(w.rate.front().where, d, "with initial: steady the pay-out speed at t = 0 must be 0");
}

void build_winch(const WinchSpec& w, Model& m) {
  Winch& win = m.winch;
  const auto& els = m.cable.elements;
  win.nominal_length = els.front().length;
  if (w.max_speed.given) win.max_speed = w.max_speed.value;
  if (w.max_acceleration.given) win.max_acceleration = w.max_acceleration.value;
  if (w.max_length.given) win.max_length = w.max_length.value;
  // The winch never hauls in the top section's last element.
  const int n_top = m.cable.sections.empty() ? m.cable.n() : m.cable.sections.front().elements;
  const double below = m.cable.total_length() - n_top * win.nominal_length;
  win.min_length = std::max(w.min_length.value, below + win.nominal_length);
  win.drum_inertia = w.drum_inertia.value;
  win.damping = w.damping.value;
  win.rating = w.rating.given ? w.rating.value : 0.0;
  win.split_at = w.split_at.value;
  win.remove_at = w.remove_at.value;
  std::vector<double> t, v;
  if (w.tension.given) {
    win.mode = Winch::Mode::Tension;
    win.tension = w.tension.value;
  } else if (w.rate_given && !w.rate.empty()) {
    win.mode = Winch::Mode::Imposed;
    columns(w.rate, t, v);
    win.schedule = schedule_from_rate(t, v, m.cable.total_length(), win.min_length, win.max_length);
  } else if (w.length_given && !w.length.empty()) {
    win.mode = Winch::Mode::Imposed;
    columns(w.length, t, v);
    win.schedule = schedule_from_length(t, v);
  }
}

bool check_winch_model(const WinchSpec& w, const Model& m, Diagnostics& d) {
  const std::size_t before = d.size();
  const double L0 = m.cable.total_length();
  const Winch& win = m.winch;
  if (w.length_given && !w.length.empty()) {
    const double at0 = winch_kinematics(win, 0.0).length;
    if (std::abs(at0 - L0) > 1e-9 * L0)
      report_at(w.length_where, d,
                "the length at t = 0 (" + fmt_num(at0) + " m) must be the cable's deployed length (" + fmt_num(L0) +
                    " m)");
    for (const RowSpec& r : w.length)
      if (r.values[1] < win.min_length * (1 - 1e-12) || r.values[1] > win.max_length * (1 + 1e-12))
        report_at(r.where, d,
                  "length " + fmt_num(r.values[1]) + " m is outside [" + fmt_num(win.min_length) + ", " +
                      fmt_num(win.max_length) + "] m (min_length, max_length; docs/scenario.md)");
  }
  if (w.max_length.given && L0 > w.max_length.value * (1 + 1e-12))
    report_at(w.max_length.where, d, "the cable's deployed length (" + fmt_num(L0) + " m) exceeds the drum's capacity");
  if (L0 < win.min_length * (1 - 1e-12))
    report_at(w.min_length.given ? w.min_length.where : w.where, d,
              "the cable's deployed length (" + fmt_num(L0) + " m) is below min_length (" + fmt_num(win.min_length) +
                  " m)");
  // Attachments inside the top section would go onto the drum.
  const int n_top = m.cable.sections.empty() ? m.cable.n() : m.cable.sections.front().elements;
  for (const Attachment& a : m.cable.attachments)
    if (a.joint >= 1 && a.joint < n_top)
      report_at(w.where, d,
                "attachments on the top section (at " + fmt_num(a.at) +
                    " m) are not supported with a winch: the winch pays out and hauls in that section");
  return d.size() == before;
}

}  // namespace towsim::scenario
