// A CSV file written in whole rows: each batch of rows is one write(2) from
// the end of the last whole batch; a batch the disk cannot take (full, I/O
// error) is cut back off the file, the cause kept, and nothing more written.
#pragma once

#include <string>

namespace towsim::output {

class RowFile {
 public:
  /// Create (truncate) `path`; throws std::runtime_error when it cannot.
  explicit RowFile(const std::string& path);
  ~RowFile();
  RowFile(const RowFile&) = delete;
  RowFile& operator=(const RowFile&) = delete;

  /// Append `rows` (whole lines); false, with error() set, when they could not
  /// all be written (the file then ends at the previous batch).
  bool append(const std::string& rows);
  /// "" while every batch went in; else "cannot write PATH: cause".
  const std::string& error() const { return error_; }

 private:
  std::string path_;
  int fd_ = -1;
  long long size_ = 0;  // bytes of whole batches written [bytes]
  std::string error_;
};

}  // namespace towsim::output
