// A persistent helper thread that runs one job at a time for the integrator
// (docs/performance.md "Concurrent step-end evaluations (h-pareval)").
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>

namespace towsim {

/// One helper thread, started once and kept for the owner's lifetime. The
/// owner hands it a job, does its own work, then waits for the job; no
/// thread made per job. Idle, the helper sleeps on a futex
/// (std::atomic::wait); expect() wakes it ahead of a job, to spin for it:
/// on a VM, waking a sleeping thread takes about as long as the job.
class Worker {
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

 private:
  void loop();

  Job job_ = nullptr;
  void* context_ = nullptr;
  std::exception_ptr error_;              // the last job's exception (written by the helper before done_)
  std::atomic<std::uint32_t> posted_{0};  // jobs handed over [-]
  std::atomic<std::uint32_t> done_{0};    // jobs ended [-]
  std::atomic<std::uint32_t> signal_{0};  // posts and expects: what the sleeping helper waits on [-]
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace towsim
