#include "towsim/scenario/scenario.hpp"

#include <filesystem>

#include "towsim/scenario/compile.hpp"
#include "towsim/scenario/parse.hpp"

namespace towsim::io {
namespace {

/// Apply the overrides, read the spec and compile, after the YAML was loaded.
void finish_loading(LoadedScenario& s, const std::string& name, const std::string& base_dir,
                    const std::vector<std::string>& sets) {
  const bool loaded = s.diags.ok();
  for (std::size_t i = 0; i < sets.size(); ++i) apply_set(s.tree, sets[i], static_cast<int>(i) + 1, s.diags);
  if (!loaded) return;
  s.spec = parse_scenario(s.tree, base_dir, s.diags);
  if (s.spec.name.empty()) s.spec.name = name;
  auto model = compile(s.spec, s.diags);
  if (s.diags.ok()) s.model = std::move(model);
}

}  // namespace

LoadedScenario load_scenario_file(const std::string& path, const std::vector<std::string>& sets) {
  LoadedScenario s;
  s.diags.set_primary(path);
  s.tree = load_yaml_file(path, s.diags);
  const std::filesystem::path p(path);
  finish_loading(s, p.stem().string(), p.parent_path().string(), sets);
  return s;
}

LoadedScenario load_scenario_text(const std::string& text, const std::string& file, const std::string& name,
                                  const std::string& base_dir, const std::vector<std::string>& sets) {
  LoadedScenario s;
  s.diags.set_primary(file);
  s.tree = parse_yaml(text, file, s.diags);
  finish_loading(s, name, base_dir, sets);
  return s;
}

}  // namespace towsim::io
