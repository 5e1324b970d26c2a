#include "io/output_set.h"

#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>
#include <set>
#include <streambuf>

#include "io/signal_cleanup.h"

namespace glint {

namespace {

std::string errno_text(int err) {
  return std::strerror(err);
}

// The process's umask, read once (umask() can only be read by setting it): the mode a new file
// gets, 0666 & ~umask, for a temporary made 0600 whose target disappeared meanwhile.
mode_t process_umask() {
  static const mode_t mask = [] {
    const mode_t m = ::umask(077);
    ::umask(m);
    return m;
  }();
  return mask;
}

}  // namespace

// 62 bits. O_EXCL is what makes a guessed name harmless; unpredictability only keeps another user
// from making every attempt fail by creating the names first.
std::string unpredictable_suffix() {
  std::uint64_t x = 0;
  if (::getrandom(&x, sizeof x, 0) != static_cast<ssize_t>(sizeof x)) {
    static std::atomic<std::uint64_t> counter{0};
    std::random_device rd;
    x = (static_cast<std::uint64_t>(rd()) << 32) ^ rd() ^
        static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()) ^
        (0x9e3779b97f4a7c15ULL * ++counter);
  }
  static constexpr char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string s(12, '0');
  for (char& c : s) {
    c = kAlphabet[x % 36];
    x /= 36;
  }
  return s;
}

namespace {

std::string random_suffix() {
  return unpredictable_suffix();
}

// Writes all of [data, data+size) to fd, retrying on EINTR and short writes. Returns 0 or errno.
int write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return 0;
}

const char* kind_of(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Why an existing non-regular target is refused.
std::string refusal(mode_t mode) {
  std::string why = std::string("it is ") + kind_of(mode) +
                    ", not a regular file: glint writes a new file and renames it over the "
                    "target, which would replace it";
  if (S_ISLNK(mode) || S_ISCHR(mode) || S_ISFIFO(mode))
    why += " (for standard output, give '-' where the option allows it)";
  return why;
}

// A path split into its folder and its last component.
struct Split {
  std::string folder, name;
};

Split split_path(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return {".", path};
  return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

// realpath of a folder, or "" with errno set.
std::string real_folder(const std::string& folder) {
  char buf[PATH_MAX];
  if (!::realpath(folder.c_str(), buf)) return "";
  return buf;
}

std::string join(const std::string& folder, const std::string& name) {
  return folder == "/" ? "/" + name : folder + "/" + name;
}

}  // namespace

// ---- OutputFile ------------------------------------------------------------------------------

// A buffered streambuf over a file descriptor that throws OutputError, naming the output, on the
// first write error (the stream has badbit in its exceptions, so the error reaches the writer).
class OutputFile::Buf : public std::streambuf {
 public:
  Buf(int fd, std::string what) : fd_(fd), what_(std::move(what)), buffer_(kSize) {
    setp(buffer_.data(), buffer_.data() + kSize);
  }

  void flush_or_throw() {
    if (flush_buffer() != 0) fail();
  }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (flush_buffer() != 0) fail();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }

  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const auto room = static_cast<std::streamsize>(epptr() - pptr());
    if (n <= room) {
      std::memcpy(pptr(), s, static_cast<std::size_t>(n));
      pbump(static_cast<int>(n));
      return n;
    }
    if (flush_buffer() != 0) fail();
    if (n >= static_cast<std::streamsize>(kSize)) {
      const int err = write_all(fd_, s, static_cast<std::size_t>(n));
      if (err != 0) {
        error_ = err;
        fail();
      }
      return n;
    }
    std::memcpy(pptr(), s, static_cast<std::size_t>(n));
    pbump(static_cast<int>(n));
    return n;
  }

  int sync() override {
    if (flush_buffer() != 0) fail();
    return 0;
  }

 private:
  static constexpr std::size_t kSize = 1 << 16;

  int flush_buffer() {
    const std::size_t used = static_cast<std::size_t>(pptr() - pbase());
    if (used > 0 && error_ == 0) error_ = write_all(fd_, pbase(), used);
    setp(buffer_.data(), buffer_.data() + kSize);
    return error_;
  }

  [[noreturn]] void fail() const {
    throw OutputError(what_ + ": write failed: " + errno_text(error_));
  }

  int fd_;
  std::string what_;
  int error_ = 0;
  std::vector<char> buffer_;
};

OutputFile::~OutputFile() {
  discard();
}

std::string OutputFile::describe() const {
  return option_.empty() ? "'" + path_ + "'" : option_ + " " + path_;
}

