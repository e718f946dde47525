#include "towsim/output/dir_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace towsim::output {

DirLock::DirLock(const std::string& dir) {
  fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error("cannot open the output directory " + dir + ": " + std::strerror(errno));
  // Not taken: another towsim writes there (its files and ours would mix).
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    if (e == EWOULDBLOCK)
      throw std::runtime_error(dir +
                               " is in use by another towsim run (wait for it to end, or choose another output "
                               "directory)");
    // A file system without flock (ENOLCK, EOPNOTSUPP): the run goes on unlocked.
  }
}

DirLock::~DirLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace towsim::output
