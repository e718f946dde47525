// ScenarioSpec -> Model: range and consistency checks, then the build.
#pragma once

#include <optional>

#include "towsim/model/model.hpp"
#include "towsim/model/network.hpp"
#include "towsim/scenario/diagnostics.hpp"
#include "towsim/scenario/spec.hpp"

namespace towsim::scenario {

/// Check every value of `spec` (ranges, unit vectors, inertia, tables, tow
/// pieces) and report all problems to `diags`. When there are none, build and
/// return the Model (elements through make_element, the body through
/// finalize_body, the tow's course through finalize_tow); otherwise return
/// nothing. Values already reported by the parser (not `given`) are not
/// checked again.
std::optional<Model> compile(const ScenarioSpec& spec, Diagnostics& diags);

/// A network (`lines:`, docs/scenario.md "Networks"): check the names and
/// the lines' ends (tow points, junctions, bodies' points, loops, winches),
/// order the lines so that each comes after the line it hangs from, and
/// compile each line as a single chain with compile() (its cable, the body
/// or junction at its end, its winch; the scenario's other sections), its
/// errors under the line's keys, errors common to the lines once. Returns
/// nothing when there is an error.
std::optional<Network> compile_network(const ScenarioSpec& spec, Diagnostics& diags);

}  // namespace towsim::scenario