std::ostream& OutputFile::stream() {
  if (!stream_) throw std::logic_error(describe() + ": no stream (produced, committed or aborted)");
  return *stream_;
}

int OutputFile::dup_fd() const {
  if (fd_ < 0) throw std::logic_error(describe() + ": no open file");
  const int fd = ::fcntl(fd_, F_DUPFD_CLOEXEC, 0);
  if (fd < 0) throw OutputError(describe() + ": " + errno_text(errno));
  return fd;
}

void OutputFile::finish(bool durable) {
  if (stdout_) {
    if (stream_) stream_->flush();
    buf_->flush_or_throw();
    return;
  }
  struct stat target {};
  const bool exists = ::lstat(target_.c_str(), &target) == 0;
  if (exists && !S_ISREG(target.st_mode))
    throw OutputError(describe() + ": " + refusal(target.st_mode));
  if (!work_folder_.empty()) {
    // Made by another program in our private folder: no one else can have replaced it.
    struct stat st {};
    if (produced_.empty() || ::lstat(produced_.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
      throw OutputError(describe() + ": the file was not produced");
    if (exists) {
      if (st.st_uid != target.st_uid || st.st_gid != target.st_gid) {
        if (::chown(produced_.c_str(), target.st_uid, target.st_gid) != 0)
          (void)!::chown(produced_.c_str(), static_cast<uid_t>(-1), target.st_gid);
      }
      ::chmod(produced_.c_str(), target.st_mode & 0777);
    }
    // The other program may not have synced (vcd2fst does not): a write-back error, e.g. a full
    // disk found only when delayed blocks are allocated, shows here, before anything is replaced.
    if (durable) {
      const int fd = ::open(produced_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
      const int err = fd < 0 || ::fsync(fd) != 0 ? errno : 0;
      if (fd >= 0) ::close(fd);
      if (err != 0)
        throw OutputError(describe() + ": fsync of '" + produced_ + "' failed: " + errno_text(err));
    }
    return;
  }
  if (stream_) stream_->flush();
  buf_->flush_or_throw();
  // The replaced file's permission bits (not set-id bits), and its owner and group where this
  // process may give them (root; else at least a group the user belongs to): fchown before
  // fchmod, which chown may otherwise reset.
  mode_t mode = 0;
  bool set_mode = false;
  if (exists) {
    struct stat st {};
    if (::fstat(fd_, &st) == 0 && (st.st_uid != target.st_uid || st.st_gid != target.st_gid)) {
      if (::fchown(fd_, target.st_uid, target.st_gid) != 0)
        (void)!::fchown(fd_, static_cast<uid_t>(-1), target.st_gid);
    }
    mode = target.st_mode & 0777;
    set_mode = true;
  } else if (private_mode_) {
    mode = 0666 & ~process_umask();
    set_mode = true;
  }
  const char* step = "chmod";
  int err = set_mode && ::fchmod(fd_, mode) != 0 ? errno : 0;
  if (err == 0 && durable && ::fsync(fd_) != 0) {
    err = errno;
    step = "fsync";
  }
  const int fd = fd_;
  fd_ = -1;
  stream_.reset();
  buf_.reset();
  if (::close(fd) != 0 && err == 0) {
    err = errno;
    step = "close";
  }
  if (err != 0)
    throw OutputError(describe() + ": " + step + " of '" + temp_path_ +
                      "' failed: " + errno_text(err));
}

void OutputFile::discard() noexcept {
  stream_.reset();
  buf_.reset();
  if (fd_ >= 0 && !stdout_) ::close(fd_);
  fd_ = -1;
  if (temp_handle_ >= 0) {
    ::unlink(temp_path_.c_str());
    release_cleanup(temp_handle_);
    temp_handle_ = -1;
  }
  if (folder_handle_ >= 0) {
    std::error_code ec;
    std::filesystem::remove_all(work_folder_, ec);  // ours, 0700: no one else put links in it
    release_cleanup(folder_handle_);
    folder_handle_ = -1;
  }
}

// ---- OutputSet -------------------------------------------------------------------------------

void check_output_path(const std::string& path) {
  if (path.empty()) throw OutputError("output file: empty path");
  const Split s = split_path(path);
  if (s.name.empty() || s.name == "." || s.name == "..")
    throw OutputError("'" + path + "': names a folder, not a file");
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode))
      throw OutputError("cannot write '" + path + "': " + refusal(st.st_mode));
    return;
  }
  if (errno != ENOENT) throw OutputError("cannot write '" + path + "': " + errno_text(errno));
  struct stat dir {};
  if (::stat(s.folder.c_str(), &dir) != 0)
    throw OutputError("cannot write '" + path + "': folder '" + s.folder +
                      "': " + errno_text(errno));
  if (!S_ISDIR(dir.st_mode))
    throw OutputError("cannot write '" + path + "': '" + s.folder + "' is not a folder");
}

