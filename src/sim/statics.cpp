// TEMPORARY: statics solver not yet written.
#include "towsim/sim/statics.hpp"

#include <stdexcept>

namespace towsim {
StaticsResult steady_state(const Model&) { throw std::runtime_error("initial: steady is not implemented yet"); }
}  // namespace towsim
