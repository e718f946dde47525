// YAML tree -> ScenarioSpec: structure, types, required and unknown keys.
// Ranges and physical consistency are checked later by compile().
#pragma once

#include <string>

#include "towsim/scenario/diagnostics.hpp"
#include "towsim/scenario/spec.hpp"
#include "towsim/scenario/yaml_tree.hpp"

namespace towsim::scenario {

/// Read a scenario tree into a spec. Every problem found is added to `diags`
/// (reading goes on after an error, so that all are reported). Track CSV files
/// are read relative to `base_dir`.
ScenarioSpec parse_scenario(const YNode& root, const std::string& base_dir, Diagnostics& diags);

/// Read a track CSV file (rows "time,x,y,z", header line optional, '#'
/// comments and blank lines skipped). `where` is the `file` key, used when the
/// file cannot be opened; errors inside name the CSV file and its line.
std::vector<RowSpec> read_track_csv(const std::string& file, const Where& where, Diagnostics& diags);

}  // namespace towsim::scenario