OutputSet::OutputSet() {
  process_umask();
}

OutputSet::~OutputSet() {
  if (!committed_) abort();
}

void OutputSet::add_input(const std::string& option, const std::string& path) {
  if (path.empty() || path == "-") return;
  Seen s{option, path, "", true, false, 0, 0};
  char buf[PATH_MAX];
  if (::realpath(path.c_str(), buf)) s.key = buf;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    s.exists = true;
    s.dev = st.st_dev;
    s.ino = st.st_ino;
  }
  if (s.key.empty() && !s.exists) return;  // the reader reports it
  check_distinct(s);
  seen_.push_back(std::move(s));
}

void OutputSet::claim_stdout(const std::string& option) {
  if (!stdout_claim_.empty())
    throw OutputError(stdout_claim_ + " and " + option +
                      " would both write standard output: give one of them a file");
  stdout_claim_ = option;
}

bool OutputSet::writes_stdout() const {
  return std::any_of(files_.begin(), files_.end(), [](const auto& f) { return f->is_stdout(); });
}

void OutputSet::check_distinct(const Seen& s) const {
  for (const Seen& o : seen_) {
    if (o.input && s.input) continue;  // reading one file twice is fine
    const bool same = (!s.key.empty() && s.key == o.key) ||
                      (s.exists && o.exists && s.dev == o.dev && s.ino == o.ino);
    if (!same) continue;
    throw OutputError(o.option + " " + o.path + " and " + s.option + " " + s.path +
                      " name the same file (" + (s.key.empty() ? o.key : s.key) + ")" +
                      (o.input || s.input ? ": the output would overwrite the input" : ""));
  }
}

OutputFile& OutputSet::declare(const std::string& option, const std::string& path,
                               bool allow_stdout) {
  if (committed_ || aborted_) throw std::logic_error("OutputSet: output added after the end");
  auto f = std::unique_ptr<OutputFile>(new OutputFile());
  f->option_ = option;
  f->path_ = path;
  const std::string what = f->describe();
  if (path.empty()) throw OutputError(what + ": empty path");
  if (allow_stdout && path == "-") {
    if (!stdout_claim_.empty())
      throw OutputError(stdout_claim_ + " and " + option +
                        " - would both write standard output: give one of them a file");
    f->stdout_ = true;
    f->fd_ = STDOUT_FILENO;
    f->buf_ = std::make_unique<OutputFile::Buf>(STDOUT_FILENO, what + " (standard output)");
    f->stream_ = std::make_unique<std::ostream>(f->buf_.get());
    f->stream_->exceptions(std::ios::badbit);
    stdout_claim_ = option + " -";
    files_.push_back(std::move(f));
    return *files_.back();
  }
  const Split s = split_path(path);
  if (s.name.empty() || s.name == "." || s.name == "..")
    throw OutputError(what + ": names a folder, not a file");
  const std::string folder = real_folder(s.folder);
  if (folder.empty()) throw OutputError(what + ": folder '" + s.folder + "': " + errno_text(errno));
  struct stat dir {};
  if (::stat(folder.c_str(), &dir) != 0 || !S_ISDIR(dir.st_mode))
    throw OutputError(what + ": '" + s.folder + "' is not a folder");
  f->target_ = join(folder, s.name);
  Seen seen{option, path, f->target_, false, false, 0, 0};
  struct stat st {};
  if (::lstat(f->target_.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) throw OutputError(what + ": " + refusal(st.st_mode));
    seen.exists = true;
    seen.dev = st.st_dev;
    seen.ino = st.st_ino;
  } else if (errno != ENOENT) {
    throw OutputError(what + ": " + errno_text(errno));
  }
  check_distinct(seen);
  f->private_mode_ = seen.exists;
  seen_.push_back(std::move(seen));
  files_.push_back(std::move(f));
  return *files_.back();
}

