// The integrator's helper thread: hand-off by two counters (docs/performance.md
// "Concurrent step-end evaluations").
#include "towsim/integrators/worker.hpp"

#include <chrono>
#include <thread>

namespace towsim {

namespace {

// A futex wake-up (std::atomic::wait/notify) of an idle vCPU costs ~100 us
// here, about one evaluation at n = 1000: a side that waits spins first.
// The helper spins up to kExpectSpin after expect() (the integrator calls it
// ~300 us ahead of the job at n = 1000), the owner up to kWaitSpin for a job
// running next to its own work (both take about as long); then they sleep.
// After a job the helper spins kLinger for the next: with run_pair (the
// loads of every evaluation) jobs come ~100 us apart at n = 1000, so
// during a run with threads 2 the helper spins through (one core busy);
// kLinger after the run's last job it sleeps.
constexpr auto kExpectSpin = std::chrono::microseconds(2000);
constexpr auto kWaitSpin = std::chrono::microseconds(2000);
constexpr auto kLinger = std::chrono::microseconds(1000);
// A wait longer than this for a job is a stall: a job takes ~0.05-0.3 ms at
// n = 1000; a helper without a core waits for a scheduler slice (~3 ms).
constexpr auto kStallWait = std::chrono::microseconds(1000);

/// A spin-wait hint to the core (x86 pause), else nothing.
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/// Spin until `counter` differs from `old` (acquire) or `budget` has passed;
/// true if it changed. With `yield`, the core goes to any other runnable
/// thread every 64 turns (a loaded machine's: the spinner does not hold it).
bool spin_for_change(const std::atomic<std::uint32_t>& counter, std::uint32_t old, std::chrono::microseconds budget,
                     bool yield = false) {
  const auto end = std::chrono::steady_clock::now() + budget;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (counter.load(std::memory_order_acquire) != old) return true;
      relax();
    }
    if (std::chrono::steady_clock::now() >= end) return false;
    if (yield) std::this_thread::yield();
  }
}

/// Wait until `counter` differs from `old` (acquire): a spin of `budget`,
/// then a futex wait.
void await_change(const std::atomic<std::uint32_t>& counter, std::uint32_t old, std::chrono::microseconds budget) {
  if (spin_for_change(counter, old, budget)) return;
  while (counter.load(std::memory_order_acquire) == old) counter.wait(old, std::memory_order_acquire);
}

/// Wait until `counter` reads `want` (acquire). Each wait is on the value
/// just seen: a change between the check and the wait ends it at once (no
/// lost wake-up).
void await_value(const std::atomic<std::uint32_t>& counter, std::uint32_t want) {
  for (std::uint32_t d = counter.load(std::memory_order_acquire); d != want;
       d = counter.load(std::memory_order_acquire))
    await_change(counter, d, kWaitSpin);
}

}  // namespace

Worker::Worker() : thread_([this] { loop(); }) {}

Worker::~Worker() {
  stop_.store(true, std::memory_order_relaxed);
  posted_.fetch_add(1, std::memory_order_release);
  signal_.fetch_add(1, std::memory_order_release);
  signal_.notify_one();
  thread_.join();
}

void Worker::start(Job job, void* context) {
  drain();
  job_ = job, context_ = context, error_ = nullptr;
  pending_ = true;
  posted_.fetch_add(1, std::memory_order_release);  // publishes job_, context_ and the caller's inputs
  signal_.fetch_add(1, std::memory_order_release);  // after posted_: a helper woken by it sees the job
  signal_.notify_one();
}

void Worker::expect() {
  signal_.fetch_add(1, std::memory_order_release);
  signal_.notify_one();
}

void Worker::wait() {
  const std::uint32_t want = posted_.load(std::memory_order_relaxed);
  ++waits_;
  if (done_.load(std::memory_order_acquire) != want) {
    // Not done yet: wait, timed (a long wait counts as a stall).
    const auto since = std::chrono::steady_clock::now();
    await_value(done_, want);
    if (std::chrono::steady_clock::now() - since > kStallWait) ++stalls_;
  }
  pending_ = false;
  if (error_) std::rethrow_exception(error_);
}

void Worker::drain() {
  if (!unconsumed_) return;
  await_value(done_, posted_.load(std::memory_order_relaxed));
  unconsumed_ = false;
}

void Worker::pair_job(void* self) {
  auto& w = *static_cast<Worker*>(self);
  if (!w.claimed_.exchange(true, std::memory_order_acq_rel)) w.pair_a_(w.pair_ca_);
}

void Worker::run_pair(Part a, void* ca, Part b, void* cb) {
  // Busy with the owner's job, or the last pair's post not taken up yet
  // (the helper has had no core since): serially, as without a fork.
  if (pending_ || (unconsumed_ && done_.load(std::memory_order_acquire) != posted_.load(std::memory_order_relaxed))) {
    a(ca);
    b(cb);
    return;
  }
  unconsumed_ = false;
  pair_a_ = a, pair_ca_ = ca;
  claimed_.store(false, std::memory_order_relaxed);
  start(&pair_job, this);  // publishes pair_a_, pair_ca_ and claimed_
  // b here meanwhile; a's failure first (serially it comes first).
  std::exception_ptr error;
  try {
    b(cb);
  } catch (...) {
    error = std::current_exception();
  }
  if (!claimed_.exchange(true, std::memory_order_acq_rel)) {
    // The helper has not taken a up: here too (its post, taken up later,
    // does nothing; drain() before the next start()).
    pending_ = false;
    unconsumed_ = true;
    a(ca);
  } else {
    wait();
  }
  if (error) std::rethrow_exception(error);
}

void Worker::loop() {
  std::uint32_t seen = 0, signals = 0;
  bool hot = false;  // a job just ended: spin kLinger for the next before sleeping
  for (;;) {
    // Sleep until a post or an expect, then spin for the post a while (a
    // post after the spin changes signal_ again: no lost wake-up).
    if (!hot) {
      await_change(signal_, signals, std::chrono::microseconds(2));
      signals = signal_.load(std::memory_order_acquire);
    }
    const bool posted = spin_for_change(posted_, seen, hot ? kLinger : kExpectSpin, true);
    hot = false;
    if (!posted) continue;
    seen = posted_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_relaxed)) return;
    try {
      job_(context_);
    } catch (...) {
      error_ = std::current_exception();
    }
    // The signals so far are this job's: sleep at the next turn (read before
    // done_, so the owner's next post, after it, is a change).
    signals = signal_.load(std::memory_order_acquire);
    done_.store(seen, std::memory_order_release);  // publishes the job's results
    done_.notify_one();
    hot = true;
  }
}

}  // namespace towsim
