// InputError: a malformed input file, pinned to a file, a 1-based line and a named field.
//
// what() reads "FILE:LINE: field 'FIELD': MESSAGE", the form compilers use, so editors and
// terminals can jump to the offending line. Raised by every glint input parser (vector files, and
// later configuration files) for anything a user can get wrong in a file; programming errors
// (calling an API with invalid arguments) use std::invalid_argument instead.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace glint {

class InputError : public std::runtime_error {
 public:
  // line is 1-based; 0 means "no particular line" (e.g. the file cannot be opened) and is then
  // left out of what(): "FILE: field 'FIELD': MESSAGE".
  InputError(std::string file, std::uint64_t line, std::string field, std::string message);

  const std::string& file() const { return file_; }
  std::uint64_t line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

  static std::string format(const std::string& file, std::uint64_t line, const std::string& field,
                            const std::string& message);

 private:
  std::string file_;
  std::uint64_t line_;
  std::string field_;
  std::string message_;
};

// Quotes a piece of untrusted input for an error message: at most max_len bytes, bytes outside
// printable ASCII shown as \xNN, wrapped in single quotes, "..." appended when cut.
std::string quote_input(std::string_view text, std::size_t max_len = 40);

}  // namespace glint
