// glint's bit-accurate fixed-point type: a raw two's-complement integer in an int64 plus a format.
//
// Semantics follow SystemC's sc_fixed<W, I, Q, O> (the test oracle, bit for bit):
//   value = raw * 2^-frac_bits, W = int_bits + frac_bits, I = int_bits (the sign bit counts as an
//   integer bit for signed formats, as in SystemC). W is 1..62 so that every exact sum of two
//   operands fits in an int64; products of two operands are formed in 128 bits.
// Quantization modes: Quant::kTrn = SC_TRN (floor), kRnd = SC_RND (round half towards +inf),
// kRndConv = SC_RND_CONV (round half to even). Overflow: kWrap = SC_WRAP (n_bits = 0, modulo 2^W),
// kSat = SC_SAT.
//
// Arithmetic is exact: add/sub/mul return a full-precision result in a format wide enough to hold
// it, and rounding happens only in an explicit quantize() to a target format, which is how a
// datapath designer thinks of a register boundary.
//
// The hot paths (round_shift, fit_overflow, quantize_raw for results that fit an int64, and the
// Fixed operations built on them) are inline; only rare wide cases and error paths are out of line.
//
// Known SystemC 2.3.4 deviation (tests/fixed/test_fixed_point.cpp,
// FixedEdge.SystemCProductCarryDefect):
// SystemC can lose the rounding carry when quantizing a product whose mantissa is all ones up to
// its top word (the result depends on how SystemC computed the value, not only on the value).
// glint always rounds the value as the mode defines, which equals SystemC's result for the same
// value formed by sc_fxval addition.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace glint {

enum class Quant : std::uint8_t { kTrn, kRnd, kRndConv };
enum class Overflow : std::uint8_t { kWrap, kSat };

const char* to_string(Quant q);
const char* to_string(Overflow o);

// A fixed-point format: widths only, no value. Plain data so unit configurations can hold it.
struct QFormat {
  int int_bits = 1;
  int frac_bits = 15;
  bool is_signed = false;

  static constexpr int kMaxWidth = 62;

  constexpr int width() const { return int_bits + frac_bits; }
  constexpr std::int64_t raw_max() const {
    return is_signed ? (std::int64_t{1} << (width() - 1)) - 1 : (std::int64_t{1} << width()) - 1;
  }
  constexpr std::int64_t raw_min() const {
    return is_signed ? -(std::int64_t{1} << (width() - 1)) : 0;
  }
  // Raw value of 1.0, or 0 when 1.0 is not representable.
  constexpr std::int64_t raw_one() const {
    return (frac_bits >= 0 && frac_bits < 62 && (std::int64_t{1} << frac_bits) <= raw_max())
               ? std::int64_t{1} << frac_bits
               : 0;
  }
  double ulp() const;  // 2^-frac_bits
  double max_value() const;
  double min_value() const;
  // In 64 bits: a format read from text may hold parts whose int sum overflows (e.g. uq2e9.2e9).
  bool valid() const {
    const std::int64_t w = std::int64_t{int_bits} + frac_bits;
    return w >= 1 && w <= kMaxWidth;
  }

  // "uq1.15" / "sq2.14": u or s, then integer bits (sign included), then fraction bits.
  std::string name() const;
  friend constexpr bool operator==(const QFormat& a, const QFormat& b) {
    return a.int_bits == b.int_bits && a.frac_bits == b.frac_bits && a.is_signed == b.is_signed;
  }
  friend constexpr bool operator!=(const QFormat& a, const QFormat& b) { return !(a == b); }
};

constexpr QFormat uq(int int_bits, int frac_bits) {
  return QFormat{int_bits, frac_bits, false};
}
constexpr QFormat sq(int int_bits, int frac_bits) {
  return QFormat{int_bits, frac_bits, true};
}

namespace detail {
// Cold error paths. They take the format as scalars (in registers), so that the hot paths do not
// store formats to memory just in case.
[[noreturn]] void throw_bad_format(int int_bits, int frac_bits, bool is_signed);
[[noreturn]] void throw_too_wide(int int_bits, int frac_bits, bool is_signed, const char* op);
}  // namespace detail

// Parses "uq1.15", "sq2.14" (also "u1.15", "s2.14"; case-insensitive u/s/q). Integer and
// fraction bits are decimal integers and may be negative (as SystemC's I may be), e.g.
// "uq-2.10", but neither below -62, so that both lie in -62..124; the width must be 1..62.
// Throws std::invalid_argument.
QFormat parse_q_format(std::string_view text);
// Throws std::invalid_argument unless 1 <= width <= 62.
inline void check_format(const QFormat& f) {
  if (__builtin_expect(!f.valid(), 0))
    detail::throw_bad_format(f.int_bits, f.frac_bits, f.is_signed);
}