OutputFile& OutputSet::add(const std::string& option, const std::string& path, bool allow_stdout) {
  OutputFile& f = declare(option, path, allow_stdout);
  if (f.stdout_) return f;
  try {
    // Signals held from registration to creation: a temporary exists only while registered.
    SignalShield shield;
    int err = 0;
    for (int attempt = 0; attempt < 100 && f.fd_ < 0; ++attempt) {
      f.temp_path_ = f.target_ + ".tmp." + random_suffix();
      f.temp_handle_ = register_cleanup(CleanupKind::kFile, f.temp_path_);
      f.fd_ = ::open(f.temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                     f.private_mode_ ? 0600 : 0666);
      if (f.fd_ >= 0) break;
      err = errno;
      release_cleanup(f.temp_handle_);
      f.temp_handle_ = -1;
      if (err != EEXIST && err != EINTR) break;
    }
    if (f.fd_ < 0)
      throw OutputError(f.describe() +
                        ": cannot create a temporary file in its folder: " + errno_text(err));
  } catch (...) {
    files_.pop_back();
    seen_.pop_back();
    throw;
  }
  f.buf_ = std::make_unique<OutputFile::Buf>(f.fd_, f.describe());
  f.stream_ = std::make_unique<std::ostream>(f.buf_.get());
  f.stream_->exceptions(std::ios::badbit);
  return f;
}

OutputFile& OutputSet::add_produced(const std::string& option, const std::string& path) {
  OutputFile& f = declare(option, path, false);
  try {
    SignalShield shield;
    int err = 0;
    for (int attempt = 0; attempt < 100; ++attempt) {
      const std::string dir = f.target_ + ".tmp." + random_suffix();
      f.folder_handle_ = register_cleanup(CleanupKind::kFolder, dir);
      if (::mkdir(dir.c_str(), 0700) == 0) {
        f.work_folder_ = dir;
        break;
      }
      err = errno;
      release_cleanup(f.folder_handle_);
      f.folder_handle_ = -1;
      if (err != EEXIST && err != EINTR) break;
    }
    if (f.work_folder_.empty())
      throw OutputError(f.describe() +
                        ": cannot create a temporary folder in its folder: " + errno_text(err));
  } catch (...) {
    files_.pop_back();
    seen_.pop_back();
    throw;
  }
  return f;
}

void OutputSet::make_folder(const std::string& option, const std::string& dir) {
  if (dir.empty()) throw OutputError(option + ": empty folder name");
  // Every level of `dir`, outermost first: a level that exists must be a folder (or a link to
  // one); a missing one is made (0777 & ~umask) and registered, so an interrupted run removes it.
  std::vector<std::string> levels;
  for (std::size_t i = 1; i < dir.size(); ++i)
    if (dir[i] == '/' && dir[i - 1] != '/') levels.push_back(dir.substr(0, i));
  levels.push_back(dir);
  for (const std::string& level : levels) {
    struct stat st {};
    if (::stat(level.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode))
        throw OutputError(option + " " + dir + ": '" + level + "' is not a folder");
      continue;
    }
    if (errno != ENOENT)
      throw OutputError(option + " " + dir + ": '" + level + "': " + errno_text(errno));
    const Split s = split_path(level);
    const std::string parent = real_folder(s.folder);
    if (parent.empty())
      throw OutputError(option + " " + dir + ": '" + s.folder + "': " + errno_text(errno));
    const std::string abs = join(parent, s.name);
    SignalShield shield;
    const int handle = register_cleanup(CleanupKind::kFolder, abs);
    if (::mkdir(abs.c_str(), 0777) == 0) {
      created_folders_.emplace_back(abs, handle);
      continue;
    }
    const int err = errno;
    release_cleanup(handle);
    // Made meanwhile by someone else: not ours to remove, but it must be a folder.
    if (err == EEXIST && ::stat(level.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) continue;
    throw OutputError(option + " " + dir + ": cannot create the folder '" + level +
                      "': " + errno_text(err));
  }
}

void OutputSet::abort() noexcept {
  if (committed_) return;
  for (auto& f : files_) f->discard();
  for (auto it = created_folders_.rbegin(); it != created_folders_.rend(); ++it) {
    ::rmdir(it->first.c_str());  // only when empty: files someone else put there stay
    release_cleanup(it->second);
  }
  created_folders_.clear();
  aborted_ = true;
}

