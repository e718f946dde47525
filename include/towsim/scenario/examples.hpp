// The built-in example scenarios (scenarios/*.yaml, embedded at build time).
#pragma once

#include <string>
#include <vector>

namespace towsim::scenario {

/// One built-in scenario.
struct Example {
  std::string name;         // e.g. "paper-3d-turn" (the file stem)
  std::string description;  // its `description:` line
  std::string yaml;         // the file's text
};

/// The example run by scripts/run-example.sh.
inline constexpr const char* kDefaultExample = "paper-3d-turn";

/// Every built-in example, sorted by name.
const std::vector<Example>& examples();

/// The example called `name`, or nullptr.
const Example* find_example(const std::string& name);

}  // namespace towsim::scenario
