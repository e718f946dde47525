// `towsim check`: the waves and the vessel of a compiled model.
#pragma once

#include <ostream>

#include "towsim/model/model.hpp"

namespace towsim::cli {

/// "waves" and "vessel" blocks (nothing when the model has neither).
void describe_sea(const Model& m, std::ostream& out);

}  // namespace towsim::cli
