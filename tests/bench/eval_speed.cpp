// `glint eval` speed end to end: writes a vector file of N rows into the build folder once (t
// uniform over [-1, 1] with six decimals, one white Blinn material n = 50, the same rows for any
// run), then runs `glint eval FILE --json` (all five units) as a child process and prints rows per
// second of wall clock, parsing included. --write-only writes the file and stops (the input of
// tests/bench/instructions.py).
//   eval_speed [--rows N] [--threads T] [--glint PATH] [--file PATH] [--write-only]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "generated_stream.h"

namespace {

// The file, unless it is there with this many rows already (its name carries the count).
void write_rows(const std::string& path, std::uint64_t rows) {
  if (std::filesystem::exists(path)) return;
  const std::string tmp = path + ".partial";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + tmp);
  std::fputs(
      "glint-vectors 1\neps 1e-3\nlights 1\nmaterial bench specular=1,1,1 shininess=50 "
      "lobe=blinn\ncolumns t material\ndata\n",
      f);
  std::uint64_t state = glint::bench::kStreamSeed;
  for (std::uint64_t i = 0; i < rows; ++i) {
    state = glint::bench::lcg_step(state);
    std::fprintf(f, "%.6f bench\n", glint::bench::stream_t(state, -1.0));
  }
  if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + tmp);
  std::filesystem::rename(tmp, path);
}

}  // namespace

int main(int argc, char* argv[]) {
  std::uint64_t rows = 10'000'000;
  std::string glint = GLINT_BINARY, file, threads;
  bool run = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--write-only")) {
      run = false;
      continue;
    }
    if (i + 1 == argc) break;
    if (!std::strcmp(argv[i], "--rows")) rows = std::stoull(argv[i + 1]);
    if (!std::strcmp(argv[i], "--threads")) threads = argv[i + 1];
    if (!std::strcmp(argv[i], "--glint")) glint = argv[i + 1];
    if (!std::strcmp(argv[i], "--file")) file = argv[i + 1];
    ++i;
  }
  if (file.empty()) file = std::string(GLINT_BUILD_DIR) + "/eval_" + std::to_string(rows) + ".vec";
  write_rows(file, rows);
  if (!run) return 0;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout)) _exit(127);
    if (threads.empty()) {
      execl(glint.c_str(), glint.c_str(), "eval", file.c_str(), "--json", nullptr);
    } else {
      execl(glint.c_str(), glint.c_str(), "eval", file.c_str(), "--json", "--threads",
            threads.c_str(), nullptr);
    }
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "glint eval failed (status %d)\n", status);
    return 1;
  }
  const double cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                     1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  std::printf("glint eval %s (%" PRIu64
              " rows, five units): %.2f s wall, %.2f s CPU, "
              "%.1f M rows/s, peak RSS %.0f MB\n",
              file.c_str(), rows, secs, cpu, static_cast<double>(rows) / secs / 1e6,
              static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;
}
