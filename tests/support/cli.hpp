// Running the towsim program from tests, and reading its CSV outputs back.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace towsim::testing {

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
    if (c == ',') out.emplace_back();
    else out.back() += c;
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

/// A fresh directory under the temporary directory, named after the test.
inline std::filesystem::path fresh_dir(const std::string& tag) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto d = std::filesystem::temp_directory_path() /
                 ("towsim_" + tag + "_" + info->test_suite_name() + "_" + info->name() + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace towsim::testing
