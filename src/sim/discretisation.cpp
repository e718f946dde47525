// The element count's share of the error (docs/theory.md §7.1): steady tows on refined cables and Richardson
// extrapolation.
#include "towsim/sim/discretisation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "towsim/sim/statics.hpp"
#include "towsim/sim/touchdown.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim {

namespace {

constexpr int kMaxAdviceElements = 20000;      // advise_elements: largest element count solved [-]
constexpr int kMaxSeabedAdviceElements = 200;  // ... with a seabed, whose steady solve is dense (~n^3: 0.4 s at
                                               // 160 elements on the bottom, 4 s at 320) [-]
constexpr int kRunRefinement = 8;              // a run's advice: largest refinement factor [-]

/// A fraction as a percentage with two significant digits ("1.2 %").
std::string percent(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2g %%", 100 * x);
  return b;
}

/// Richardson's error of T_n from T_n and T_2n, relative to T_n [-].
double richardson(double Tn, double T2n) {
  return std::abs(Tn - T2n) / (1 - std::pow(2.0, -kDiscretisationOrder)) / Tn;
}

}  // namespace

bool needs_steady_proxy(const Model& model) {
  if (has_sea(model) || model.winch.active()) return true;
  return std::any_of(model.tow.pieces.begin(), model.tow.pieces.end(), [](const auto& piece) {
    if (std::holds_alternative<Heave>(piece)) return true;
    const auto* turn = std::get_if<Turn>(&piece);
    return turn != nullptr && !std::isfinite(turn->angle);
  });
}

Model refined_model(const Model& model, int factor) {
  Model m = model;
  const auto f = static_cast<std::size_t>(factor);
  m.cable.elements.clear();
  m.cable.elements.reserve(model.cable.elements.size() * f);
  for (const Element& el : model.cable.elements)
    for (std::size_t i = 0; i < f; ++i) m.cable.elements.push_back(scaled_element(el, el.length / factor));
  for (Section& s : m.cable.sections) {
    s.first_element *= factor;
    s.elements *= factor;
  }
  for (Attachment& a : m.cable.attachments) a.joint *= factor;
  for (Body& b : m.bodies)
    if (b.joint >= 0) b.joint *= factor;
  if (m.winch.active()) m.winch.nominal_length /= factor;
  return m;
}

DiscretisationEstimate estimate_discretisation_error(const Model& model, const volatile int* stop_flag) {
  DiscretisationEstimate d;
  d.elements = model.cable.n();
  if (model.tow.mode != Tow::Mode::Motion) {
    d.message = "tow.mode: force has no tow law speed to solve a steady tow at";
    return d;
  }
  const Vec3 V = final_tow_velocity(model.tow);
  d.speed = V.norm();
  d.proxy = needs_steady_proxy(model);
  // The steady tow with n elements, then with 2n (over a flat seabed each
  // with its touchdown joint, as `towsim statics` and a steady start have it).
  const StaticsResult coarse = touchdown_statics(model, V, stop_flag).statics;
  const StaticsResult fine = coarse.converged ? touchdown_statics(refined_model(model, 2), V, stop_flag).statics
                                              : StaticsResult{};
  d.interrupted = coarse.interrupted || fine.interrupted;
  if (d.interrupted) {
    d.message = "interrupted";
    return d;
  }
  if (!coarse.converged || !fine.converged) {
    const StaticsResult& failed = coarse.converged ? fine : coarse;
    d.message = "the steady tow at " + std::to_string(coarse.converged ? 2 * d.elements : d.elements) +
                " elements did not converge (" + failed.message + ")";
    return d;
  }
  d.tension = coarse.tow_force.norm();
  d.refined_tension = fine.tow_force.norm();
  if (!(d.tension > 0)) {
    d.message = "no steady tow tension";
    return d;
  }
  d.estimate = richardson(d.tension, d.refined_tension);
  return d;
}

ElementAdvice advise_elements(const Model& model, const DiscretisationEstimate& d, double accuracy, int max_refinement,
                              const volatile int* stop_flag) {
  ElementAdvice a;
  if (!d.available()) return a;
  if (d.estimate <= accuracy) {
    a.elements = d.elements;
    a.enough = true;
    return a;
  }
  // Levels of f n elements, f = 1, 2, 4, ...: the estimate at f n from the
  // tensions at f n and 2 f n, until one meets the accuracy (`below`, at 2 f n).
  const Vec3 V = final_tow_velocity(model.tow);
  const int max_elements = model.seabed ? kMaxSeabedAdviceElements : kMaxAdviceElements;
  int f = 1;
  double T2 = d.refined_tension, est = d.estimate, below = -1;
  while (2 * f <= max_refinement && 4 * f * d.elements <= max_elements) {
    const StaticsResult r = touchdown_statics(refined_model(model, 4 * f), V, stop_flag).statics;
    if (!r.converged) return a;
    const double T4 = r.tow_force.norm();
    const double next = richardson(T2, T4);
    if (next <= accuracy) {
      below = next;
      break;
    }
    f *= 2, T2 = T4, est = next;
  }
  const int n = f * d.elements;
  if (below < 0) {
    a.elements = n;
    a.beyond = true;
    return a;
  }
  // Between n and 2n, with the order measured there: the estimate falls by
  // est / below over the doubling (2^p, p = 2 once asymptotic).
  const double p = below > 0 && est > below ? std::log2(est / below) : 0;
  a.elements = p > 0 ? static_cast<int>(std::ceil(n * std::pow(est / accuracy, 1 / p))) : 2 * n;
  a.elements = std::min(a.elements, 2 * n);
  return a;
}

std::string discretisation_warning(const DiscretisationEstimate& d, const ElementAdvice& advice) {
  if (d.interrupted) return {};
  if (!d.available()) {
    // Force mode has no estimate by design; a failed solve is worth saying.
    if (d.message.rfind("tow.mode", 0) == 0) return {};
    return "no discretisation error estimate: " + d.message;
  }
  if (d.estimate <= kDiscretisationWarnAbove) return {};
  std::string w = "discretisation error estimate " + percent(d.estimate) + " of the tow tension exceeds " +
                  percent(kDiscretisationWarnAbove) + ": use more elements";
  if (advice.elements > 0)
    w += std::string(" (") + (advice.beyond ? "more than " : "about ") + std::to_string(advice.elements) + " for " +
         percent(kAdvisedAccuracy) + ")";
  if (d.proxy) w += "; from the steady tow at the final speed, which stands in for this run's unsteady conditions";
  return w;
}

void record_discretisation_estimate(const Model& model, RunStats& stats, const volatile int* stop_flag) {
  if (stats.status == "interrupted") return;
  const DiscretisationEstimate d = estimate_discretisation_error(model, stop_flag);
  stats.discretisation_error_estimate = d.estimate;
  // The advice costs further solves: only with a warning.
  const ElementAdvice advice = d.available() && d.estimate > kDiscretisationWarnAbove
                                   ? advise_elements(model, d, kAdvisedAccuracy, kRunRefinement, stop_flag)
                                   : ElementAdvice{};
  if (const std::string w = discretisation_warning(d, advice); !w.empty()) stats.warnings.push_back(w);
}

}  // namespace towsim
