// The integrator's helper thread: hand-off by two counters (docs/performance.md
// "Concurrent step-end evaluations (h-pareval)").
#include "towsim/integrators/worker.hpp"

namespace towsim {

namespace {

// Spins before blocking on a counter. A futex wake-up costs ~5-50 us on a
// loaded machine against ~150 us for one evaluation at n = 1000: the side
// waiting for the other (both evaluations take about as long) spins this
// long first, then sleeps; a spin of ~1-2 us (x86, loads from cache) takes
// no core from other work for longer than a scheduler tick would.
constexpr int kSpins = 2000;  // [-]

/// Wait until `counter` differs from `old` (acquire).
void await_change(const std::atomic<std::uint32_t>& counter, std::uint32_t old) {
  for (int i = 0; i < kSpins; ++i)
    if (counter.load(std::memory_order_acquire) != old) return;
  while (counter.load(std::memory_order_acquire) == old) counter.wait(old, std::memory_order_acquire);
}

}  // namespace

Worker::Worker() : thread_([this] { loop(); }) {}

Worker::~Worker() {
  stop_.store(true, std::memory_order_relaxed);
  posted_.fetch_add(1, std::memory_order_release);
  posted_.notify_one();
  thread_.join();
}

void Worker::start(Job job, void* context) {
  job_ = job, context_ = context, error_ = nullptr;
  posted_.fetch_add(1, std::memory_order_release);  // publishes job_, context_ and the caller's inputs
  posted_.notify_one();
}

void Worker::wait() {
  // Each wait is on the value just seen: a job ending between the check and
  // the wait ends the wait at once (no lost wake-up).
  const std::uint32_t want = posted_.load(std::memory_order_relaxed);
  for (std::uint32_t d = done_.load(std::memory_order_acquire); d != want; d = done_.load(std::memory_order_acquire))
    await_change(done_, d);
  if (error_) std::rethrow_exception(error_);
}

void Worker::loop() {
  std::uint32_t seen = 0;
  for (;;) {
    await_change(posted_, seen);
    seen = posted_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_relaxed)) return;
    try {
      job_(context_);
    } catch (...) {
      error_ = std::current_exception();
    }
    done_.store(seen, std::memory_order_release);  // publishes the job's results
    done_.notify_one();
  }
}

}  // namespace towsim
