// Driving the built program (TOWSIM_BINARY) from tests and reading what it
// writes: run it through the shell or as a child process, a fresh directory
// per test, whole files, lines and CSV tables.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace towsim::testing {

namespace fs = std::filesystem;

/// How a run of the program ended: exit status and what it printed.
struct CliResult {
  int status = -1;  // exit code, or -1 when it did not exit normally
  std::string out;  // stdout and stderr together
};

/// Run TOWSIM_BINARY with `args` (shell syntax: quote paths with quoted()),
/// capturing stdout and stderr together.
inline CliResult run_towsim(const std::string& args) {
  const std::string cmd = std::string("'") + TOWSIM_BINARY + "' " + args + " 2>&1";
  CliResult r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// A path in single quotes, for run_towsim's shell command.
inline std::string quoted(const fs::path& p) {
  std::string q(1, '\'');  // built by appending: "'" + string trips GCC 12's -Wrestrict
  q += p.string();
  q += '\'';
  return q;
}

/// The whole file, bytes as written ("" when it cannot be read).
inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The file's lines, without their newlines.
inline std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// A CSV file of numbers under a header row.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;  // one per data line; unparsable fields are NaN
  /// Index of the column `name`, or -1.
  int column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
  }
};

/// Read a CSV file written by towsim (comma-separated, no quoting).
inline Csv read_csv(const fs::path& p) {
  const auto split = [](const std::string& line) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (!line.empty() && line.back() == ',') f.emplace_back();
    return f;
  };
  Csv csv;
  const auto lines = lines_of(p);
  if (lines.empty()) return csv;
  csv.header = split(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::vector<double> row;
    for (const auto& f : split(lines[i])) {
      std::size_t used = 0;
      double v = std::nan("");
      try {
        v = std::stod(f, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      row.push_back(used == f.size() && used > 0 ? v : std::nan(""));
    }
    csv.rows.push_back(row);
  }
  return csv;
}

/// A fresh, empty directory under the system's temporary directory, named
/// after `tag` and this process.
inline fs::path fresh_dir(const std::string& tag) {
  const fs::path d = fs::temp_directory_path() / ("towsim_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A fixture giving each test a fresh directory dir_ (removed at the end).
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string tag = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(tag.begin(), tag.end(), '/', '_');  // parametrised names: Prefix/Suite, Test/0
    dir_ = fresh_dir(tag);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

/// How a child ended: exit status and its two streams, separately.
struct Exit {
  int status = -1;  // exit code, or -signal when killed by a signal
  std::string err;  // what it wrote to stderr
  std::string out;  // what it wrote to stdout
};

/// A child running TOWSIM_BINARY with `args` (no shell), stdout and stderr
/// sent to files in `dir`: for tests that signal it or read its streams apart.
class Child {
 public:
  Child(const std::vector<std::string>& args, const fs::path& dir) : out_(dir / "stdout"), err_(dir / "stderr") {
    std::vector<std::string> argv{TOWSIM_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    pid_ = ::fork();
    if (pid_ == 0) {
      const int o = ::open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(o, STDOUT_FILENO);
      ::dup2(e, STDERR_FILENO);
      std::vector<char*> cargv;
      for (auto& a : argv) cargv.push_back(a.data());
      cargv.push_back(nullptr);
      ::execv(cargv[0], cargv.data());
      ::_exit(127);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  /// True while the child has not exited.
  bool running() {
    if (waited_) return false;
    int st = 0;
    if (::waitpid(pid_, &st, WNOHANG) == pid_) {
      waited_ = true;
      status_ = st;
    }
    return !waited_;
  }
  /// Wait for the child to end; its status and streams.
  Exit wait() {
    if (!waited_) {
      ::waitpid(pid_, &status_, 0);
      waited_ = true;
    }
    Exit r;
    r.status = WIFEXITED(status_) ? WEXITSTATUS(status_) : WIFSIGNALED(status_) ? -WTERMSIG(status_) : -1000;
    r.out = slurp(out_);
    r.err = slurp(err_);
    return r;
  }

 private:
  fs::path out_, err_;
  pid_t pid_ = -1;
  bool waited_ = false;
  int status_ = 0;
};

/// Run a shell command; returns (exit status, stdout + stderr).
inline std::pair<int, std::string> shell(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (p == nullptr) return {-1, out};
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  const int st = ::pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

/// Run the towsim binary with `args`; returns (exit status, stdout + stderr).
inline std::pair<int, std::string> towsim_cli(const std::string& args) {
  return shell(std::string("'") + TOWSIM_BINARY + "' " + args);
}

/// A CSV file as text cells: header and rows.
struct TextCsv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int col(const std::string& n) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == n) return static_cast<int>(i);
    return -1;
  }
  /// Cell (r, name) as a number (exact parse of the written text).
  double num(std::size_t r, const std::string& n) const {
    const std::string& s = rows.at(r).at(static_cast<std::size_t>(col(n)));
    double v = 0;
    std::from_chars(s.data(), s.data() + s.size(), v);
    return v;
  }
};

inline std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

inline TextCsv read_text_csv(const std::filesystem::path& p) {
  TextCsv t;
  std::ifstream in(p);
  std::string line;
  if (std::getline(in, line)) t.header = split_csv(line);
  while (std::getline(in, line))
    if (!line.empty()) t.rows.push_back(split_csv(line));
  return t;
}

}  // namespace towsim::testing
