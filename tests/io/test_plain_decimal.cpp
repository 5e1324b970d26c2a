// parse_plain_decimal (io/vector_syntax.h), the row parser's fast path for t: wherever it takes a
// number, the same bits and the same end as std::from_chars (correctly rounded, as fast_float is);
// every other form is left to the general path.
#include <gtest/gtest.h>

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "io/vector_syntax.h"

namespace glint {
namespace {

std::uint64_t bits(double v) {
  std::uint64_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Checks one text; true when the fast path took it.
bool check(const std::string& text) {
  const char* b = text.data();
  const char* e = b + text.size();
  double fast = 0;
  const char* end = parse_plain_decimal(b, e, fast);
  if (!end) return false;
  double ref = 0;
  const auto r = std::from_chars(b, e, ref);
  EXPECT_EQ(r.ec, std::errc()) << text;
  EXPECT_EQ(end, r.ptr) << text;
  EXPECT_EQ(bits(fast), bits(ref)) << text;
  return true;
}

TEST(PlainDecimal, SameBitsAsFromChars) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> decimals(0, 21), exponent(-8, 12);
  std::size_t taken = 0, tried = 0;
  char text[64];
  for (int i = 0; i < 400000; ++i) {
    const double v = unit(rng) * std::pow(10.0, exponent(rng));
    std::snprintf(text, sizeof text, "%.*f", decimals(rng), v);
    taken += check(text);
    ++tried;
    // Followed by the rest of a row: the digits after the point read eight bytes at a time.
    static const char* const kRest[] = {" bench", "\tx", ",1", "#c", "        ", " 12345678"};
    taken += check(std::string(text) + kRest[i % 6]);
    ++tried;
    // Digits that do not come from a double: every digit string of the form is its own test.
    std::string digits = std::to_string(rng() % 100000000000000000ULL);
    const std::size_t point = rng() % (digits.size() + 1);
    if (point < digits.size()) digits.insert(point == 0 ? 1 : point, ".");
    taken += check((rng() & 1 ? "-" : "") + digits);
    ++tried;
  }
  // A good part of them take the fast path (else this test would test nothing): longer digit
  // strings than 2^53 go the general way.
  EXPECT_GT(taken, tried / 4);
  for (const char* s : {"0", "-0", "-0.0", "1", "0.5", "-0.123456", "9007199254740992",
                        "0.0000000000000000000001", "1.0000000000000002220446049250313080847"})
    check(s);
  // Followed by what ends a field: the number stops there.
  EXPECT_TRUE(check("0.25 bench"));
  EXPECT_TRUE(check("-1,2"));
  // Every count of digits after the point, 1 to 18, before each byte that can end them, with
  // eight bytes or more to read.
  std::string fraction;
  for (int k = 1; k <= 18; ++k) {
    fraction += static_cast<char>('0' + (k * 7) % 10);
    for (const char* rest :
         {" bench", "\tlight 1", ",gold", "#comment", "/ 0", ": 9", "        "}) {
      // The fast path takes every such number of up to 15 digits (below 2^53); check() tests the
      // longer ones too when it takes them.
      const bool short_taken = check("0." + fraction + rest);
      const bool long_taken = check("-12." + fraction + rest);
      EXPECT_TRUE(k > 13 || (short_taken && long_taken)) << k << rest;
    }
  }
}

TEST(PlainDecimal, LeavesOtherFormsToTheGeneralPath) {
  double v = 0;
  for (const char* s :
       {"", "-", ".5", "1.", "1e3", "1.5e-3", "1E3", "+1", "inf", "-nan", "0x1p3", "1.2.3",
        "9007199254740993", "12345678901234567890", "0.12345678901234567890123", "--1"}) {
    const char* b = s;
    EXPECT_EQ(parse_plain_decimal(b, b + std::strlen(s), v), nullptr) << s;
  }
}

}  // namespace
}  // namespace glint
