// The lexical rules of vector files (traces/README.md, "Lexical rules"): blanks, decimal numbers
// and integers, material names. Shared by the header and row parsers, and by validate(), which
// holds names in memory to the same rule.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
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

// How many of the eight bytes at p, from the first, are decimal digits (0 to 8), and when fewer
// than eight, their value: a row's fraction in a few operations instead of a loop per digit.
// Little-endian (the first byte lowest). A byte less '0' is its digit; it is not a digit when
// the difference has its top bit set (a byte below '0') or reaches 10 (adding 0x76 then sets the
// top bit). Borrows and carries between bytes only move to later bytes, past the first non-digit,
// which is all that is looked at. The value: the digits moved to the high end (zeros in front of
// them), then 10 d_i + d_(i+1) in every even byte, then the four pairs weighted 10^6, 10^4, 100
// and 1 by two multiplies whose high halves add up to the number (at most 10^8 - 1, no carry).
// With the digit loop alone, glint eval of six-decimal rows ran 5 % more instructions
// (tests/bench/RESULTS.md, "Issue 30").
inline unsigned leading_digits(const char* p, std::uint64_t& value) {
  std::uint64_t w = 0;
  std::memcpy(&w, p, sizeof w);
  const std::uint64_t x = w - 0x3030303030303030ULL;
  const std::uint64_t stop = (x | (x + 0x7676767676767676ULL)) & 0x8080808080808080ULL;
  const unsigned n = stop ? static_cast<unsigned>(__builtin_ctzll(stop)) / 8 : 8;
  if (n == 0 || n == 8) return n;
  std::uint64_t v = (x & ((std::uint64_t{1} << (8 * n)) - 1)) << (8 * (8 - n));
  v = v * 10 + (v >> 8);
  v = ((v & 0x000000FF000000FFULL) * (100 + (1000000ULL << 32)) +
       ((v >> 16) & 0x000000FF000000FFULL) * (1 + (10000ULL << 32))) >>
      32;
  value = v;
  return n;
}

// The common form of a vector file's t, "-0.123456": an optional '-', 1 to 19 digits, optionally
// '.' and 1 or more digits, at most 19 digits in all. When the digits make an integer m <= 2^53
// and there are k <= 22 of them after the point, m and 10^k are exact doubles and m / 10^k is one
// correctly rounded division (Clinger's fast path), so `out` gets the bits fast_float's correctly
// rounded conversion gives, at a third of its cost; returns the end of the number. Else nullptr
// (the caller takes parse_decimal's path). Inline: rows call it per field. With fast_float alone
// (the row parser calling it directly), glint eval of six-decimal rows ran 11 % more instructions
// (tests/bench/RESULTS.md, "Issue 30").
inline const char* parse_plain_decimal(const char* b, const char* e, double& out) {
  static constexpr double kPow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                        1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                        1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* p = b;
  const bool negative = p != e && *p == '-';
  p += negative;
  std::uint64_t m = 0;
  const char* const int_begin = p;
  while (p != e && static_cast<unsigned char>(*p - '0') < 10 && p - int_begin < 19) {
    m = m * 10 + static_cast<unsigned>(*p - '0');
    ++p;
  }
  const std::ptrdiff_t int_digits = p - int_begin;
  if (int_digits == 0) return nullptr;
  std::ptrdiff_t frac_digits = 0;
  if (p != e && *p == '.') {
    const char* const frac_begin = ++p;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    static constexpr std::uint64_t kTens[8] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};
    // Fewer than eight digits with eight bytes to read (a row's t and what follows it): at once.
    // Else (and for the digits beyond) the loop below.
    std::uint64_t fraction = 0;
    if (e - p >= 8) {
      const unsigned k = leading_digits(p, fraction);
      if (k > 0 && k < 8 && int_digits + static_cast<std::ptrdiff_t>(k) <= 19) {
        m = m * kTens[k] + fraction;
        p += k;
      }
    }
#endif
    while (p != e && static_cast<unsigned char>(*p - '0') < 10 &&
           int_digits + (p - frac_begin) < 19) {
      m = m * 10 + static_cast<unsigned>(*p - '0');
      ++p;
    }
    frac_digits = p - frac_begin;
    if (frac_digits == 0) return nullptr;
  }
  // A digit left over (more than 19), an exponent or a hex or special form: the general path.
  if (p != e && (static_cast<unsigned char>(*p - '0') < 10 || *p == 'e' || *p == 'E' || *p == '.' ||
                 *p == 'x' || *p == 'X'))
    return nullptr;
  if (m > (std::uint64_t{1} << 53) || frac_digits > 22) return nullptr;
  const double v = static_cast<double>(m) / kPow10[frac_digits];
  out = negative ? -v : v;
  return p;
}

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
