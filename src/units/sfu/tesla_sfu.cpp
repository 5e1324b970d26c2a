#include "units/sfu/tesla_sfu.h"

namespace glint::tesla_sfu {
namespace {

constexpr std::uint32_t kOne = 1u << 23;  // the significand's hidden one
constexpr int kBias = 127;
constexpr std::uint32_t kNaN = 0x7fffffffu;  // the canonical NaN the SFU and FMUL return
constexpr std::uint32_t kNegInf = 0xff800000u, kPosInf = 0x7f800000u;
constexpr std::uint32_t kPreNaN = 0x40000000u, kPreInf = 0x40800000u;

std::uint32_t sign_of(std::uint32_t x) {
  return x >> 31;
}
int exp_field(std::uint32_t x) {
  return static_cast<int>(x >> 23 & 0xff);
}
std::uint32_t frac_field(std::uint32_t x) {
  return x & (kOne - 1);
}
bool is_nan(std::uint32_t x) {
  return exp_field(x) == 0xff && frac_field(x) != 0;
}
bool is_inf(std::uint32_t x) {
  return exp_field(x) == 0xff && frac_field(x) == 0;
}

// A finite fp32 as sign, biased exponent and significand with its hidden one; denormals flushed
// to zero (the Tesla datapaths flush them on input), keeping the exponent field's weight (1).
struct Unpacked {
  std::uint32_t sign;
  int exp;
  std::uint32_t sig;
};
Unpacked unpack(std::uint32_t x) {
  const int e = exp_field(x);
  if (e == 0) return {sign_of(x), 1, 0};
  return {sign_of(x), e, kOne | frac_field(x)};
}

// Packs sign, biased exponent and a significand already rounded to 24 bits (or exactly 2^24 after
// a rounding carry). Results below the normal range flush to zero, above it round to infinity.
std::uint32_t pack(std::uint32_t sign, int exp, std::uint32_t sig) {
  if (sig == 2 * kOne) {
    sig >>= 1;
    ++exp;
  }
  if (sig < kOne || exp <= 0) return sign << 31;
  if (exp >= 0xff) return sign << 31 | kPosInf;
  return sign << 31 | static_cast<std::uint32_t>(exp) << 23 | (sig - kOne);
}

// Shifts left until bit `lead` is the leading one (v has none above it), lowering *exp by each
// step (0 stays 0). One shift by the leading-zero count: lg2's sum can need 40 steps, and the sfu
// unit states its bound from every input code.
std::uint64_t normalise(std::uint64_t v, int lead, int* exp) {
  if (v == 0) return 0;
  const int steps = lead - (63 - __builtin_clzll(v));
  *exp -= steps;
  return v << steps;
}

// The SFU's squarer: r^2 / 2^19 from 17 partial-product rows, row i (r * 2^i) truncated to its
// bits of weight 2^18 and up before the sum, then the sum halved. Cheaper than a full 17 x 17
// multiplier, at most ~17 ulp of r^2's top bits low: the tables' C coefficients absorb the bias.
std::int64_t truncated_square(std::uint32_t r) {
  std::uint32_t sum = 0;
  for (int i = 0; i < kOffsetBits; ++i)
    if (r >> i & 1) sum += r >> (18 - i);
  return sum >> 1;
}

struct Segment {
  const Coefficients& k;
  std::int64_t r, r2;
};
// The segment of a 23-bit fraction: its top 6 bits pick the table entry, its low 17 are r.
Segment segment_of(const Table& table, std::uint32_t frac) {
  const std::uint32_t r = frac & ((1u << kOffsetBits) - 1);
  return {table[frac >> kOffsetBits & (kSegments - 1)], r, truncated_square(r)};
}

}  // namespace

std::uint32_t lg2(std::uint32_t x, const Table& table) {
  if (is_nan(x)) return kNaN;
  const Unpacked u = unpack(x);
  if (u.sig == 0) return kNegInf;
  if (u.sign) return kNaN;
  if (is_inf(x)) return x;
  // The logarithm of the significand in 36 fraction bits (A scaled by 2^12, C r^2 by 2, a
  // rounding constant, then two bits dropped); lg2(1) is exactly 0 (the one input the
  // polynomial would miss).
  std::int64_t fixed = 0;
  if (!(u.sig == kOne && u.exp == kBias)) {
    const Segment s = segment_of(table, u.sig);
    fixed = (std::int64_t{s.k.a} * 4096 + s.k.b * s.r + 2 * (s.k.c * s.r2) + 0x3345) / 4;
  }
  // The exponent is the integer part; a negative sum is complemented (one's complement: the
  // hardware's, one ulp below the negation) and its magnitude normalised into 43 bits.
  fixed += std::int64_t{u.exp - kBias} * (std::int64_t{1} << 36);
  std::uint32_t sign = 0;
  if (fixed < 0) {
    sign = 1;
    fixed = ~fixed;
  }
  int exp = kBias + 6;
  const std::uint64_t m = normalise(static_cast<std::uint64_t>(fixed), 42, &exp);
  return pack(sign, exp, static_cast<std::uint32_t>(m >> 19));  // truncated to 24 bits
}

std::uint32_t pre_ex2(std::uint32_t x) {
  const std::uint32_t sign = sign_of(x) << 31;
  if (is_nan(x)) return sign | kPreNaN;
  if (is_inf(x)) return sign | kPreInf;
  const Unpacked u = unpack(x);
  const int e = u.exp - kBias;  // the significand's 1.23 becomes 7.23 shifted by e
  if (e >= 7) return sign | kPreInf;
  if (e >= 0) return sign | u.sig << e;
  return sign | (-e >= 32 ? 0 : u.sig >> -e);  // truncated
}

std::uint32_t ex2(std::uint32_t p, const Table& table) {
  const std::uint32_t negative = sign_of(p);
  int integer = exp_field(p);  // bits 30..23: the 7-bit integer part, or a special code
  std::uint32_t frac = frac_field(p);
  if (integer & 0x80) {
    if (!(integer & 1)) return kNaN;
    return negative ? 0 : kPosInf;
  }
  // 2^-(i + f) = 2^-(i + 1) * 2^(1 - f), with 1 - f taken as the complement of f (one ulp low).
  if (negative) {
    integer = -integer - 1;
    if (frac != 0) {
      frac = ~frac;
    } else {
      ++integer;
    }
  }
  const Segment s = segment_of(table, frac);
  const std::int64_t sum = std::int64_t{s.k.a} * 8192 + s.k.b * s.r + s.k.c * s.r2 + 0x77e2;
  return pack(0, integer + kBias, static_cast<std::uint32_t>(sum >> 15));
}

std::uint32_t fmul(std::uint32_t a, std::uint32_t b) {
  const Unpacked x = unpack(a), y = unpack(b);
  if (is_nan(a) || is_nan(b)) return kNaN;
  const std::uint32_t sign = x.sign ^ y.sign;
  if (is_inf(a) || is_inf(b)) {
    if (x.sig == 0 || y.sig == 0) return kNaN;  // inf * 0
    return sign << 31 | kPosInf;
  }
  std::uint64_t product = std::uint64_t{x.sig} * y.sig;
  if (product == 0) return sign << 31;  // a signed zero
  int exp = x.exp + y.exp - kBias + 1;
  product = normalise(product, 47, &exp);
  // Round to nearest, ties to even, on the 24 bits kept.
  const std::uint64_t kept = product >> 24, rest = product & 0xffffff;
  const std::uint64_t half = 0x800000;
  const std::uint64_t rounded = kept + ((rest > half || (rest == half && (kept & 1))) ? 1 : 0);
  return pack(sign, exp, static_cast<std::uint32_t>(rounded));
}

Highlight highlight(std::uint32_t t, std::uint32_t n) {
  Highlight h;
  h.lg2 = lg2(t);
  h.product = fmul(h.lg2, n);
  h.pre = pre_ex2(h.product);
  h.ex2 = ex2(h.pre);
  return h;
}

}  // namespace glint::tesla_sfu
