// What an interrupted run must not leave behind: its temporary files and folders, and the helper
// processes writing into them, removed from the handler of a termination signal.
//
// A signal handler may only call async-signal-safe functions (POSIX: kill, waitpid, unlink,
// rmdir, sigaction, raise; no malloc, no locks, no C++ library), so the registry is a fixed table
// of C strings with an atomic state per entry, filled and cleared by the normal code. The handler
// stops the registered processes (SIGKILL, then waitpid), unlinks the registered files, removes
// the registered folders (last registered first), restores the signal's default action and raises
// it again: the process still dies of the signal it got (exit status, core dump as before).
//
// While a SignalShield is alive (committing a set of outputs: a few renames that must all happen
// or none), the termination signals are blocked in its thread, and a handler that runs in another
// thread only records the signal; the outermost shield's end delivers it. So a signal never
// interrupts a commit half-way.
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <cstddef>
#include <string>

namespace glint {

// Entries the table holds at once (every temporary file, folder, backup and helper process of a
// run). Registering more throws OutputError.
inline constexpr std::size_t kMaxCleanupEntries = 1024;

enum class CleanupKind { kFile, kFolder, kProcess };

// Registers `path` (an absolute path is best: the handler runs wherever the process stands; at
// most PATH_MAX - 1 bytes) for removal if a termination signal arrives. Returns the handle to
// release. Throws OutputError when the table is full or the path too long.
int register_cleanup(CleanupKind kind, const std::string& path);
// Registers a helper process to SIGKILL (and reap) before any file is removed.
int register_cleanup_process(pid_t pid);
// Forgets an entry (the file was renamed into place or removed); -1 is ignored.
void release_cleanup(int handle) noexcept;

// Installs the cleanup handler for SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGUSR1,
// SIGUSR2, SIGXCPU and SIGABRT (an uncaught exception), each only if its action is the default one
// (a signal the caller ignores, e.g. SIGHUP under nohup, stays ignored), and ignores SIGXFSZ (when
// default), so that exceeding a file size limit (ulimit -f) makes write() fail with EFBIG, an
// error glint reports, instead of killing the process. Idempotent. glint's main() calls it; a
// library user decides.
void install_cleanup_handlers();

// The termination signals held for a scope (see above). Nests.
class SignalShield {
 public:
  SignalShield();
  ~SignalShield();
  SignalShield(const SignalShield&) = delete;
  SignalShield& operator=(const SignalShield&) = delete;

 private:
  sigset_t old_mask_{};  // the thread's mask before
  bool restore_ = false;
};

}  // namespace glint
