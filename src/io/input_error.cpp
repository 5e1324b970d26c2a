#include "io/input_error.h"

#include <utility>

namespace glint {

InputError::InputError(std::string file, std::uint64_t line, std::string field, std::string message)
    : std::runtime_error(format(file, line, field, message)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(std::move(message)) {}

std::string InputError::format(const std::string& file, std::uint64_t line,
                               const std::string& field, const std::string& message) {
  std::string out = file;
  if (line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  out += ": field '";
  out += field;
  out += "': ";
  out += message;
  return out;
}

std::string quote_input(std::string_view text, std::size_t max_len) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "'";
  const std::size_t n = text.size() < max_len ? text.size() : max_len;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  out += '\'';
  if (n < text.size()) out += "...";
  return out;
}

}  // namespace glint
