// Where each part of a formulation's flat state lies, derived from the model
// (docs/theory.md §6).
#pragma once

#include <cstddef>
#include <string>

#include "towsim/model/model.hpp"

namespace towsim {

/// A contiguous run of rows of the flat state.
struct StateBlock {
  std::size_t offset = 0;  // first row
  std::size_t size = 0;    // rows (0: the block is absent)
  std::size_t end() const { return offset + size; }
  bool contains(std::size_t i) const { return i >= offset && i < end(); }
};

/// The blocks of a flat state, in order. Default formulation: the tow point
/// [r0, v0], the elements' directions e_1..e_n and angular velocities
/// w_1..w_n, per body its quaternion (w, x, y, z) and angular velocity, the
/// winch's [l_1, l_1'] (over an elastic top element [L_1, L_1'], the paid-out
/// unstretched length), the elastic elements' [l_1..l_n, l_1'..l_n'], per
/// depth controller (bodies in order, surfaces in order) [I, delta]. Paper
/// formulation: the tow point, the angles q, their rates q', the charts
/// (per element its pole frame, then the body's; 9 entries each, column-major).
struct StateLayout {
  static constexpr std::size_t kBodyRows = 7;   // quaternion, angular velocity
  static constexpr std::size_t kChartRows = 9;  // a 3x3 frame

  std::size_t elements = 0;  // n [-]
  StateBlock tow;            // r0, v0
  StateBlock directions;     // e_k (default)
  StateBlock rates;          // w_k (default)
  StateBlock bodies;         // kBodyRows per body (default)
  StateBlock winch;          // l_1, l_1' or L_1, L_1' (default, with a winch)
  StateBlock lengths;        // l_k, then l_k' (default, elastic elements)
  StateBlock controls;       // I, delta per depth controller (default)
  StateBlock angles;         // q (paper)
  StateBlock angle_rates;    // q' (paper)
  StateBlock charts;         // kChartRows per element, then the body's (paper)
  std::size_t size = 0;      // rows in all [-]

  /// The default formulation's layout of the model's chain.
  static StateLayout default_of(const Model& model);
  /// The paper formulation's layout of the model's chain.
  static StateLayout paper_of(const Model& model);

  std::size_t direction(std::size_t k) const { return directions.offset + 3 * k; }
  std::size_t rate(std::size_t k) const { return rates.offset + 3 * k; }
  std::size_t body(std::size_t b) const { return bodies.offset + kBodyRows * b; }
  std::size_t length(std::size_t k) const { return lengths.offset + k; }
  std::size_t length_rate(std::size_t k) const { return lengths.offset + elements + k; }
  std::size_t control(std::size_t i) const { return controls.offset + 2 * i; }
  std::size_t chart(std::size_t k) const { return charts.offset + kChartRows * k; }

  /// What row i belongs to ("element 3", "body fish", "tow point").
  std::string describe(std::size_t i, const Model& model) const;
};

}  // namespace towsim
