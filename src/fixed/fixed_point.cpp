#include "fixed/fixed_point.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace glint {

const char* to_string(Quant q) {
  switch (q) {
    case Quant::kTrn:
      return "trn";
    case Quant::kRnd:
      return "rnd";
    case Quant::kRndConv:
      return "rnd_conv";
  }
  return "?";
}

const char* to_string(Overflow o) {
  return o == Overflow::kWrap ? "wrap" : "sat";
}

double QFormat::ulp() const {
  return std::ldexp(1.0, -frac_bits);
}
double QFormat::max_value() const {
  return std::ldexp(static_cast<double>(raw_max()), -frac_bits);
}
double QFormat::min_value() const {
  return std::ldexp(static_cast<double>(raw_min()), -frac_bits);
}

std::string QFormat::name() const {
  return fmt::format("{}q{}.{}", is_signed ? 's' : 'u', int_bits, frac_bits);
}

namespace detail {
void throw_bad_format(int int_bits, int frac_bits, bool is_signed) {
  const QFormat f{int_bits, frac_bits, is_signed};
  throw std::invalid_argument(fmt::format("fixed-point format {} has width {}; allowed 1..{}",
                                          f.name(), std::int64_t{int_bits} + frac_bits,
                                          QFormat::kMaxWidth));
}

void throw_too_wide(int int_bits, int frac_bits, bool is_signed, const char* op) {
  const QFormat f{int_bits, frac_bits, is_signed};
  throw std::overflow_error(
      fmt::format("exact {} needs format {} wider than {} bits", op, f.name(), QFormat::kMaxWidth));
}
}  // namespace detail

QFormat parse_q_format(std::string_view text) {
  const std::string orig(text);
  auto fail = [&]() -> QFormat {
    throw std::invalid_argument("bad fixed-point format '" + orig +
                                "': expected uqI.F or sqI.F, e.g. uq1.15");
  };
  if (text.empty()) return fail();
  QFormat f;
  if (text[0] == 'u' || text[0] == 'U') {
    f.is_signed = false;
  } else if (text[0] == 's' || text[0] == 'S') {
    f.is_signed = true;
  } else {
    return fail();
  }
  text.remove_prefix(1);
  if (!text.empty() && (text[0] == 'q' || text[0] == 'Q')) text.remove_prefix(1);
  const auto dot = text.find('.');
  if (dot == std::string_view::npos) return fail();
  auto parse_int = [&](std::string_view s, int& out) {
    const char* b = s.data();
    const char* e = s.data() + s.size();
    auto [p, ec] = std::from_chars(b, e, out);
    return ec == std::errc() && p == e && !s.empty();
  };
  if (!parse_int(text.substr(0, dot), f.int_bits) || !parse_int(text.substr(dot + 1), f.frac_bits))
    return fail();
  // A part below -62 leaves no representable bit at either end of a 62-bit word; bounding both
  // parts from below bounds them from above (width <= 62), so the differences of two formats'
  // parts that the datapaths compute (shifts between formats) stay far from int overflow.
  if (f.int_bits < -QFormat::kMaxWidth || f.frac_bits < -QFormat::kMaxWidth)
    throw std::invalid_argument(fmt::format(
        "bad fixed-point format '{}': integer and fraction bits must each be at least -{}", orig,
        QFormat::kMaxWidth));
  check_format(f);
  return f;
}

__int128 round_shift128(__int128 raw, int shift, Quant q) {
  if (shift <= 0) return raw;
  if (shift >= 127) {
    // |raw| < 2^126 here, so the value lies in (-1/2, 1/2): floor is 0 or -1, and only a
    // negative value could round up, which needs the remainder to reach one half: it cannot.
    const __int128 fl = raw < 0 ? -1 : 0;
    return q == Quant::kTrn ? fl : 0;  // |value| < 1/2: nearest is 0 in both rounding modes
  }
  const __int128 fl = raw >> shift;
  if (q == Quant::kTrn) return fl;
  const unsigned __int128 one = 1;
  const unsigned __int128 mask = (one << shift) - 1;
  const unsigned __int128 rem = static_cast<unsigned __int128>(raw) & mask;
  const unsigned __int128 half = one << (shift - 1);
  if (q == Quant::kRnd) return fl + (rem >= half ? 1 : 0);
  return fl + ((rem > half || (rem == half && (fl & 1))) ? 1 : 0);
}

