// LineReader: the physical lines of a vector file, read from a stream in chunks of at most 1 MiB
// so memory stays constant whatever the input, and the current position for error messages.
//
// It enforces the rules that hold for every line, header or row: at most kVectorMaxLineBytes
// bytes (without "\n" / "\r\n"), no NUL byte. Errors are glint::InputError "FILE:LINE: field".
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <ios>
#include <memory>
#include <string>
#include <string_view>

#include "io/vectors.h"

namespace glint {

class LineReader {
 public:
  // Reads from `in`, which must outlive the reader; `file` names it in errors.
  LineReader(std::istream& in, std::string file);
  ~LineReader();

  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its "\n" or "\r\n"; false at the end of the input. The view is valid
  // until the next call. Throws InputError: field "line" for a long line or a NUL byte, "file"
  // for a read error.
  bool next(std::string_view& line) {
    // Inline for the common case, a whole line in the buffer: the row loop calls this per row.
    const char* const nl = find_newline();
    if (nl == nullptr) return next_at_buffer_end(line);
    line = take_line(nl, nl + 1);
    return true;
  }

  // The whole lines already read and not yet returned, [begin, end) (end just past a "\n"),
  // reading more first when there is none, for a caller that splits and checks them itself (the
  // parallel row parser); skip_block() then passes over them. False when there is no such block,
  // or a NUL byte lies in it: next() then goes on a line at a time (and reports the NUL).
  bool block(const char*& begin, const char*& end);
  void skip_block(const char* end, std::uint64_t lines) {
    pos_ = end;
    line_no_ += lines;
  }

  const std::string& file() const { return file_; }
  // 1-based number of the line next() returned last (0 before the first).
  std::uint64_t line_number() const { return line_no_; }
  // Where the end of the input is reported: on the last line when it lacks its line end,
  // otherwise on the (empty) line after it.
  std::uint64_t end_line() const { return last_unterminated_ ? line_no_ : line_no_ + 1; }

  // Throws InputError at the current line, or at `line`. Cold: callers' error branches are
  // laid out away from their parsing loops.
  [[noreturn]] __attribute__((cold)) void fail(const char* field, const std::string& message) const;
  [[noreturn]] __attribute__((cold)) void fail_at(std::uint64_t line, const char* field,
                                                  const std::string& message) const;

 private:
  const char* find_newline() const {
    const std::size_t avail = static_cast<std::size_t>(end_ - pos_);
    return avail != 0 ? static_cast<const char*>(std::memchr(pos_, '\n', avail)) : nullptr;
  }
  // The line [pos_, line_end), the next one starting at `next`.
  std::string_view take_line(const char* line_end, const char* next) {
    ++line_no_;
    const char* const begin = pos_;
    pos_ = next;
    std::size_t len = static_cast<std::size_t>(line_end - begin);
    if (len != 0 && begin[len - 1] == '\r') --len;
    if (len > kVectorMaxLineBytes) fail_long_line(line_no_);
    if (nul_ != nullptr && nul_ < line_end) fail_nul();
    return std::string_view(begin, len);
  }
  // No "\n" after pos_: reads more, or returns the unterminated last line.
  bool next_at_buffer_end(std::string_view& line);
  void refill();
  [[noreturn]] __attribute__((cold)) void fail_long_line(std::uint64_t line) const;
  [[noreturn]] __attribute__((cold)) void fail_nul() const;

  std::istream* in_;
  std::string file_;
  // The caller's exception mask, restored on destruction: a short read at the end of the input
  // sets failbit, which that mask could turn into std::ios_base::failure while we read.
  std::ios_base::iostate saved_exceptions_;

  std::unique_ptr<char[]> buf_;
  std::size_t capacity_ = 0;   // bytes of buf_
  bool filled_ = false;        // refill() has run: the next one grows a small buffer
  const char* pos_;            // start of the next line
  char* end_;                  // end of the bytes read so far
  const char* nul_ = nullptr;  // the first NUL byte in [pos_, end_), if any
  bool eof_ = false;           // the stream has nothing more to give
  bool last_unterminated_ = false;
  std::uint64_t line_no_ = 0;
};

}  // namespace glint
