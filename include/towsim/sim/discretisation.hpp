// The element count's share of a run's error: the steady tow on the model's
// cable and on one with every element halved, and Richardson extrapolation
// (docs/theory.md §7.1 "Discretisation error estimate").
#pragma once

#include <string>

#include "towsim/model/model.hpp"
#include "towsim/sim/simulate.hpp"

namespace towsim {

/// Order p of the steady tow tension's convergence in the element length,
/// T_n - T = O(n^-p): measured 2.0 (ratios of successive differences 3.9 to
/// 4.1 once in the asymptotic range) on paper 5.1's tow, the 1 km 100-element
/// turn and the 1 km 1000-element cable (docs/validation.md) [-].
inline constexpr double kDiscretisationOrder = 2;
/// An estimate above this fraction of the tow tension is warned about [-].
inline constexpr double kDiscretisationWarnAbove = 0.01;
/// The accuracy the warning and `towsim check` advise an element count for [-].
inline constexpr double kAdvisedAccuracy = 1e-3;

/// The estimate and what it was made from.
struct DiscretisationEstimate {
  double estimate = -1;        // relative error of the steady tow tension with n elements [-]; < 0: none
  double tension = 0;          // steady tow tension |F_R| with the model's n elements [N]
  double refined_tension = 0;  // ... with every element halved (2n elements) [N]
  double speed = 0;            // steady tow speed solved at (the tow law's final velocity) [m/s]
  int elements = 0;            // n [-]
  bool proxy = false;          // the run has no steady state of its own (a turn without end, heave, waves,
                               // a winch): the steady tow at the final speed stands in for it
  bool interrupted = false;    // the stop flag ended a solve
  std::string message;         // why there is no estimate

  bool available() const { return estimate >= 0; }
};

/// An element count for a target accuracy.
struct ElementAdvice {
  int elements = -1;    // advised total count [-]; < 0: none (a solve failed)
  bool enough = false;  // the present count already meets the target
  bool beyond = false;  // the refinements stopped below the target: more than `elements`
};

/// True when the tow law or the model has no steady state of its own (a
/// turn without end, heave, waves, a winch): the steady tow at the final
/// speed then stands in for the run (DiscretisationEstimate::proxy).
bool needs_steady_proxy(const Model& model);

/// `model` with every element split into `factor` equal elements (same
/// section, per-length properties kept); joints of bodies, attachments and
/// sections keep their place on the cable.
Model refined_model(const Model& model, int factor);

/// The relative error of the steady tow tension due to the element count,
/// |T_n - T_2n| / (1 - 2^-p) / |T_n| with p = kDiscretisationOrder, from two
/// steady solves at the tow law's final velocity (solve_statics, O(n) each).
/// None in force mode (no tow law speed), when a solve fails or is
/// interrupted, or when the tension is zero.
DiscretisationEstimate estimate_discretisation_error(const Model& model, const volatile int* stop_flag = nullptr);

/// The element count for a relative error `accuracy` of the steady tow
/// tension: the cable refined by 2, 4, 8, ... (each section alike) until the
/// estimate at a level 2n meets it, then between n (the last level above it)
/// and 2n with the order p measured there (estimate_n / estimate_2n = 2^p):
/// n (estimate_n / accuracy)^(1/p). Each level is one more steady
/// solve; the estimates stop at max_refinement n (solves at twice that) or
/// solves of 20000 elements, 200 with a seabed (`beyond`). A run's warning
/// goes up to 8 n, `towsim check` up to 64 n.
ElementAdvice advise_elements(const Model& model, const DiscretisationEstimate& d, double accuracy, int max_refinement,
                              const volatile int* stop_flag = nullptr);

/// The warning the estimate calls for (above kDiscretisationWarnAbove, with
/// the advice for kAdvisedAccuracy; or a failed solve), one sentence; empty when none.
std::string discretisation_warning(const DiscretisationEstimate& d, const ElementAdvice& advice);

/// The estimate into stats.discretisation_error_estimate and its warning into
/// stats.warnings (an interrupted run gets none).
void record_discretisation_estimate(const Model& model, RunStats& stats, const volatile int* stop_flag = nullptr);

}  // namespace towsim