// ---- Raw-level kernels (the hot path of every datapath; inline and branch-light) -------------

__int128 round_shift128(__int128 raw, int shift, Quant q);

// raw * 2^shift for a raw of either sign: a left shift of a negative int64_t is undefined in
// C++17, so the shift is done on the two's-complement bits (a hardware shifter's behaviour). The
// caller keeps the result in range (every datapath proves its register widths fit 62 bits).
inline std::int64_t shift_left(std::int64_t raw, int shift) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(raw) << shift);
}

namespace detail {
// round_shift for |raw| near the int64 limits, where adding the rounding offset could overflow.
inline std::int64_t round_shift_near_limits(std::int64_t raw, int shift, Quant q) {
  const std::int64_t fl = raw >> shift;                          // arithmetic shift = floor
  if (q == Quant::kRnd) return fl + ((raw >> (shift - 1)) & 1);  // + the round bit
  // Round half even: (rem + half - 1 + odd) carries out iff rem > half, or rem == half and odd.
  const std::uint64_t rem = static_cast<std::uint64_t>(raw) & ((std::uint64_t{1} << shift) - 1);
  const std::uint64_t half_m1 = (std::uint64_t{1} << (shift - 1)) - 1;
  return fl +
         static_cast<std::int64_t>((rem + half_m1 + static_cast<std::uint64_t>(fl & 1)) >> shift);
}
}  // namespace detail

namespace detail {
// round_shift for |raw| < 2^62 and shift 0..62, where adding the rounding offset cannot
// overflow: floor((raw + half) / 2^shift) rounds half up; adding half - 1, plus one more when the
// floor is odd, rounds half to even.
inline std::int64_t round_shift_narrow(std::int64_t raw, int shift, Quant q) {
  const std::int64_t half = (std::int64_t{1} << shift) >> 1;  // 0 for shift 0
  switch (q) {
    case Quant::kTrn:
      break;
    case Quant::kRnd:
      return (raw + half) >> shift;
    case Quant::kRndConv:
      if (shift == 0) return raw;
      return (raw + (half - 1) + ((raw >> shift) & 1)) >> shift;
  }
  return raw >> shift;  // arithmetic shift = floor
}
}  // namespace detail

// Rounds raw (scaled by 2^-shift relative to the target) right by `shift` >= 0 bits.
// Branch-free for a given q except for a predictable test of |raw| against 2^62.
inline std::int64_t round_shift(std::int64_t raw, int shift, Quant q) {
  if (shift <= 0) return raw;
  if (shift >= 63) return static_cast<std::int64_t>(round_shift128(raw, shift, q));
  constexpr std::uint64_t kLimit = std::uint64_t{1} << 62;
  if (q != Quant::kTrn &&
      __builtin_expect(static_cast<std::uint64_t>(raw) + kLimit >= 2 * kLimit, 0)) {
    return detail::round_shift_near_limits(raw, shift, q);
  }
  return detail::round_shift_narrow(raw, shift, q);
}

namespace detail {
// fit_overflow for a value already known to fit an int64.
inline std::int64_t fit_overflow64(std::int64_t v, const QFormat& to, Overflow o) {
  const std::int64_t hi = to.raw_max(), lo = to.raw_min();
  // One unsigned compare, v - lo <= hi - lo, and a branch that is almost always taken (values
  // seldom overflow), which keeps the clamp off the dependency chain of a datapath.
  if (__builtin_expect(static_cast<std::uint64_t>(v) - static_cast<std::uint64_t>(lo) <=
                           static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo),
                       1)) {
    return v;
  }
  if (o == Overflow::kSat) return v < lo ? lo : hi;
  // Wrap: keep the low W bits, then sign-extend for signed formats.
  const int unused = 64 - to.width();
  const std::uint64_t low = static_cast<std::uint64_t>(v) << unused;
  return to.is_signed ? static_cast<std::int64_t>(low) >> unused
                      : static_cast<std::int64_t>(low >> unused);
}

std::int64_t quantize_raw_wide(__int128 raw, int from_frac, const QFormat& to, Quant q, Overflow o);
}  // namespace detail

// Applies the overflow mode of `to` (a valid format) to an integer already at `to`'s scale.
inline std::int64_t fit_overflow(__int128 v, const QFormat& to, Overflow o) {
  const auto v64 = static_cast<std::int64_t>(v);
  if (static_cast<__int128>(v64) == v) return detail::fit_overflow64(v64, to, o);
  // Beyond int64: saturate by sign, or keep the low W (<= 62) bits, which v64 already holds.
  if (o == Overflow::kSat) return v > 0 ? to.raw_max() : to.raw_min();
  return detail::fit_overflow64(v64, to, Overflow::kWrap);
}

