#include "io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <streambuf>
#include <vector>

namespace glint {

namespace {

std::string errno_text(int err) {
  return std::strerror(err);
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

std::string unique_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  static const std::uint64_t seed = [] {
    std::random_device rd;
    return (static_cast<std::uint64_t>(rd()) << 32) ^ rd() ^
           static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  }();
  std::uint64_t x = seed + 0x9e3779b97f4a7c15ULL * (++counter);
  x ^= static_cast<std::uint64_t>(::getpid()) << 17;
  // splitmix64 finaliser, then 12 characters from [0-9a-z].
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  static constexpr char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string s(12, '0');
  for (char& c : s) {
    c = kAlphabet[x % 36];
    x /= 36;
  }
  return s;
}

}  // namespace

// A minimal buffered streambuf over a POSIX file descriptor that remembers the first error.
class AtomicOutputFile::FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buffer_(kSize) { setp(buffer_.data(), buffer_.data() + kSize); }
  ~FdBuf() override { close_fd(); }

  int fd() const { return fd_; }
  int error() const { return error_; }

  // Flushes the buffer; returns 0 or the first error seen.
  int flush_all() {
    sync();
    return error_;
  }

  int close_fd() {
    int err = 0;
    if (fd_ >= 0) {
      if (::close(fd_) != 0) err = errno;
      fd_ = -1;
    }
    return err;
  }

 protected:
  int_type overflow(int_type ch) override {
    if (flush_buffer() != 0) return traits_type::eof();
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
    if (flush_buffer() != 0) return 0;
    if (n >= static_cast<std::streamsize>(kSize)) {
      if (fd_ < 0) return 0;
      const int err = write_all(fd_, s, static_cast<std::size_t>(n));
      if (err != 0) {
        if (error_ == 0) error_ = err;
        return 0;
      }
      return n;
    }
    std::memcpy(pptr(), s, static_cast<std::size_t>(n));
    pbump(static_cast<int>(n));
    return n;
  }

  int sync() override { return flush_buffer() == 0 ? 0 : -1; }

 private:
  static constexpr std::size_t kSize = 1 << 16;

  int flush_buffer() {
    const std::size_t used = static_cast<std::size_t>(pptr() - pbase());
    if (used > 0 && error_ == 0) {
      const int err = fd_ < 0 ? EBADF : write_all(fd_, pbase(), used);
      if (err != 0) error_ = err;
    }
    setp(buffer_.data(), buffer_.data() + kSize);
    return error_;
  }

  int fd_;
  int error_ = 0;
  std::vector<char> buffer_;
};

void check_output_path(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    throw OutputError("cannot write '" + path +
                      "': it exists and is not a regular file (it would be replaced)");
  }
}

AtomicOutputFile::AtomicOutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw OutputError("cannot write output file: empty path");
  check_output_path(path_);
  int fd = -1;
  int err = 0;
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_path_ = path_ + ".tmp." + unique_suffix();
    fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) break;
    err = errno;
    if (err != EEXIST && err != EINTR) break;
  }
  if (fd < 0) {
    throw OutputError("cannot create temporary file '" + temp_path_ + "' for '" + path_ +
                      "': " + errno_text(err));
  }
  buf_ = std::make_unique<FdBuf>(fd);
  stream_ = std::make_unique<std::ostream>(buf_.get());
}

AtomicOutputFile::~AtomicOutputFile() {
  abort();
}

std::ostream& AtomicOutputFile::stream() {
  if (!stream_) throw std::logic_error("AtomicOutputFile '" + path_ + "': already closed");
  return *stream_;
}

void AtomicOutputFile::abort() noexcept {
  if (committed_ || !buf_) return;
  stream_.reset();
  buf_->close_fd();
  buf_.reset();
  ::unlink(temp_path_.c_str());
}

void AtomicOutputFile::commit(bool durable) {
  if (committed_) throw std::logic_error("AtomicOutputFile '" + path_ + "': committed twice");
  if (!buf_) throw std::logic_error("AtomicOutputFile '" + path_ + "': already aborted");
  stream_->flush();
  int err = buf_->flush_all();
  const char* what = "write";
  if (err == 0 && durable && ::fsync(buf_->fd()) != 0) {
    err = errno;
    what = "fsync";
  }
  if (err == 0) {
    err = buf_->close_fd();
    what = "close";
  }
  if (err == 0 && ::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    err = errno;
    what = "rename";
  }
  if (err != 0) {
    abort();
    throw OutputError("cannot write output file '" + path_ + "': " + what + " of '" + temp_path_ +
                      "' failed: " + errno_text(err));
  }
  committed_ = true;
  stream_.reset();
  buf_.reset();
  if (durable) {
    // Make the rename itself durable: fsync the directory (best effort).
    const auto slash = path_.rfind('/');
    const std::string dir = slash == std::string::npos ? "." : path_.substr(0, slash + 1);
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
      ::fsync(dfd);
      ::close(dfd);
    }
  }
}

}  // namespace glint
