// Slack and snap bookkeeping of an elastic cable over a run (docs/theory.md
// §5.4, docs/scenario.md "Output files": summary.json `elastic`).
#pragma once

#include <limits>
#include <vector>

#include "towsim/model/model.hpp"

namespace towsim {

/// One slack episode: a time interval during which at least one elastic
/// element is slack, and the snap that follows it.
struct SlackEvent {
  double start = 0;         // first accepted step with a slack element [s]
  double end = 0;           // first accepted step with none again (the run's end if it never came taut) [s]
  int first_element = 0;    // highest slack element during the episode (1 = top) [-]
  int last_element = 0;     // lowest slack element [-]
  double from = 0, to = 0;  // unstretched arc length from the tow point: top of first_element, bottom of last [m]
  double min_strain = 0;    // most negative strain of a slack element [-]
  bool ended = false;       // false: still slack at the end of the run
  double snap_tension = 0;  // largest element tension after it came taut, until the next episode [N]
  double snap_time = std::numeric_limits<double>::quiet_NaN();  // when [s]
  int snap_element = 0;                                         // where (element index, 1 = top) [-]
};

/// Slack episodes and the peak element tension over a run, updated after
/// every accepted step from the elements' lengths and rates (so at the
/// integrator's resolution, not the output interval's).
class SlackRecord {
 public:
  /// An element counts as slack when its strain is below -kSlackStrain:
  /// well above round-off of an unstretched element (1e-16), far below any
  /// physical slack (a slack element shortens by centimetres, strain > 1e-6).
  static constexpr double kSlackStrain = 1e-9;
  static constexpr std::size_t kMaxEvents = 1000;  // episodes kept (all are counted)

  /// Account for the state at time t: lengths l_k [m] and rates l_k' [m/s]
  /// of every element (index k-1), given at the strain of the model's
  /// unstretched lengths. top_unstretched > 0: the top element's own
  /// unstretched length L_1 [m] (a winch over an elastic cable), which places
  /// the elements below it along the cable (from, to).
  void update(const Model& model, const std::vector<double>& length, const std::vector<double>& rate, double t,
              double top_unstretched = 0);
  /// Close an episode still open at the end of the run (time t).
  void finish(double t);

  const std::vector<SlackEvent>& events() const { return events_; }
  long episodes = 0;       // slack episodes counted (events() keeps the first kMaxEvents)
  double slack_time = 0;   // total time with some element slack [s]
  double max_tension = 0;  // largest element tension over the run [N]
  double max_tension_time = std::numeric_limits<double>::quiet_NaN();  // [s]
  int max_tension_element = 0;                                         // (1 = top; 0: never taut) [-]
  bool active() const { return active_; }

 private:
  std::vector<SlackEvent> events_;
  bool active_ = false;     // an episode is open
  double last_t_ = 0;       // time of the last update [s]
  bool snap_open_ = false;  // the last episode's snap is still being tracked
};

}  // namespace towsim
