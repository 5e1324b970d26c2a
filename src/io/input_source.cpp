#include "io/input_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "io/output_set.h"
#include "io/signal_cleanup.h"

namespace glint {

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 16;

// read() or pread() until `size` bytes, the end of the input, or an error (-1, errno set).
ssize_t read_some(int fd, bool positional, off_t offset, char* data, std::size_t size) {
  for (;;) {
    const ssize_t n = positional ? ::pread(fd, data, size, offset) : ::read(fd, data, size);
    if (n >= 0 || errno != EINTR) return n;
  }
}

}  // namespace

class FdInputStream::Buf : public std::streambuf {
 public:
  Buf(int fd, bool positional, off_t offset)
      : fd_(fd), positional_(positional), offset_(offset), buffer_(kBufferBytes) {
    setg(buffer_.data(), buffer_.data(), buffer_.data());
  }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    const ssize_t n = fill(buffer_.data(), buffer_.size());
    setg(buffer_.data(), buffer_.data(), buffer_.data() + (n > 0 ? n : 0));
    return n > 0 ? traits_type::to_int_type(*gptr()) : traits_type::eof();
  }

  // Large reads (the line reader asks for 1 MiB) go straight into the caller's buffer.
  std::streamsize xsgetn(char* s, std::streamsize n) override {
    std::streamsize done = 0;
    const auto buffered = std::min<std::streamsize>(n, egptr() - gptr());
    if (buffered > 0) {
      std::memcpy(s, gptr(), static_cast<std::size_t>(buffered));
      gbump(static_cast<int>(buffered));
      done = buffered;
    }
    while (done < n) {
      const ssize_t got = fill(s + done, static_cast<std::size_t>(n - done));
      if (got <= 0) break;
      done += got;
    }
    return done;
  }

 private:
  ssize_t fill(char* data, std::size_t size) {
    const ssize_t n = read_some(fd_, positional_, offset_, data, size);
    if (n < 0) {
      // The istream turns an exception from its buffer into badbit; errno stays for the message.
      const int err = errno;
      std::ios_base::failure e(std::strerror(err));
      errno = err;
      throw e;
    }
    offset_ += n;
    return n;
  }

  int fd_;
  bool positional_;
  off_t offset_;
  std::vector<char> buffer_;
};

FdInputStream::FdInputStream(int fd, bool positional, off_t offset)
    : std::istream(nullptr), buf_(std::make_unique<Buf>(fd, positional, offset)) {
  rdbuf(buf_.get());
}

FdInputStream::~FdInputStream() = default;

namespace {

// An anonymous file in the temporary folder: O_TMPFILE where the file system has it, else a fresh
// name removed right after it is made (registered meanwhile, so a signal cannot leave it).
int anonymous_file(const std::string& folder) {
#ifdef O_TMPFILE
  const int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
#endif
  int err = 0;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string path = folder + "/glint-stdin.tmp." + unpredictable_suffix();
    SignalShield shield;
    const int handle = register_cleanup(CleanupKind::kFile, path);
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    err = errno;
    if (fd >= 0) ::unlink(path.c_str());
    release_cleanup(handle);
    if (fd >= 0) return fd;
    if (err != EEXIST && err != EINTR) break;
  }
  errno = err;
  return -1;
}

}  // namespace

RereadableInput::RereadableInput(std::string path)
    : path_(std::move(path)), name_(path_ == "-" ? kStdinName : path_) {
  int in = -1;
  if (path_ == "-") {
    struct stat st {};
    if (::fstat(STDIN_FILENO, &st) == 0 && S_ISREG(st.st_mode)) {
      // Redirected from a file: read it in place, from where standard input stands.
      const off_t at = ::lseek(STDIN_FILENO, 0, SEEK_CUR);
      if (at >= 0) {
        fd_ = STDIN_FILENO;
        base_ = at;
        return;
      }
    }
    in = STDIN_FILENO;
  } else {
    struct stat st {};
    if (::stat(path_.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return;  // opened by path
    in = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) {
      const int err = errno;
      throw InputError(path_, 0, "file",
                       std::string("cannot open for reading: ") + std::strerror(err));
    }
  }
  const char* env = std::getenv("TMPDIR");
  const std::string folder = env && *env ? env : "/tmp";
  auto fail = [&](const std::string& why) {
    if (in != STDIN_FILENO) ::close(in);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw OutputError(name_ +
                      ": the clocked model reads its input once per lane, so input that is not "
                      "a regular file is first copied to a temporary file in '" +
                      folder + "': " + why);
  };
  fd_ = anonymous_file(folder);
  if (fd_ < 0) fail(std::strerror(errno));
  owned_ = true;
  std::vector<char> buf(std::size_t{1} << 20);
  for (;;) {
    const ssize_t n = read_some(in, false, 0, buf.data(), buf.size());
    if (n < 0) {
      const int err = errno;
      if (in != STDIN_FILENO) ::close(in);
      ::close(fd_);
      fd_ = -1;
      throw InputError(name_, 0, "file", std::string("read error: ") + std::strerror(err));
    }
    if (n == 0) break;
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(fd_, buf.data() + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) fail(std::strerror(errno));
      done += w;
    }
  }
  if (in != STDIN_FILENO) ::close(in);
}

RereadableInput::~RereadableInput() {
  if (owned_ && fd_ >= 0) ::close(fd_);
}

std::unique_ptr<VectorReader> RereadableInput::open() const {
  if (fd_ < 0) return std::make_unique<VectorReader>(path_);
  return std::make_unique<VectorReader>(std::make_unique<FdInputStream>(fd_, true, base_), name_);
}

}  // namespace glint
