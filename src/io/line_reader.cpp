#include "io/line_reader.h"

#include <cerrno>
#include <istream>

#include "io/input_error.h"
#include "io/vector_rules.h"

namespace glint {

namespace {

// The buffer starts small and doubles at each refill up to kMaxBufferBytes: a large file is read
// in 1 MiB chunks (the block parser's unit of work), while a small input costs no 1 MiB allocation
// (under ASan such a block is an mmap and munmap per reader: the fuzzer's vectors harness spent a
// quarter of its time there). Any size holds a longest line and its "\r\n".
constexpr std::size_t kFirstBufferBytes = std::size_t{1} << 16;
constexpr std::size_t kMaxBufferBytes = std::size_t{1} << 20;
static_assert(kFirstBufferBytes > kVectorMaxLineBytes + 2, "the buffer must hold a longest line");

}  // namespace

LineReader::LineReader(std::istream& in, std::string file)
    : in_(&in), file_(std::move(file)), saved_exceptions_(in.exceptions()) {
  in_->exceptions(std::ios_base::goodbit);
  buf_.reset(new char[kFirstBufferBytes]);
  capacity_ = kFirstBufferBytes;
  pos_ = end_ = buf_.get();
}

LineReader::~LineReader() {
  try {
    in_->exceptions(saved_exceptions_);
  } catch (...) {  // the stream is at EOF/failed: restoring the mask may throw; nothing to do
  }
}

void LineReader::fail(const char* field, const std::string& message) const {
  fail_at(line_no_, field, message);
}

void LineReader::fail_at(std::uint64_t line, const char* field, const std::string& message) const {
  throw InputError(file_, line, field, message);
}

void LineReader::fail_long_line(std::uint64_t line) const {
  fail_at(line, "line", line_too_long_text());
}

void LineReader::fail_nul() const {
  fail("line", "embedded NUL byte (not a text file?)");
}

bool LineReader::next_at_buffer_end(std::string_view& line) {
  for (;;) {
    const std::size_t avail = static_cast<std::size_t>(end_ - pos_);
    // Without a "\n" in more than a line's worth of bytes (plus a "\r"), the line is too long
    // whatever follows: refuse it now rather than read on to its end.
    if (avail > kVectorMaxLineBytes + 1) fail_long_line(line_no_ + 1);
    if (eof_) {
      if (avail == 0) return false;
      last_unterminated_ = true;
      line = take_line(end_, end_);
      return true;
    }
    refill();
    if (const char* const nl = find_newline()) {
      line = take_line(nl, nl + 1);
      return true;
    }
  }
}

bool LineReader::block(const char*& begin, const char*& end) {
  const auto last_newline = [&]() -> const char* {
    const std::size_t avail = static_cast<std::size_t>(end_ - pos_);
    return avail != 0 ? static_cast<const char*>(memrchr(pos_, '\n', avail)) : nullptr;
  };
  const char* nl = last_newline();
  if (nl == nullptr && !eof_ && static_cast<std::size_t>(end_ - pos_) <= kVectorMaxLineBytes + 1) {
    refill();
    nl = last_newline();
  }
  if (nl == nullptr || (nul_ != nullptr && nul_ <= nl)) return false;
  begin = pos_;
  end = nl + 1;
  return true;
}

// Moves the unread tail to the front of the buffer (a larger one after the first fill, up to
// kMaxBufferBytes) and fills the rest from the stream.
void LineReader::refill() {
  const std::size_t rem = static_cast<std::size_t>(end_ - pos_);
  if (filled_ && capacity_ < kMaxBufferBytes) {
    std::unique_ptr<char[]> bigger(new char[capacity_ * 2]);
    std::memcpy(bigger.get(), pos_, rem);
    if (nul_ != nullptr) nul_ = bigger.get() + (nul_ - pos_);
    buf_ = std::move(bigger);
    capacity_ *= 2;
    pos_ = buf_.get();
    end_ = buf_.get() + rem;
  } else if (pos_ != buf_.get()) {
    std::memmove(buf_.get(), pos_, rem);
    if (nul_ != nullptr) nul_ -= pos_ - buf_.get();
    pos_ = buf_.get();
    end_ = buf_.get() + rem;
  }
  filled_ = true;
  const std::size_t room = capacity_ - rem;
  errno = 0;
  in_->read(end_, static_cast<std::streamsize>(room));
  const auto got = static_cast<std::size_t>(in_->gcount());
  if (in_->bad()) {
    const int err = errno;
    fail_at(line_no_ + 1, "file",
            std::string("read error") + (err != 0 ? std::string(": ") + std::strerror(err) : ""));
  }
  if (got < room) eof_ = true;
  if (nul_ == nullptr && got > 0) nul_ = static_cast<const char*>(std::memchr(end_, '\0', got));
  end_ += got;
}

}  // namespace glint
