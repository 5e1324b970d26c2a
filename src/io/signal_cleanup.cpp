#include "io/signal_cleanup.h"

#include <limits.h>
#include <pthread.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "io/output_set.h"

namespace glint {

namespace {

// Entry states. An entry is written only between kBusy and its kind, so the handler, which reads
// only entries in a kind state, never sees a half-copied path.
enum State : int { kFree = 0, kBusy, kFileEntry, kFolderEntry, kProcessEntry };

struct Entry {
  std::atomic<int> state{kFree};
  pid_t pid = 0;
  char path[PATH_MAX] = {};
};

// Static storage: no allocation, zero pages until touched. std::atomic<int> is lock-free on every
// platform glint builds on, hence usable from a handler (checked below).
Entry g_entries[kMaxCleanupEntries];
static_assert(std::atomic<int>::is_always_lock_free, "the handler needs lock-free atomics");

std::atomic<int> g_shields{0};        // SignalShields alive (any thread)
std::atomic<int> g_pending{0};        // a signal a handler deferred because of a shield
std::atomic<bool> g_cleaning{false};  // a handler is removing the entries

// The signals whose default action ends the process and which the handler turns into a cleanup.
constexpr int kSignals[] = {SIGHUP,  SIGINT,  SIGQUIT, SIGTERM, SIGPIPE,
                            SIGALRM, SIGUSR1, SIGUSR2, SIGXCPU, SIGABRT};

sigset_t termination_set() {
  sigset_t set;
  sigemptyset(&set);
  for (int s : kSignals) sigaddset(&set, s);
  return set;
}

int claim(int kind, const char* path, pid_t pid) {
  for (std::size_t i = 0; i < kMaxCleanupEntries; ++i) {
    int expected = kFree;
    if (!g_entries[i].state.compare_exchange_strong(expected, kBusy)) continue;
    if (path) {
      std::strcpy(g_entries[i].path, path);
    } else {
      g_entries[i].path[0] = '\0';
    }
    g_entries[i].pid = pid;
    g_entries[i].state.store(kind, std::memory_order_release);
    return static_cast<int>(i);
  }
  throw OutputError("too many temporary files at once (glint keeps at most " +
                    std::to_string(kMaxCleanupEntries) + ")");
}

// Async-signal-safe from here on: kill, waitpid, unlink, rmdir only.
void remove_entries() {
  for (Entry& e : g_entries) {
    if (e.state.load(std::memory_order_acquire) != kProcessEntry) continue;
    ::kill(e.pid, SIGKILL);  // before its folder goes: it could create files there again
    while (::waitpid(e.pid, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  for (Entry& e : g_entries)
    if (e.state.load(std::memory_order_acquire) == kFileEntry) ::unlink(e.path);
  // Folders last. One may sit inside another (render -o a/b/c makes three), and entries are not
  // in any order: pass over them until no rmdir succeeds (a folder still holding files someone
  // else put there stays).
  for (bool progress = true; progress;) {
    progress = false;
    for (Entry& e : g_entries)
      if (e.state.load(std::memory_order_acquire) == kFolderEntry && ::rmdir(e.path) == 0)
        progress = true;
  }
}

extern "C" void cleanup_handler(int sig) {
  const int saved_errno = errno;
  // A commit in another thread: let it finish, it delivers the signal (SIGABRT cannot wait: abort()
  // would end the process right after this handler returns).
  if (sig != SIGABRT && g_shields.load() > 0) {
    g_pending.store(sig);
    errno = saved_errno;
    return;
  }
  // A second signal while another thread cleans up: that thread ends the process.
  if (!g_cleaning.exchange(true)) {
    remove_entries();
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    ::sigaction(sig, &dfl, nullptr);
    // Blocked while this handler runs: delivered, with the default action, when it returns.
    ::raise(sig);
  }
  errno = saved_errno;
}

}  // namespace

int register_cleanup(CleanupKind kind, const std::string& path) {
  if (path.empty() || path.size() >= PATH_MAX)
    throw OutputError("cannot register '" + path + "' for removal: path longer than " +
                      std::to_string(PATH_MAX - 1) + " bytes");
  return claim(kind == CleanupKind::kFolder ? kFolderEntry : kFileEntry, path.c_str(), 0);
}

int register_cleanup_process(pid_t pid) {
  return claim(kProcessEntry, nullptr, pid);
}

void release_cleanup(int handle) noexcept {
  if (handle < 0 || static_cast<std::size_t>(handle) >= kMaxCleanupEntries) return;
  g_entries[handle].state.store(kBusy);  // the handler skips it from now on
  g_entries[handle].state.store(kFree);
}

void install_cleanup_handlers() {
  static std::atomic<bool> installed{false};
  if (installed.exchange(true)) return;
  struct sigaction sa {};
  sa.sa_handler = cleanup_handler;
  // Every termination signal is held while the handler runs, so one cleanup is not interrupted by
  // another in the same thread.
  sa.sa_mask = termination_set();
  sa.sa_flags = SA_RESTART;
  for (int s : kSignals) {
    struct sigaction old {};
    if (::sigaction(s, nullptr, &old) != 0) continue;
    if (!(old.sa_flags & SA_SIGINFO) && old.sa_handler == SIG_DFL) ::sigaction(s, &sa, nullptr);
  }
  struct sigaction old {};
  if (::sigaction(SIGXFSZ, nullptr, &old) == 0 && !(old.sa_flags & SA_SIGINFO) &&
      old.sa_handler == SIG_DFL) {
    struct sigaction ign {};
    ign.sa_handler = SIG_IGN;
    sigemptyset(&ign.sa_mask);
    ::sigaction(SIGXFSZ, &ign, nullptr);
  }
}

SignalShield::SignalShield() {
  const sigset_t set = termination_set();
  restore_ = ::pthread_sigmask(SIG_BLOCK, &set, &old_mask_) == 0;
  g_shields.fetch_add(1);
}

SignalShield::~SignalShield() {
  g_shields.fetch_sub(1);
  // A signal sent to this thread meanwhile is delivered here (the handler now cleans up), one a
  // handler in another thread deferred just after.
  if (restore_) ::pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
  if (g_shields.load() == 0) {
    const int pending = g_pending.exchange(0);
    if (pending != 0) ::raise(pending);
  }
}

}  // namespace glint