// Requantizes raw (with `from_frac` fraction bits) to `to` (a valid format): rounding, then
// overflow handling. Inline for the common case (raw fits an int64, shift 0..62 bits right).
inline std::int64_t quantize_raw(__int128 raw, int from_frac, const QFormat& to, Quant q,
                                 Overflow o) {
  const int shift = from_frac - to.frac_bits;
  const auto r64 = static_cast<std::int64_t>(raw);
  if (__builtin_expect(static_cast<__int128>(r64) == raw && shift >= 0 && shift < 63, 1)) {
    return detail::fit_overflow64(round_shift(r64, shift, q), to, o);
  }
  return detail::quantize_raw_wide(raw, from_frac, to, q, o);
}

// ---- The value type --------------------------------------------------------------------------

class Fixed {
 public:
  Fixed() = default;
  // Raw constructor: raw must already lie in fmt's range (checked; throws std::out_of_range).
  Fixed(std::int64_t raw, const QFormat& fmt) : raw_(raw), fmt_(fmt) {
    check_format(fmt);
    if (raw < fmt.raw_min() || raw > fmt.raw_max()) throw_out_of_range();
  }

  // Documented conversion from double: the exact value of x is rounded by q and fitted by o
  // exactly as SystemC assigns a double to sc_fixed (also for subnormal, huge and out-of-range
  // x). NaN throws std::invalid_argument; +-Inf saturate under kSat and throw
  // std::invalid_argument under kWrap (SystemC rejects both).
  static Fixed from_double(double x, const QFormat& fmt, Quant q = Quant::kRndConv,
                           Overflow o = Overflow::kSat);
  static Fixed from_raw(std::int64_t raw, const QFormat& fmt) { return Fixed(raw, fmt); }

  std::int64_t raw() const { return raw_; }
  const QFormat& format() const { return fmt_; }
  // Exact for width <= 53 (the double mantissa) unless the value underflows double (frac_bits
  // beyond ~1000); wider values round to nearest even.
  double to_double() const;
  std::string to_string() const;

 private:
  [[noreturn]] void throw_out_of_range() const;

  struct Unchecked {};
  // For results that are in range by construction.
  Fixed(std::int64_t raw, const QFormat& fmt, Unchecked) : raw_(raw), fmt_(fmt) {}
  friend Fixed add(const Fixed& a, const Fixed& b);
  friend Fixed sub(const Fixed& a, const Fixed& b);
  friend Fixed mul(const Fixed& a, const Fixed& b);
  friend Fixed quantize(const Fixed& v, const QFormat& to, Quant q, Overflow o);
  friend Fixed mul_quantize(const Fixed& a, const Fixed& b, const QFormat& to, Quant q, Overflow o);

  std::int64_t raw_ = 0;
  QFormat fmt_{};
};

// Full-precision result formats: conventional bit growth (the smallest formats that hold every
// exact result for operands spanning their formats' whole ranges). add: one integer bit more than
// the wider operand, signed if either is (an unsigned operand then counts one more bit); sub:
// always signed, one bit more than the wider operand (as signed, unless both are unsigned);
// mul: integer and fraction bits add up, signed if either is.
namespace detail {
// Integer bits an operand needs when viewed as signed.
constexpr int signed_int_bits(const QFormat& f) {
  return f.int_bits + (f.is_signed ? 0 : 1);
}
constexpr int max_int(int a, int b) {
  return a > b ? a : b;
}
}  // namespace detail

constexpr QFormat add_format(const QFormat& a, const QFormat& b) {
  const bool s = a.is_signed || b.is_signed;
  const int int_bits = s ? detail::max_int(detail::signed_int_bits(a), detail::signed_int_bits(b))
                         : detail::max_int(a.int_bits, b.int_bits);
  return QFormat{int_bits + 1, detail::max_int(a.frac_bits, b.frac_bits), s};
}
constexpr QFormat sub_format(const QFormat& a, const QFormat& b) {
  // Unsigned - unsigned lies in (-2^Ib, 2^Ia).
  const int int_bits = (a.is_signed || b.is_signed)
                           ? detail::max_int(detail::signed_int_bits(a), detail::signed_int_bits(b))
                           : detail::max_int(a.int_bits, b.int_bits);
  return QFormat{int_bits + 1, detail::max_int(a.frac_bits, b.frac_bits), true};
}
constexpr QFormat mul_format(const QFormat& a, const QFormat& b) {
  // Signed x unsigned of widths Wa, Wb fits Wa + Wb signed bits, so the integer bits simply add.
  return QFormat{a.int_bits + b.int_bits, a.frac_bits + b.frac_bits, a.is_signed || b.is_signed};
}

