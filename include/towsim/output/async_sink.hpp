// A sink that hands samples to another sink on its own thread
// (docs/performance.md "Output on its own thread").
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "towsim/sim/simulate.hpp"

namespace towsim::output {

/// Passes every sample, in order, to `inner` on a writer thread, so that
/// formatting and writing the files (RunWriter: a sixth of paper-3d-turn's
/// work) overlap the integration. Samples are copied into a batch, handed
/// over when it holds kBatch of them or kHandEvery after the last hand-over,
/// into a ring of kDepth batches: the run waits only when the writer is
/// kDepth - 1 batches behind (never drops a sample). The writer sleeps when
/// it has nothing to write (no spinning). What `inner` throws is rethrown by
/// the next write() or flush() on the caller's thread. `inner` is used by the
/// writer thread only: read it (extremes, last row) after flush().
class AsyncSink final : public OutputSink {
 public:
  /// Samples per hand-over [-]
  static constexpr std::size_t kBatch = 64;
  /// ... or this long after the last hand-over [wall time]
  static constexpr std::chrono::milliseconds kHandEvery{100};
  /// Batches in the ring: the one filling and up to kDepth - 1 to write [-]
  static constexpr std::size_t kDepth = 4;

  explicit AsyncSink(OutputSink& inner);
  /// Writes what is pending (errors dropped: call flush() to see them), then
  /// ends the thread.
  ~AsyncSink() override;
  AsyncSink(const AsyncSink&) = delete;
  AsyncSink& operator=(const AsyncSink&) = delete;

  /// Copy the sample into the batch; hand the batch over when due.
  void write(const Sample& s) override;
  /// Hand over what is pending, wait until the writer has written it, then
  /// flush `inner` (on this thread); rethrows what `inner` threw.
  void flush() override;

 private:
  /// One batch of samples (their storage reused around the ring).
  struct Batch {
    std::vector<Sample> samples;
    std::size_t count = 0;  // samples in use [-]
  };
  /// Give the writer the filling batch; first wait for a free one.
  void hand_over();
  /// Wait until `done` holds; rethrow (once) what `inner` threw.
  template <class Done>
  void wait_for(std::unique_lock<std::mutex>& lock, Done done);
  /// The writer thread: write each batch handed over, until stopped.
  void run();

  OutputSink& inner_;
  std::vector<Batch> ring_;  // kDepth batches: [next_, next_ + queued_) to write, then the filling one
  std::size_t fill_ = 0;     // the batch the caller fills (not in the writer's range) [-]
  std::chrono::steady_clock::time_point last_hand_;
  std::mutex mutex_;
  std::condition_variable changed_;  // queued_ or stop_ changed
  std::size_t next_ = 0;             // the next batch to write [-]
  std::size_t queued_ = 0;           // batches handed over and not yet written [-]
  bool stop_ = false;                // the writer ends when nothing is queued
  std::exception_ptr error_;         // what inner_ threw, until rethrown
  bool failed_ = false;              // inner_ threw: later batches are dropped
  std::thread thread_;               // started last: every member above exists
};

}  // namespace towsim::output
