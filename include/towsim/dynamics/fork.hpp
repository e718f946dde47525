// Two independent parts of one evaluation, possibly run at the same time
// (docs/performance.md "Loads on two threads").
#pragma once

namespace towsim {

/// Runs two independent parts of a computation; a dynamics function that
/// has such parts takes a Fork* (nullptr: one after the other, here). The
/// parts write disjoint entries of the Workspace and each does the same
/// arithmetic as in the serial order: the results are bit for bit the same.
/// Implemented by the integrator's worker thread (towsim::Worker).
class Fork {
 public:
  using Part = void (*)(void* context);
  /// Run a(ca) and b(cb), possibly at the same time (a on another thread);
  /// return when both have ended. An exception of a is rethrown before
  /// one of b (a comes first in the serial order).
  virtual void run_pair(Part a, void* ca, Part b, void* cb) = 0;

 protected:
  Fork() = default;
  ~Fork() = default;
  Fork(const Fork&) = default;
  Fork& operator=(const Fork&) = default;
};

/// a() then b(), or both at once on `fork` (nullptr: a() then b()); a and b
/// are callables the caller keeps alive (named, not const).
template <class A, class B>
void fork_pair(Fork* fork, A& a, B& b) {
  if (fork == nullptr) {
    a();
    b();
    return;
  }
  fork->run_pair([](void* c) { (*static_cast<A*>(c))(); }, &a, [](void* c) { (*static_cast<B*>(c))(); }, &b);
}

}  // namespace towsim
