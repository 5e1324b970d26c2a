// Small helpers shared by the test programs: a scratch directory per test, shell quoting, whole
// file reads and runs of the glint binary. Standard library and gtest only, so that a test of any
// layer (or of the glint binary alone) can use them; a vector file's rows are in vector_rows.h.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace glint::test {

// A fresh, empty scratch directory per test (under the build tree), removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::path(GLINT_BINARY_DIR) / "test_tmp" /
            (std::string(info->test_suite_name()) + "." + info->name() + "." +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Names of the entries, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(path_))
      out.push_back(e.path().filename());
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  std::filesystem::path path_;
};

// Single-quotes a word for /bin/sh.
inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// One run of the glint binary: its exit status (-1 if it did not exit normally) and its output.
struct CliRun {
  int status = -1;
  std::string out, err;
};

// Runs `glint ARGS` (ARGS shell-quoted by the caller) in `dir`, standard input from /dev/null;
// stdout and stderr go through files in `dir`, removed again.
inline CliRun run_glint(const std::filesystem::path& dir, const std::string& args) {
  const std::filesystem::path out = dir / "glint.stdout", err = dir / "glint.stderr";
  const std::string cmd =
      "cd " + shell_quote(dir.string()) + " && " + shell_quote(GLINT_BINARY_DIR "/glint") + " " +
      args + " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace glint::test