// Exact arithmetic. Throws std::overflow_error if the exact result format exceeds 62 bits; use
// mul_quantize for wide products.
inline Fixed add(const Fixed& a, const Fixed& b) {
  const QFormat f = add_format(a.format(), b.format());
  if (__builtin_expect(f.width() > QFormat::kMaxWidth, 0))
    detail::throw_too_wide(f.int_bits, f.frac_bits, f.is_signed, "sum");
  // Both aligned operands fit the <= 62-bit result, so 64-bit shifts are exact.
  const auto ua = static_cast<std::uint64_t>(a.raw()) << (f.frac_bits - a.format().frac_bits);
  const auto ub = static_cast<std::uint64_t>(b.raw()) << (f.frac_bits - b.format().frac_bits);
  return Fixed(static_cast<std::int64_t>(ua + ub), f, Fixed::Unchecked{});
}
inline Fixed sub(const Fixed& a, const Fixed& b) {
  const QFormat f = sub_format(a.format(), b.format());
  if (__builtin_expect(f.width() > QFormat::kMaxWidth, 0))
    detail::throw_too_wide(f.int_bits, f.frac_bits, f.is_signed, "difference");
  const auto ua = static_cast<std::uint64_t>(a.raw()) << (f.frac_bits - a.format().frac_bits);
  const auto ub = static_cast<std::uint64_t>(b.raw()) << (f.frac_bits - b.format().frac_bits);
  return Fixed(static_cast<std::int64_t>(ua - ub), f, Fixed::Unchecked{});
}
inline Fixed mul(const Fixed& a, const Fixed& b) {
  const QFormat f = mul_format(a.format(), b.format());
  if (__builtin_expect(f.width() > QFormat::kMaxWidth, 0))
    detail::throw_too_wide(f.int_bits, f.frac_bits, f.is_signed, "product");
  return Fixed(a.raw() * b.raw(), f, Fixed::Unchecked{});  // |product| < 2^62
}

// Rounding and overflow handling to a target format: the only place precision is lost.
inline Fixed quantize(const Fixed& v, const QFormat& to, Quant q, Overflow o) {
  check_format(to);
  // |raw| < 2^62 (width <= 62), so a right shift of 0..62 bits takes round_shift's short path.
  const int shift = v.format().frac_bits - to.frac_bits;
  const std::int64_t r =
      __builtin_expect(static_cast<unsigned>(shift) < 63u, 1)
          ? detail::fit_overflow64(detail::round_shift_narrow(v.raw(), shift, q), to, o)
          : detail::quantize_raw_wide(v.raw(), v.format().frac_bits, to, q, o);
  return Fixed(r, to, Fixed::Unchecked{});
}
// Exact product formed in 128 bits, then quantized; valid for any pair of <= 62-bit operands.
inline Fixed mul_quantize(const Fixed& a, const Fixed& b, const QFormat& to, Quant q, Overflow o) {
  check_format(to);
  const int from_frac = a.format().frac_bits + b.format().frac_bits;
  const int shift = from_frac - to.frac_bits;
  // Operands of Wa + Wb <= 62 bits: |product| < 2^62 in 64 bits, the short rounding path.
  if (__builtin_expect(
          a.format().width() + b.format().width() <= 62 && static_cast<unsigned>(shift) < 63u, 1)) {
    return Fixed(
        detail::fit_overflow64(detail::round_shift_narrow(a.raw() * b.raw(), shift, q), to, o), to,
        Fixed::Unchecked{});
  }
  const __int128 p = static_cast<__int128>(a.raw()) * b.raw();
  return Fixed(quantize_raw(p, from_frac, to, q, o), to, Fixed::Unchecked{});
}

// Exact comparison of values in any two formats: -1, 0 or +1.
int compare(const Fixed& a, const Fixed& b);
inline bool operator==(const Fixed& a, const Fixed& b) {
  return compare(a, b) == 0;
}
inline bool operator!=(const Fixed& a, const Fixed& b) {
  return compare(a, b) != 0;
}
inline bool operator<(const Fixed& a, const Fixed& b) {
  return compare(a, b) < 0;
}
inline bool operator<=(const Fixed& a, const Fixed& b) {
  return compare(a, b) <= 0;
}
inline bool operator>(const Fixed& a, const Fixed& b) {
  return compare(a, b) > 0;
}
inline bool operator>=(const Fixed& a, const Fixed& b) {
  return compare(a, b) >= 0;
}

}  // namespace glint