void OutputSet::commit(bool durable) {
  if (committed_) throw std::logic_error("OutputSet: committed twice");
  if (aborted_) throw std::logic_error("OutputSet: commit after abort");
  // 1. Every output complete on disk, or none is used.
  try {
    for (auto& f : files_) f->finish(durable);
  } catch (...) {
    abort();
    throw;
  }

  struct Step {
    OutputFile* f;
    std::string from;  // the temporary or the produced file
    std::string backup;
    int backup_handle = -1;
    bool existed = false, renamed = false;
  };
  std::vector<Step> steps, last;
  std::string failure;
  {
    SignalShield shield;
    // 2. A hard link to each existing target: what a failed rename restores.
    for (auto& fp : files_) {
      OutputFile* f = fp.get();
      if (f->stdout_) continue;
      Step step{f, f->work_folder_.empty() ? f->temp_path_ : f->produced_, "", -1, false, false};
      struct stat st {};
      if (::lstat(f->target_.c_str(), &st) == 0) {
        if (!S_ISREG(st.st_mode)) {
          failure = f->describe() + ": " + refusal(st.st_mode);
          break;
        }
        step.existed = true;
        int err = 0;
        for (int attempt = 0; attempt < 100; ++attempt) {
          const std::string b = f->target_ + ".tmp." + random_suffix();
          step.backup_handle = register_cleanup(CleanupKind::kFile, b);
          if (::link(f->target_.c_str(), b.c_str()) == 0) {
            step.backup = b;
            break;
          }
          err = errno;
          release_cleanup(step.backup_handle);
          step.backup_handle = -1;
          if (err != EEXIST && err != EINTR) break;
        }
        if (step.backup.empty()) {
          // No hard links here (or not to this file: protected_hardlinks): no backup possible.
          if (err == EPERM || err == EXDEV || err == EMLINK || err == ENOTSUP ||
              err == EOPNOTSUPP || err == ENOSYS || err == EACCES) {
            last.push_back(std::move(step));
            continue;
          }
          failure = f->describe() +
                    ": cannot make a backup link of the file it replaces: " + errno_text(err);
          break;
        }
      }
      steps.push_back(std::move(step));
    }
    // Targets without a backup last: if one of them fails, every earlier one can be undone.
    for (Step& s : last) steps.push_back(std::move(s));

    // 3. The renames, in a row; the first failure undoes the ones done.
    std::size_t failed_at = steps.size();
    if (failure.empty()) {
      for (std::size_t i = 0; i < steps.size(); ++i) {
        if (::rename(steps[i].from.c_str(), steps[i].f->target_.c_str()) != 0) {
          failure = steps[i].f->describe() + ": rename of '" + steps[i].from +
                    "' failed: " + errno_text(errno);
          failed_at = i;
          break;
        }
        steps[i].renamed = true;
        if (steps[i].f->temp_handle_ >= 0) {
          release_cleanup(steps[i].f->temp_handle_);
          steps[i].f->temp_handle_ = -1;
        }
      }
    }
    if (!failure.empty()) {
      std::string unrestored;
      for (std::size_t j = std::min(failed_at, steps.size()); j-- > 0;) {
        Step& s = steps[j];
        if (!s.renamed) continue;
        const std::string& target = s.f->target_;
        bool ok = true;
        if (!s.backup.empty()) {
          ok = ::rename(s.backup.c_str(), target.c_str()) == 0;
          if (ok) {
            release_cleanup(s.backup_handle);
            s.backup_handle = -1;
            s.backup.clear();
          } else {
            unrestored += "; " + s.f->describe() + " could not be restored (" + errno_text(errno) +
                          "), its previous content is in '" + s.backup + "'";
            release_cleanup(s.backup_handle);  // keep that file
            s.backup_handle = -1;
            s.backup.clear();
          }
        } else if (!s.existed) {
          ::unlink(target.c_str());
        } else {
          unrestored += "; " + s.f->describe() +
                        " was replaced and cannot be restored (no hard link backup on its file "
                        "system)";
        }
      }
      for (Step& s : steps) {
        if (s.backup_handle >= 0) {
          ::unlink(s.backup.c_str());
          release_cleanup(s.backup_handle);
        }
      }
      failure += unrestored.empty() ? "; no output was changed" : unrestored;
    }
  }
  if (!failure.empty()) {
    abort();
    throw OutputError(failure);
  }
  // 4. The backups go; the folders' new entries are made durable.
  std::set<std::string> folders;
  for (Step& s : steps) {
    if (s.backup_handle >= 0) {
      ::unlink(s.backup.c_str());
      release_cleanup(s.backup_handle);
    }
    folders.insert(split_path(s.f->target_).folder);
  }
  for (auto& f : files_) {
    if (f->folder_handle_ >= 0) {
      std::error_code ec;
      std::filesystem::remove_all(f->work_folder_, ec);
      release_cleanup(f->folder_handle_);
      f->folder_handle_ = -1;
    }
  }
  for (auto& [path, handle] : created_folders_) release_cleanup(handle);
  created_folders_.clear();
  committed_ = true;
  if (durable) {
    for (const std::string& d : folders) {
      const int dfd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
      }
    }
  }
}

}  // namespace glint
