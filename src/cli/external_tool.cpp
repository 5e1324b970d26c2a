#include "cli/external_tool.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/output_set.h"
#include "io/signal_cleanup.h"

extern char** environ;

namespace glint::cli {

WorkFolder::WorkFolder() {
  const char* tmp = std::getenv("TMPDIR");
  const std::string parent = tmp && *tmp ? tmp : "/tmp";
  std::string pattern = parent + "/glint-synth.XXXXXX";
  if (::mkdtemp(pattern.data()) == nullptr)
    throw OutputError(fmt::format("synth: cannot make a work folder in '{}' (TMPDIR): {}", parent,
                                  std::strerror(errno)));
  dir_ = pattern;
  handles_.push_back(register_cleanup(CleanupKind::kFolder, dir_));
}

WorkFolder::~WorkFolder() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);  // ours, 0700: no one else put links in it
  for (int h : handles_) release_cleanup(h);
}

std::string WorkFolder::file(const std::string& name) {
  files_.push_back(dir_ + "/" + name);
  handles_.push_back(register_cleanup(CleanupKind::kFile, files_.back()));
  return files_.back();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw OutputError("synth: cannot write " + path + ": " + std::strerror(errno));
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

// This process's environment with TMPDIR set to `tmp`.
std::vector<std::string> environment_with_tmpdir(const std::string& tmp) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e)
    if (std::strncmp(*e, "TMPDIR=", 7) != 0) env.emplace_back(*e);
  env.push_back("TMPDIR=" + tmp);
  return env;
}

}  // namespace

int run_tool(const std::string& program, const std::vector<std::string>& args,
             const std::string& output, const std::string& work, const std::string& missing) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<std::string> words{program};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::vector<std::string> env = environment_with_tmpdir(work);
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = -1;
  int err = 0;
  int handle = -1;
  {
    // Signals held from the start to the registration: the process is never unregistered.
    SignalShield shield;
    err = ::posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), envp.data());
    if (err == 0) handle = register_cleanup_process(pid);
  }
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw std::invalid_argument(missing);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  release_cleanup(handle);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

unsigned long long free_bytes(const std::string& dir) {
  struct statvfs st {};
  if (::statvfs(dir.c_str(), &st) != 0) return ~0ULL;
  return static_cast<unsigned long long>(st.f_bavail) * st.f_frsize;
}

}  // namespace glint::cli
