// Starting the waveform tools glint runs (vcd2fst, fst2vcd) the same way: posix_spawnp, not fork +
// exec of a shell, so a path needs no quoting and an exec failure (the tool not on PATH) comes back
// as an error number rather than as a broken pipe later.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace glint::rtl {

struct ToolStart {
  std::vector<std::string> argv;  // argv[0] is the program, looked up on PATH
  int stdin_fd = -1;              // dup'ed to the tool's 0; -1: /dev/null
  int stdout_fd = -1;             // dup'ed to the tool's 1; -1: /dev/null
  std::string log;                // the tool's stderr: a new file (O_EXCL, no link followed)
  // SIGXFSZ at its default too: for a tool that writes a file and may not check its writes, past
  // a file size limit it dies (a failure seen) where glint, which ignores SIGXFSZ, gets EFBIG.
  bool default_sigxfsz = false;
};

// Starts the tool with an empty signal mask and SIGPIPE at its default, whatever this process
// uses. Returns 0 and sets `pid`, or the error number of posix_spawnp.
int start_tool(const ToolStart& start, pid_t& pid);

}  // namespace glint::rtl
