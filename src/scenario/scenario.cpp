#include "towsim/scenario/scenario.hpp"

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "towsim/scenario/compile.hpp"
#include "towsim/scenario/parse.hpp"

namespace towsim::scenario {
namespace {

/// Compile a chain or a network, as the spec is.
void compile_any(const ScenarioSpec& spec, Diagnostics& d, LoadedScenario* into = nullptr) {
  if (spec.is_network()) {
    auto net = compile_network(spec, d);
    if (into != nullptr && d.ok()) into->network = std::move(net);
    return;
  }
  auto model = compile(spec, d);
  if (into != nullptr && d.ok()) into->model = std::move(model);
}

/// The errors of `tree` with the overrides `only` (ranks from 1, as given) applied, as text.
std::set<std::string> errors_with(YNode tree, const std::string& base_dir, const std::vector<std::string>& sets,
                                  const std::vector<std::size_t>& only) {
  Diagnostics d;
  for (std::size_t i : only) apply_set(tree, sets[i], static_cast<int>(i) + 1, d);
  const ScenarioSpec spec = parse_scenario(tree, base_dir, d);
  compile_any(spec, d);
  std::set<std::string> out;
  for (const auto& e : d.list()) out.insert(e.str());
  return out;
}

/// Errors found in the scenario file that only the overrides cause (a turn
/// left without speed by --set tow.motion.0.speed=0) point at the override
/// that causes them (or the last one, when no single one does), naming it and
/// the file's place. Errors in other files (a track file an override names)
/// keep their own line.
Diagnostics blame_overrides(const Diagnostics& diags, const YNode& tree, const std::string& base_dir,
                            const std::vector<std::string>& sets) {
  Diagnostics out;
  out.set_primary(diags.primary());
  const std::set<std::string> plain = errors_with(tree, base_dir, sets, {});
  std::vector<std::set<std::string>> single;  // each override alone, computed when first needed
  for (const auto& e : diags.list()) {
    if (e.loc.file != diags.primary() || plain.count(e.str()) != 0) {  // a track file's line stays the place
      out.error(e.loc, e.path, e.message);
      continue;
    }
    if (single.empty())
      for (std::size_t i = 0; i < sets.size(); ++i) single.push_back(errors_with(tree, base_dir, sets, {i}));
    std::size_t culprit = sets.size() - 1;
    for (std::size_t i = 0; i < sets.size(); ++i)
      if (single[i].count(e.str()) != 0) {
        culprit = i;
        break;
      }
    const std::string& set = sets[culprit];
    const auto eq = set.find('=');
    const SourceLoc at{"--set", static_cast<int>(culprit) + 1, static_cast<int>(eq) + 2};
    out.error(at, e.path,
              e.message + " [caused by --set " + set + "; see " + e.loc.file + ":" + std::to_string(e.loc.line) + ":" +
                  std::to_string(e.loc.col) + "]");
  }
  return out;
}

/// Apply the overrides, read the spec and compile, after the YAML was loaded.
void finish_loading(LoadedScenario& s, const std::string& name, const std::string& base_dir,
                    const std::vector<std::string>& sets) {
  const bool loaded = s.diags.ok();
  const YNode plain = sets.empty() ? YNode{} : s.tree;
  for (std::size_t i = 0; i < sets.size(); ++i) apply_set(s.tree, sets[i], static_cast<int>(i) + 1, s.diags);
  if (!loaded) return;
  s.spec = parse_scenario(s.tree, base_dir, s.diags);
  if (s.spec.name.empty()) s.spec.name = name;
  compile_any(s.spec, s.diags, &s);
  if (!s.diags.ok() && !sets.empty()) {
    s.diags = blame_overrides(s.diags, plain, base_dir, sets);
  }
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

}  // namespace towsim::scenario
