// Samples handed to another sink on a writer thread (async_sink.hpp).
#include "towsim/output/async_sink.hpp"

#include <utility>

namespace towsim::output {

AsyncSink::AsyncSink(OutputSink& inner)
    : inner_(inner), ring_(kDepth), last_hand_(std::chrono::steady_clock::now()), thread_([this] { run(); }) {}

AsyncSink::~AsyncSink() {
  // Write what is pending; an error here has no caller left to take it.
  try {
    flush();
  } catch (...) {  // NOLINT(bugprone-empty-catch): flush() rethrows to callers that call it
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void AsyncSink::write(const Sample& s) {
  // Copy into the filling batch (a slot's vectors keep their storage).
  Batch& b = ring_[fill_];
  if (b.count < b.samples.size()) {
    b.samples[b.count] = s;
  } else {
    b.samples.push_back(s);
  }
  ++b.count;
  // Hand over a full batch, or a partial one that waited long enough.
  if (b.count >= kBatch || std::chrono::steady_clock::now() - last_hand_ >= kHandEvery) hand_over();
}

void AsyncSink::flush() {
  if (ring_[fill_].count > 0) hand_over();
  {
    std::unique_lock<std::mutex> lock(mutex_);
    wait_for(lock, [this] { return queued_ == 0; });
  }
  inner_.flush();  // the writer is idle: inner_ is this thread's until the next hand-over
}

template <class Done>
void AsyncSink::wait_for(std::unique_lock<std::mutex>& lock, Done done) {
  changed_.wait(lock, [&] { return done() || error_; });
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void AsyncSink::hand_over() {
  {
    // Queue the filling batch once the batch after it is free.
    std::unique_lock<std::mutex> lock(mutex_);
    wait_for(lock, [this] { return queued_ + 1 < kDepth; });
    ++queued_;
  }
  changed_.notify_all();
  fill_ = (fill_ + 1) % kDepth;
  ring_[fill_].count = 0;
  last_hand_ = std::chrono::steady_clock::now();
}

void AsyncSink::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    // Sleep until a batch comes or the sink ends.
    changed_.wait(lock, [this] { return queued_ > 0 || stop_; });
    if (queued_ == 0) return;
    // Write the batch outside the lock; keep what inner_ throws (and
    // drop the batches queued after it: the run is told at its next call).
    const Batch& b = ring_[next_];
    const bool failed = failed_;
    lock.unlock();
    std::exception_ptr error;
    try {
      for (std::size_t i = 0; i < b.count && !failed; ++i) inner_.write(b.samples[i]);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error) error_ = error, failed_ = true;
    next_ = (next_ + 1) % kDepth;
    --queued_;
    changed_.notify_all();
  }
}

}  // namespace towsim::output
