// Loading a scenario end to end: YAML -> --set overrides -> spec -> Model.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "towsim/model/model.hpp"
#include "towsim/model/network.hpp"
#include "towsim/scenario/diagnostics.hpp"
#include "towsim/scenario/spec.hpp"
#include "towsim/scenario/yaml_tree.hpp"

namespace towsim::scenario {

/// A scenario read, overridden, checked and (when valid) compiled.
struct LoadedScenario {
  YNode tree;                      // the YAML after the --set overrides
  ScenarioSpec spec;               // as read
  std::optional<Model> model;      // a single chain, present when there is no error
  std::optional<Network> network;  // a network (`lines:`), present when there is no error
  Diagnostics diags;               // every error found

  /// True when the scenario is valid and compiled (a chain or a network).
  bool ok() const { return (model.has_value() || network.has_value()) && diags.ok(); }
  /// True for a network scenario (`lines:`): `model` is empty then.
  bool is_network() const { return spec.is_network(); }
};

/// Load a scenario file: parse it, apply the `--set KEY=VALUE` overrides in
/// order, read and check it, compile it. Relative track files are read from
/// the file's directory; the model's default name is the file's stem.
LoadedScenario load_scenario_file(const std::string& path, const std::vector<std::string>& sets = {});

/// The same from YAML text: `file` names it in messages, `name` is the
/// default model name, `base_dir` the directory of relative track files.
LoadedScenario load_scenario_text(const std::string& text, const std::string& file, const std::string& name,
                                  const std::string& base_dir, const std::vector<std::string>& sets = {});

}  // namespace towsim::scenario
