#include "towsim/output/row_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace towsim::output {

RowFile::RowFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) throw std::runtime_error("cannot create " + path + ": " + std::strerror(errno));
}

RowFile::~RowFile() {
  if (fd_ >= 0) ::close(fd_);
}

bool RowFile::append(const std::string& rows) {
  if (!error_.empty()) return false;
  std::size_t done = 0;
  while (done < rows.size()) {
    const ssize_t n = ::write(fd_, rows.data() + done, rows.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      // A short batch would end the file in a cut row: cut it back.
      error_ = "cannot write " + path_ + ": " + std::strerror(n < 0 ? errno : ENOSPC);
      if (::ftruncate(fd_, static_cast<off_t>(size_)) == 0) ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  size_ += static_cast<long long>(rows.size());
  return true;
}

}  // namespace towsim::output
