#include "io/vector_syntax.h"

#include <fast_float/fast_float.h>

#include "io/input_error.h"
#include "io/vectors.h"

namespace glint {

void split_header_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  const auto hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

NumberStatus parse_decimal(const char* b, const char* e, double& out) {
  if (parse_plain_decimal(b, e, out) == e) return NumberStatus::kOk;
  double v = 0;
  const auto r = fast_float::from_chars(b, e, v);
  if (r.ptr != e || r.ec != std::errc()) return NumberStatus::kNotNumber;
  if (v == 0 || std::isinf(v)) {
    const char* p = b + (*b == '-');
    const bool word = p != e && ((*p | 0x20) == 'i' || (*p | 0x20) == 'n');  // inf, nan
    if (std::isinf(v) && !word) return NumberStatus::kOutOfRange;
    if (v == 0) {
      // Zero from a mantissa with a non-zero digit: an underflow, as from_chars reports it.
      for (; p != e && *p != 'e' && *p != 'E'; ++p)
        if (*p >= '1' && *p <= '9') return NumberStatus::kOutOfRange;
    }
  }
  if (!std::isfinite(v)) return NumberStatus::kNotFinite;
  out = v;
  return NumberStatus::kOk;
}

std::string number_problem(NumberStatus status, std::string_view text, bool integer) {
  switch (status) {
    case NumberStatus::kOk:
      break;
    case NumberStatus::kNotNumber:
      return std::string(integer ? "not an integer: " : "not a number: ") + quote_input(text);
    case NumberStatus::kOutOfRange:
      return (integer ? "integer out of range: " : "number out of the range of a double: ") +
             quote_input(text);
    case NumberStatus::kNotFinite:
      return "value must be finite, got " + quote_input(text);
  }
  return "invalid value " + quote_input(text);
}

std::string format_double(double v) {
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, v);
  return std::string(text, r.ptr);
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.size() > kVectorMaxNameLength) return false;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (!alpha(name[0]) && name[0] != '_') return false;
  for (char c : name) {
    if (!alpha(c) && !(c >= '0' && c <= '9') && c != '_' && c != '.' && c != '-') return false;
  }
  return true;
}

std::string name_rule() {
  return "names are 1-" + std::to_string(kVectorMaxNameLength) +
         " characters [A-Za-z0-9_.-] starting with a letter or '_'";
}

}  // namespace glint
