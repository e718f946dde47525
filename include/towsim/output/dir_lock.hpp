// An output directory held by one towsim at a time: an exclusive flock(2) on
// the directory itself (no lock file is left behind), released when the
// holder ends, however it ends.
#pragma once

#include <string>

namespace towsim::output {

class DirLock {
 public:
  /// Lock the existing directory `dir`; throws std::runtime_error when
  /// another process holds it or it cannot be opened (on a file system
  /// without flock it goes on unlocked).
  explicit DirLock(const std::string& dir);
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace towsim::output
