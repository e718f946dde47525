// libFuzzer target: the track CSV reader (`tow.motion[].file`).
//
// Input: the bytes of a track file. The first byte picks how it is used:
//   even: the track alone, tow.motion = [{type: track, file: F}]
//   odd:  after a ramp and before a turn starting at a time taken from the
//         second byte, so that the compile-time turn check interpolates it.
// The rest is written to a scratch file F and loaded through the scenario
// reader (read_track_csv -> row checks -> compile). When the scenario is
// valid, the interpolated tow motion is evaluated at a few times (the spline
// that the simulation would use). Errors are fine; crashes, sanitizer
// reports, hangs and memory blow-ups are not.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "towsim/scenario/scenario.hpp"

namespace {

std::string g_file;  // the scratch track file

void remove_file() { std::remove(g_file.c_str()); }

const char* kHead =
    "cable: {length: 100, elements: 5, mass_per_length: 1.5, diameter: 0.019}\n"
    "simulation: {duration: 10}\n";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_file =
      (std::filesystem::temp_directory_path() / ("towsim_fuzz_track_" + std::to_string(::getpid()) + ".csv")).string();
  std::atexit(remove_file);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const bool with_turn = (data[0] & 1) != 0;
  const double turn_start = data[1] / 8.0;
  std::FILE* f = std::fopen(g_file.c_str(), "wb");
  if (f == nullptr) std::abort();
  std::fwrite(data + 2, 1, size - 2, f);
  std::fclose(f);

  std::string yaml = std::string(kHead) + "tow:\n  motion:\n";
  if (with_turn) yaml += "    - {type: ramp, direction: [1, 0, 0], speed: 2, ramp_time: 5}\n";
  yaml += "    - {type: track, file: '" + g_file + "'}\n";
  if (with_turn) yaml += "    - {type: turn, radius: 10, start_time: " + std::to_string(turn_start) + "}\n";

  const auto s = towsim::scenario::load_scenario_text(yaml, "fuzz.yaml", "fuzz", "", {});
  (void)s.diags.str();
  if (s.ok() != s.diags.ok()) std::abort();
  if (!s.ok()) return 0;
  const auto& tow = s.model->tow;
  double sum = 0;
  for (double t : {-1.0, 0.0, 0.5, 1.0, 3.0, 7.5, 12.0, 100.0}) {
    const auto k = towsim::tow_kinematics(tow, t);
    sum += k.pos.sum() + k.vel.sum() + k.acc.sum();
  }
  volatile double sink = sum;  // keep the evaluations
  (void)sink;
  return 0;
}