namespace detail {
// quantize_raw for raws beyond int64 and shifts outside 0..62 (left shifts, huge right shifts).
std::int64_t quantize_raw_wide(__int128 raw, int from_frac, const QFormat& to, Quant q,
                               Overflow o) {
  const int shift = from_frac - to.frac_bits;
  __int128 v;
  if (shift >= 0) {
    v = round_shift128(raw, shift, q);
  } else {
    // Exact left shift; saturate the intermediate before it could leave 128 bits.
    const int up = -shift;
    const __int128 limit = static_cast<__int128>(1) << (126 - std::min(up, 126));
    if (up >= 126 || raw >= limit || raw < -limit) {
      if (raw == 0) return 0;
      if (o == Overflow::kSat) return raw > 0 ? to.raw_max() : to.raw_min();
      if (up >= 64) return 0;  // every kept bit is a shifted-in zero
      v = static_cast<__int128>(static_cast<unsigned __int128>(raw) << up);
    } else {
      v = raw * (static_cast<__int128>(1) << up);
    }
  }
  return fit_overflow(v, to, o);
}
}  // namespace detail

void Fixed::throw_out_of_range() const {
  throw std::out_of_range(fmt::format("raw value {} outside format {}", raw_, fmt_.name()));
}

Fixed Fixed::from_double(double x, const QFormat& fmt, Quant q, Overflow o) {
  check_format(fmt);
  if (std::isnan(x)) throw std::invalid_argument("cannot convert NaN to fixed point");
  if (std::isinf(x)) {
    if (o == Overflow::kSat) return Fixed(x > 0 ? fmt.raw_max() : fmt.raw_min(), fmt);
    throw std::invalid_argument("cannot wrap an infinite value into fixed point");
  }
  // x = mant * 2^(e - 53) exactly, with |mant| < 2^53 an integer (also for subnormals, which
  // frexp normalizes); quantize_raw then rounds and fits exactly, with no double arithmetic
  // that could round or underflow.
  int e = 0;
  const double m = std::frexp(x, &e);
  const auto mant = static_cast<std::int64_t>(std::ldexp(m, 53));
  return Fixed(quantize_raw(mant, 53 - e, fmt, q, o), fmt);
}

double Fixed::to_double() const {
  return std::ldexp(static_cast<double>(raw_), -fmt_.frac_bits);
}

std::string Fixed::to_string() const {
  return fmt::format("{} ({})", to_double(), fmt_.name());
}

namespace {
// Aligns a raw to `frac` fraction bits (exact: frac >= the operand's frac bits, shift <= 64).
__int128 align(const Fixed& v, int frac) {
  return static_cast<__int128>(v.raw()) *
         (static_cast<__int128>(1) << (frac - v.format().frac_bits));
}
}  // namespace

int compare(const Fixed& a, const Fixed& b) {
  const int frac = std::max(a.format().frac_bits, b.format().frac_bits);
  // Both raws fit 62 bits and the alignment shift is at most ~124 bits for sane formats; clamp
  // the shift so the comparison stays exact for any formats that pass check_format.
  const int sa = frac - a.format().frac_bits, sb = frac - b.format().frac_bits;
  if (sa > 64 || sb > 64) {
    // One value has far more fraction bits: shift it down to the other's scale instead (floor),
    // then break ties with the discarded bits.
    const Fixed& hi = sa > 64 ? b : a;  // the one with more fraction bits
    const Fixed& lo = sa > 64 ? a : b;
    const int s = hi.format().frac_bits - lo.format().frac_bits;
    const __int128 hi_floor = round_shift128(hi.raw(), s, Quant::kTrn);
    const bool hi_has_rest = (static_cast<__int128>(hi.raw()) -
                              hi_floor * (static_cast<__int128>(1) << std::min(s, 126))) != 0;
    int c = hi_floor < lo.raw() ? -1 : (hi_floor > lo.raw() ? 1 : (hi_has_rest ? 1 : 0));
    return sa > 64 ? -c : c;
  }
  const __int128 x = align(a, frac), y = align(b, frac);
  return x < y ? -1 : (x > y ? 1 : 0);
}

}  // namespace glint
