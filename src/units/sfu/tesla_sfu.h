// The special-function unit (SFU) of NVIDIA's Tesla-class GPUs (G80 to GT200, 2006-2010), as a
// shader uses it for a specular highlight: t^n = ex2(n * lg2 t), i.e. MUFU.LG2, an FMUL by n,
// RRO.EX2 (the range reduction into fixed point) and MUFU.EX2. Every function is bit-exact on fp32
// bit patterns, written for glint from the behaviour envytools reverse-engineered and checked
// against hardware (nvhw/sfu.c, nvhw/fp.c); tests/units/test_tesla_sfu.cpp holds it to reference
// vectors generated from that model (tests/units/data/README.md says how).
//
// The design (Oberman & Siu, "A high-performance area-efficient multifunction interpolator",
// ARITH-17, 2005): the top 6 bits of the significand (lg2) or of the fraction (ex2) pick one of 64
// segments, the remaining 17 bits r enter A + B r + C r^2 with a truncated squarer for r^2 (17
// partial-product rows, each truncated to its top bits) and one rounding constant per function.
// Where glint needs more than a float function, this is the datapath: its quirks (lg2 of 2^-15 is
// -14.999999, negative logarithms are one's complements, results are truncated, denormals are
// flushed to zero) are the hardware's and are kept.
#pragma once

#include <array>
#include <cstdint>

namespace glint::tesla_sfu {

inline constexpr int kSegments = 64;    // table entries per function: the top 6 bits
inline constexpr int kOffsetBits = 17;  // r, the segment's offset, and the squarer's width

struct Coefficients {
  std::int32_t a, b, c;  // A + B r + C r^2, scaled per function (tesla_sfu.cpp)
};
using Table = std::array<Coefficients, kSegments>;
extern const Table kEx2Table, kLg2Table;

// MUFU.LG2: log2 of an fp32. lg2(+-0 or a denormal) = -inf, lg2(negative) = NaN, lg2(inf) = inf.
// `table` is the hardware's unless a test gives another (to show every entry matters).
std::uint32_t lg2(std::uint32_t x, const Table& table = kLg2Table);
// RRO.EX2: an fp32 to the sign and a 7.23 fixed-point magnitude (bits 29..0); NaN becomes
// 0x40000000 and +-inf, or a magnitude of 128 or more, 0x40800000 (with the sign): the codes ex2
// reads as NaN and infinity.
std::uint32_t pre_ex2(std::uint32_t x);
// MUFU.EX2 of pre_ex2's output.
std::uint32_t ex2(std::uint32_t p, const Table& table = kEx2Table);
// FMUL: fp32 product rounded to nearest even, denormal inputs and results flushed to zero,
// NaN results the canonical 0x7fffffff.
std::uint32_t fmul(std::uint32_t a, std::uint32_t b);

// The shader's highlight, every intermediate kept (the stages a trace shows).
struct Highlight {
  std::uint32_t lg2 = 0, product = 0, pre = 0, ex2 = 0;
};
Highlight highlight(std::uint32_t t, std::uint32_t n);

}  // namespace glint::tesla_sfu
