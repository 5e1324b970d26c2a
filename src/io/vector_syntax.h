// The lexical rules of vector files (traces/README.md, "Lexical rules"): blanks, decimal numbers
// and integers, material names. Shared by the header and row parsers, and by validate(), which
// holds names in memory to the same rule.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

namespace glint {

inline bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

// The blank-separated tokens of a header line, up to its comment.
void split_header_tokens(std::string_view line, std::vector<std::string_view>& tokens);

enum class NumberStatus { kOk, kNotNumber, kOutOfRange, kNotFinite };

// A double from [b, e), all of it, by fast_float (Debian libfast-float-dev: locale-independent,
// correctly rounded, several times faster than strtod), with std::from_chars' verdicts: text
// whose value overflows to infinity or underflows to zero is kOutOfRange, which fast_float alone
// would return as inf or 0. No sign handling beyond from_chars' (parse_number does the '+').
NumberStatus parse_decimal(const char* b, const char* e, double& out);

// Decimal numbers (doubles by parse_decimal, 32-bit integers by std::from_chars). An optional
// leading '+' is accepted, which from_chars alone refuses. Hex floats are not (from_chars'
// general format has no "0x"). nan/inf parse but are kNotFinite; magnitudes beyond the type's
// range (1e999, 1e-999, 2^31) are kOutOfRange. Inline: rows call it per field.
template <class T>
NumberStatus parse_number(std::string_view text, T& out) {
  const char* b = text.data();
  const char* const e = b + text.size();
  if (b != e && *b == '+') {
    ++b;
    if (b != e && *b == '-') return NumberStatus::kNotNumber;
  }
  if (b == e) return NumberStatus::kNotNumber;
  if constexpr (std::is_same_v<T, double>) {
    return parse_decimal(b, e, out);
  }
  T v = 0;
  const auto r = std::from_chars(b, e, v);
  if (r.ptr != e) return NumberStatus::kNotNumber;
  if (r.ec == std::errc::result_out_of_range) return NumberStatus::kOutOfRange;
  if (r.ec != std::errc()) return NumberStatus::kNotNumber;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return NumberStatus::kNotFinite;
  }
  out = v;
  return NumberStatus::kOk;
}

// What is wrong with `text`, which parse_number refused with `status`, for an error message.
std::string number_problem(NumberStatus status, std::string_view text, bool integer);

// v in shortest round-trip form, as the writer writes numbers (and messages quote limits).
std::string format_double(double v);

// Names: 1..kVectorMaxNameLength bytes of [A-Za-z0-9_.-], starting with a letter or '_'.
bool valid_name(std::string_view name);
// The rule valid_name() checks, in words, for error messages.
std::string name_rule();

}  // namespace glint
