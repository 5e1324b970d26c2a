#include "io/standard_output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <streambuf>
#include <string>
#include <vector>

#include "io/output_set.h"

namespace glint {

namespace {

class CheckedStdoutBuf : public std::streambuf {
 public:
  CheckedStdoutBuf() : buffer_(kSize), line_buffered_(::isatty(STDOUT_FILENO) == 1) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }

  // The errno of the first failed write since the last call (0: none); clears it.
  int take_error() {
    const int err = error_;
    error_ = 0;
    return err;
  }

 protected:
  int_type overflow(int_type ch) override {
    flush_buffer();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
      if (line_buffered_ && ch == '\n') flush_buffer();
    }
    return traits_type::not_eof(ch);
  }

  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const std::streamsize done = std::streambuf::xsputn(s, n);
    if (line_buffered_ && std::memchr(s, '\n', static_cast<std::size_t>(n)) != nullptr)
      flush_buffer();
    return done;
  }

  // 0 even after a failed write: the error is reported once, by finish_standard_output(), rather
  // than as a stream state that would also silence every later write of the run.
  int sync() override {
    flush_buffer();
    return 0;
  }

 private:
  static constexpr std::size_t kSize = 1 << 16;

  void flush_buffer() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    // After a failure the rest is dropped: text after a lost block would read as whole.
    while (left > 0 && error_ == 0) {
      const ssize_t n = ::write(STDOUT_FILENO, p, left);
      if (n < 0) {
        if (errno != EINTR) error_ = errno;
        continue;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }

  std::vector<char> buffer_;
  bool line_buffered_;
  int error_ = 0;
};

CheckedStdoutBuf* g_buf = nullptr;

}  // namespace

void check_standard_output() {
  if (g_buf) return;
  std::cout.flush();
  std::fflush(stdout);
  // Never deleted: the library flushes std::cout once more as the process ends.
  g_buf = new CheckedStdoutBuf();
  std::cout.rdbuf(g_buf);
}

void finish_standard_output() {
  std::cout.flush();
  int err = g_buf ? g_buf->take_error() : 0;
  errno = 0;
  if (std::fflush(stdout) != 0 && err == 0) err = errno != 0 ? errno : EIO;
  if (std::ferror(stdout)) {
    if (err == 0) err = EIO;
    std::clearerr(stdout);
  }
  if (std::cout.bad()) {
    if (err == 0) err = EIO;
    std::cout.clear();
  }
  if (err != 0)
    throw OutputError(std::string("standard output: write failed: ") + std::strerror(err));
}

}  // namespace glint
