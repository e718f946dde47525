// libFuzzer target: the sweep file reader (`towsim sweep`), up to the point
// where the cases would run.
//
// Input: the text of a sweep file. It is written to a scratch directory that
// also holds a valid base scenario (base.yaml), read (grid, cases, set,
// scenario or example, statics, write_cases), and its base scenario and first
// kMaxCheckedCases cases are loaded with their overrides, as `towsim sweep`
// checks them before running anything. Errors are fine; crashes, sanitizer
// reports, hangs (-timeout) and memory blow-ups (-rss_limit_mb) are not. The
// cases are never run.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sweep.hpp"

namespace {

std::string g_dir;  // scratch directory: base.yaml and the sweep file

void remove_dir() { std::filesystem::remove_all(g_dir); }

/// Cases loaded per input: each is a whole scenario load, and a grid of a
/// few short lists expands to 100000 cases; the expansion of every case
/// still runs (read_sweep).
constexpr std::size_t kMaxCheckedCases = 16;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_dir = (std::filesystem::temp_directory_path() / ("towsim_fuzz_sweep_" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(g_dir);
  std::ofstream(g_dir + "/base.yaml")
      << "cable: {length: 10, elements: 2, mass_per_length: 1, diameter: 0.01}\n"
         "tow:\n  motion:\n    - {type: ramp, direction: [1, 0, 0], speed: 1, ramp_time: 5}\n"
         "simulation: {duration: 1}\n";
  std::atexit(remove_dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = g_dir + "/sweep.yaml";
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::ostringstream err;
  const bool ok = towsim::cli::check_sweep_file(path, err, kMaxCheckedCases);
  // A valid sweep reports nothing, an invalid one at least one message.
  if (ok != err.str().empty()) std::abort();
  return 0;
}
