// A persistent helper thread that runs one job at a time for the integrator
// (docs/performance.md "Concurrent step-end evaluations").
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>

#include "towsim/dynamics/fork.hpp"

namespace towsim {

/// One helper thread, started once and kept for the owner's lifetime. The
/// owner hands it a job, does its own work, then waits for the job; no
/// thread made per job. Idle, the helper sleeps on a futex
/// (std::atomic::wait); expect() wakes it ahead of a job, to spin for it:
/// on a VM, waking a sleeping thread takes about as long as the job.
/// After a job it spins for the next one a while (kLinger in worker.cpp):
/// the parts of one evaluation come every ~100 us (run_pair). As a Fork,
/// it runs one part of a pair when it has no job of the owner's pending
/// and takes it up before the caller has done the other, else the caller
/// runs both (a helper without a core, on a loaded machine, costs no wait).
class Worker final : public Fork {
 public:
  using Job = void (*)(void* context);

  Worker();
  ~Worker();
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  /// Run job(context) on the helper thread; returns at once. At most one
  /// job at a time: wait() before the next start().
  void start(Job job, void* context);
  /// A job comes soon: the helper leaves its sleep now and spins for it
  /// (for at most kExpectSpin, then sleeps again).
  void expect();
  /// Wait until the job started last has ended; rethrows what it threw.
  void wait();
  /// A job started and not waited for yet (the owner's view) [-].
  bool pending() const { return pending_; }
  /// Waits for a job that lasted over kStallWait after the owner got there
  /// (the helper had no core: another process holds it) [-]. The owner may
  /// then do without the helper (DefaultSystem: results are the same).
  int stalls() const { return stalls_; }
  /// Waits for a job so far (wait(), run_pair's included) [-].
  long waits() const { return waits_; }
  /// Fork: a on the helper, b on the caller, at once. The caller runs a
  /// too (after b) when the helper has not taken a up by then, and both
  /// (a, then b) while a job is pending or the helper has not yet taken up
  /// the previous pair's post.
  void run_pair(Part a, void* ca, Part b, void* cb) override;

 private:
  void loop();
  /// The helper's side of run_pair: a, unless the caller claimed it first.
  static void pair_job(void* self);
  /// Wait until the helper has taken up every post (a run_pair's the
  /// caller did itself included): before job_ and context_ change.
  void drain();

  Job job_ = nullptr;
  void* context_ = nullptr;
  bool pending_ = false;     // a job started and not waited for (the owner's) [-]
  int stalls_ = 0;           // waits over kStallWait (the owner's) [-]
  long waits_ = 0;           // waits for a job (the owner's) [-]
  bool unconsumed_ = false;  // a run_pair's post the caller did not wait for (the owner's) [-]
  Part pair_a_ = nullptr;    // run_pair's a and its context
  void* pair_ca_ = nullptr;
  std::atomic<bool> claimed_{false};      // run_pair's a taken up (by the helper or the caller) [-]
  std::exception_ptr error_;              // the last job's exception (written by the helper before done_)
  std::atomic<std::uint32_t> posted_{0};  // jobs handed over [-]
  std::atomic<std::uint32_t> done_{0};    // jobs ended [-]
  std::atomic<std::uint32_t> signal_{0};  // posts and expects: what the sleeping helper waits on [-]
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace towsim
