#include "rtl_model/fst_read_back.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include "io/output_set.h"
#include "io/signal_cleanup.h"
#include "rtl_model/tool_process.h"

namespace glint::rtl {

namespace {

// FST block types (gtkwave's fstapi.h, enum fstBlockType).
constexpr int kHeaderBlock = 0, kGeometryBlock = 3, kHierarchyBlock = 4, kHierarchyLz4Block = 6,
              kHierarchyLz4DuoBlock = 7, kUnfinishedBlock = 255;

std::string status_text(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

}  // namespace

std::string log_start(const std::string& path, std::size_t max) {
  std::ifstream in(path, std::ios::binary);
  std::string text(max + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > max) text = text.substr(0, max) + " ...";
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

FstReadBack read_back_fst(const std::string& fst, const std::string& log, const std::string& what) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw OutputError(what + ": pipe for fst2vcd: " + std::strerror(errno));
  ToolStart start;
  start.argv = {"fst2vcd", "-f", fst};
  start.stdout_fd = fds[1];
  start.log = log;
  pid_t pid = -1;
  int handle = -1;
  int err = 0;
  {
    // Signals held from the start to the registration: the process is never unregistered.
    SignalShield shield;
    err = start_tool(start, pid);
    if (err == 0) handle = register_cleanup_process(pid);
  }
  ::close(fds[1]);
  if (err != 0) {
    ::close(fds[0]);
    throw OutputError(what + ": cannot run fst2vcd to check the FST (" + std::strerror(err) +
                      "); it comes with the Debian package gtkwave");
  }
  VcdTally tally;
  std::vector<char> buf(1 << 16);
  for (;;) {
    const ssize_t n = ::read(fds[0], buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    tally.feed(buf.data(), static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  FstReadBack back;
  while (::waitpid(pid, &back.status, 0) < 0 && errno == EINTR) {
  }
  release_cleanup(handle);
  back.counts = tally.counts();
  back.messages = log_start(log, 300);
  return back;
}

std::string fst_incomplete(const FstReadBack& back, const VcdCounts& written) {
  std::string why;
  if (!WIFEXITED(back.status) || WEXITSTATUS(back.status) != 0)
    why = "fst2vcd cannot read it back (" + status_text(back.status) + ")";
  else
    why = vcd_counts_difference(written, back.counts);
  if (why.empty()) return "";
  if (!back.messages.empty()) why += ": " + back.messages;
  return "vcd2fst wrote an incomplete FST (exit status 0, but " + why +
         "); a full disk is the likely cause";
}

std::string fst_structure_error(const std::string& fst) {
  const int fd = ::open(fst.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::string("cannot open it: ") + std::strerror(errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return std::string("cannot stat it: ") + std::strerror(err);
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  std::string why;
  bool geometry = false, hierarchy = false;
  std::uint64_t pos = 0, blocks = 0;
  while (why.empty() && pos < size) {
    unsigned char head[9];
    if (size - pos < sizeof head || ::pread(fd, head, sizeof head, static_cast<off_t>(pos)) != 9) {
      why = "it ends inside a block header at byte " + std::to_string(pos);
      break;
    }
    std::uint64_t length = 0;
    for (int i = 1; i < 9; ++i) length = length << 8 | head[i];
    const int type = head[0];
    if (blocks == 0 && type != kHeaderBlock) why = "it does not start with an FST header block";
    if (type == kUnfinishedBlock) why = "a block at byte " + std::to_string(pos) + " is unfinished";
    if (length < 8)
      why = "the block at byte " + std::to_string(pos) + " has no length (unfinished)";
    else if (length > size - pos - 1)
      why = "it ends inside the block at byte " + std::to_string(pos) + " (" +
            std::to_string(size) + " bytes of " + std::to_string(pos + 1 + length) + ")";
    geometry = geometry || type == kGeometryBlock;
    hierarchy = hierarchy || type == kHierarchyBlock || type == kHierarchyLz4Block ||
                type == kHierarchyLz4DuoBlock;
    pos += 1 + length;
    ++blocks;
  }
  ::close(fd);
  if (why.empty() && !(geometry && hierarchy))
    why = std::string("it lacks its ") + (geometry ? "hierarchy" : "geometry") + " block";
  return why;
}

std::string check_fst(const std::string& fst, const std::string& log, const std::string& what,
                      const VcdCounts& written) {
  const std::string broken = fst_structure_error(fst);
  if (!broken.empty())
    return "vcd2fst wrote an incomplete FST (exit status 0, but " + broken +
           "); a full disk is the likely cause";
  return fst_incomplete(read_back_fst(fst, log, what), written);
}

}  // namespace glint::rtl
