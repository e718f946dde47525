// libFuzzer target: the scenario reader, end to end, without simulating.
//
// Input: YAML text, optionally followed by NUL-separated `--set KEY=VALUE`
// overrides ("cable: ...\0cable.elements=3\0simulation.duration=2").
// It is loaded like `towsim check` does (parse -> --set -> read -> compile),
// then the diagnostics, the JSON echo and (when valid) the derived quantities
// are formatted (the accuracy section's steady solves on small cables only).
// Errors are fine; crashes, sanitizer reports, hangs (-timeout) and memory
// blow-ups (-rss_limit_mb) are not.
//
// Relative track files are read from a scratch directory holding a valid
// track.csv and a broken bad.csv, so that inputs can reach the track reader.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/scenario/yaml_tree.hpp"

namespace {

std::string g_dir;  // scratch directory for relative track files

void remove_dir() { std::filesystem::remove_all(g_dir); }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_dir = (std::filesystem::temp_directory_path() / ("towsim_fuzz_scenario_" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(g_dir);
  std::ofstream(g_dir + "/track.csv") << "time,x,y,z\n0,0,0,0\n10,20,0,0\n20,40,5,-1\n30,60,10,-1\n";
  std::ofstream(g_dir + "/bad.csv") << "# broken\n0,0,0,0\n1,x,0\n1,2,3,4\n";
  std::atexit(remove_dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string in(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t nul = in.find('\0', start);
    parts.push_back(in.substr(start, nul == std::string::npos ? std::string::npos : nul - start));
    if (nul == std::string::npos) break;
    start = nul + 1;
  }
  const std::string yaml = parts.front();
  const std::vector<std::string> sets(parts.begin() + 1, parts.end());

  const auto s = towsim::scenario::load_scenario_text(yaml, "fuzz.yaml", "fuzz", g_dir, sets);
  std::ostringstream out;
  out << s.diags.str();
  // As summary.json is written (output.cpp write_summary).
  out << towsim::scenario::to_json(s.tree).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  // The accuracy section's steady solves only on small cables: their cost
  // grows with the element count (8 s at 100000 elements in Release), and a
  // big model is not what this target looks for.
  constexpr int kMaxSolvedElements = 50;
  if (s.ok()) towsim::cli::describe_model(*s.model, out, s.model->cable.n() <= kMaxSolvedElements);
  // A valid scenario reports no error and an invalid one at least one.
  if (s.ok() != s.diags.ok()) std::abort();
  return 0;
}
