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
  bool valid() const { return width() >= 1 && width() <= kMaxWidth; }

  // "uq1.15" / "sq2.14": u or s, then integer bits (sign included), then fraction bits.
  std::string name() const;
  friend constexpr bool operator==(const QFormat& a, const QFormat& b) {
    return a.int_bits == b.int_bits && a.frac_bits == b.frac_bits && a.is_signed == b.is_signed;
  }
  friend constexpr bool operator!=(const QFormat& a, const QFormat& b) { return !(a == b); }
};

constexpr QFormat uq(int int_bits, int frac_bits) { return QFormat{int_bits, frac_bits, false}; }
constexpr QFormat sq(int int_bits, int frac_bits) { return QFormat{int_bits, frac_bits, true}; }

// Parses "uq1.15", "sq2.14" (also "u1.15", "s2.14"). Throws std::invalid_argument.
QFormat parse_q_format(std::string_view text);
// Throws std::invalid_argument unless 1 <= width <= 62.
void check_format(const QFormat& f);

// ---- Raw-level kernels (the hot path of every datapath; inline and branch-light) -------------

__int128 round_shift128(__int128 raw, int shift, Quant q);

// Rounds raw (scaled by 2^-shift relative to the target) right by `shift` >= 0 bits.
inline std::int64_t round_shift(std::int64_t raw, int shift, Quant q) {
  if (shift <= 0) return raw;
  if (shift >= 63) return static_cast<std::int64_t>(round_shift128(raw, shift, q));
  const std::int64_t fl = raw >> shift;  // arithmetic shift = floor
  if (q == Quant::kTrn) return fl;
  const std::uint64_t mask = (std::uint64_t{1} << shift) - 1;
  const std::uint64_t rem = static_cast<std::uint64_t>(raw) & mask;
  const std::uint64_t half = std::uint64_t{1} << (shift - 1);
  if (q == Quant::kRnd) return fl + (rem >= half ? 1 : 0);
  return fl + ((rem > half || (rem == half && (fl & 1))) ? 1 : 0);
}


// Applies the overflow mode of `to` to an integer already at `to`'s scale.
inline std::int64_t fit_overflow(__int128 v, const QFormat& to, Overflow o) {
  const std::int64_t hi = to.raw_max(), lo = to.raw_min();
  if (v >= lo && v <= hi) return static_cast<std::int64_t>(v);
  if (o == Overflow::kSat) return v > hi ? hi : lo;
  const int w = to.width();
  const unsigned __int128 m = (static_cast<unsigned __int128>(1) << w) - 1;
  std::uint64_t u = static_cast<std::uint64_t>(static_cast<unsigned __int128>(v) & m);
  if (to.is_signed && (u >> (w - 1)) & 1) u |= ~static_cast<std::uint64_t>(m);  // sign-extend
  return static_cast<std::int64_t>(u);
}

// Requantizes raw (with `from_frac` fraction bits) to `to`: rounding then overflow handling.
std::int64_t quantize_raw(__int128 raw, int from_frac, const QFormat& to, Quant q, Overflow o);

// ---- The value type --------------------------------------------------------------------------

class Fixed {
 public:
  Fixed() = default;
  // Raw constructor: raw must already lie in fmt's range (checked; throws std::out_of_range).
  Fixed(std::int64_t raw, const QFormat& fmt);

  // Documented conversion from double: x is scaled by 2^frac_bits exactly (ldexp), then rounded
  // by q and fitted by o exactly as SystemC assigns a double to sc_fixed. NaN throws
  // std::invalid_argument; +-Inf saturate under kSat and throw under kWrap.
  static Fixed from_double(double x, const QFormat& fmt, Quant q = Quant::kRndConv,
                           Overflow o = Overflow::kSat);
  static Fixed from_raw(std::int64_t raw, const QFormat& fmt) { return Fixed(raw, fmt); }

  std::int64_t raw() const { return raw_; }
  const QFormat& format() const { return fmt_; }
  // Exact for width <= 53 (the double mantissa); wider values round to nearest even.
  double to_double() const;
  std::string to_string() const;

 private:
  std::int64_t raw_ = 0;
  QFormat fmt_{};
};

// Full-precision result formats (the smallest formats that hold every exact result).
QFormat add_format(const QFormat& a, const QFormat& b);
QFormat sub_format(const QFormat& a, const QFormat& b);
QFormat mul_format(const QFormat& a, const QFormat& b);

// Exact arithmetic. Throws std::overflow_error if the exact result format exceeds 62 bits; use
// mul_quantize for wide products.
Fixed add(const Fixed& a, const Fixed& b);
Fixed sub(const Fixed& a, const Fixed& b);
Fixed mul(const Fixed& a, const Fixed& b);

// Rounding and overflow handling to a target format: the only place precision is lost.
Fixed quantize(const Fixed& v, const QFormat& to, Quant q, Overflow o);
// Exact product formed in 128 bits, then quantized; valid for any pair of <= 62-bit operands.
Fixed mul_quantize(const Fixed& a, const Fixed& b, const QFormat& to, Quant q, Overflow o);

// Exact comparison of values in any two formats: -1, 0 or +1.
int compare(const Fixed& a, const Fixed& b);
inline bool operator==(const Fixed& a, const Fixed& b) { return compare(a, b) == 0; }
inline bool operator!=(const Fixed& a, const Fixed& b) { return compare(a, b) != 0; }
inline bool operator<(const Fixed& a, const Fixed& b) { return compare(a, b) < 0; }
inline bool operator<=(const Fixed& a, const Fixed& b) { return compare(a, b) <= 0; }
inline bool operator>(const Fixed& a, const Fixed& b) { return compare(a, b) > 0; }
inline bool operator>=(const Fixed& a, const Fixed& b) { return compare(a, b) >= 0; }

}  // namespace glint
