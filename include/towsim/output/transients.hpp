// Transient figures per manoeuvre phase (summary.json `phases`,
// docs/scenario.md "Outputs"): extremes within each phase and the time its
// response takes to settle, collected on the fly from the rows a run writes.
#pragma once

#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "towsim/sim/phases.hpp"

namespace towsim::output {

/// The settling band is the largest of: this fraction of the change over the
/// window (settled value - first value) [-] ...
inline constexpr double kSettleChangeFraction = 0.02;
/// ... for tensions, this fraction of the settled value [-] (half the 1 %
/// of the tow tension above which towsim warns that the element count's
/// error alone is large: discretisation_error_estimate) ...
inline constexpr double kSettleValueFraction = 0.005;
/// ... and an absolute floor: tensions [N] (a tenth of a newton: the weight
/// of 10 g, below any towing load) ...
inline constexpr double kSettleTensionFloor = 0.1;
/// ... depths [m] (ten centimetres: about what a towfish's depth sensor resolves).
inline constexpr double kSettleDepthFloor = 0.1;
/// A signal counts as settled only when it then stays within the band for at
/// least this fraction of the window's length [-]: a value held for less is
/// a passing value, the window ended before the response flattened.
inline constexpr double kSettleHoldFraction = 0.2;

/// The settling of one signal over a window, on the fly and in little memory:
/// the staircases of its suffix maxima and minima (the samples above, or
/// below, every later one), which say at the end, for any band around the
/// last value, the last sample outside it.
class Settling {
 public:
  /// One sample, in time order [s], [any unit].
  void add(double t, double v);
  /// The outcome for a band: band = max(change_fraction |last - first|,
  /// value_fraction |last|, floor).
  struct Result {
    double first = std::numeric_limits<double>::quiet_NaN();    // the window's first value
    double settled = std::numeric_limits<double>::quiet_NaN();  // its last value
    double band = std::numeric_limits<double>::quiet_NaN();     // half-width of the band
    double since = std::numeric_limits<double>::quiet_NaN();    // the first sample time from which every
                                                                // later one is within the band; NaN: not
                                                                // settled (see result()) [s]
  };
  /// The band and the time the signal settles in it. Not settled (since =
  /// NaN): fewer than two samples, or the band held for less than
  /// hold_fraction of (last sample time - window_start).
  Result result(double change_fraction, double value_fraction, double floor, double hold_fraction,
                double window_start) const;
  long samples() const { return samples_; }

 private:
  struct Step {
    double t, v;
    double t_next;  // the time of the sample after it [s]
  };
  std::vector<Step> hi_, lo_;  // suffix maxima (values falling with time), suffix minima (rising)
  double first_ = std::numeric_limits<double>::quiet_NaN();
  double first_t_ = 0, last_t_ = 0, last_ = 0;
  long samples_ = 0;
};

/// The phases of a run and their figures, from the written rows.
class TransientRecord {
 public:
  /// `phases` as run_phases gives them for a run of `duration` [s]; `link`:
  /// the rows have a link tension (an end body).
  TransientRecord(std::vector<Phase> phases, double duration, bool link);
  /// One row's values as written: time [s], tow tension [N], depth of the
  /// end body's origin or of the cable's end [m], link tension [N] (ignored
  /// without `link`). A sample belongs to a phase when start <= t < end (t
  /// <= end when the phase ends with the run), to its settling window when
  /// start <= t < settle_end (the same): the loads written at a boundary
  /// are those of the inputs from then on (an imposed acceleration that
  /// starts there makes the tow tension jump at that very sample).
  void add(double t, double tow_tension, double depth, double link_tension);
  /// summary.json `phases` for a run that reached `end_time` [s]: windows
  /// it did not reach (an interrupted run) have no settled values.
  nlohmann::ordered_json json(double end_time) const;
  const std::vector<Phase>& phases() const { return phases_; }

 private:
  struct Quantity {
    double min = std::numeric_limits<double>::quiet_NaN(), min_t = 0;
    double max = std::numeric_limits<double>::quiet_NaN(), max_t = 0;
    Settling settling;
  };
  struct Figures {
    Quantity q[3];  // tow tension, depth, link tension
  };
  std::vector<Phase> phases_;  // times tidied as written
  std::vector<Figures> figures_;
  double duration_ = 0;  // [s], tidied
  bool link_ = false;
};

}  // namespace towsim::output
