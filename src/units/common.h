// What every specular datapath unit shares: the per-material constants it is built for, the input
// front end that turns a float t into the unit's input format, and the tau comparator.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "fixed/fixed_point.h"

namespace glint {

// One "slot" of a unit: a material, or a light x material pair when lights are coloured. Plain data
// derived from the vector header (or later a scene); the unit quantizes what it needs.
struct MaterialParams {
  double shininess = 1.0;    // exponent n (gaussian lobes: equivalent 2/omega^2)
  double tau = 0.0;          // skip threshold, Källberg eq.5 (or eq.9); may be < 0
  bool always_skip = false;  // c_y <= eps: the lobe is never perceptible
};

// Default formats: 16-bit input and output, enough for 8-bit display output with guard bits.
inline constexpr QFormat kDefaultIn = uq(1, 15);
inline constexpr QFormat kDefaultOut = uq(1, 15);

// Front end: t = r.v or n.h arrives as a float in [-1, 1 + 1e-3]. The unit computes max(0, t)^n, so
// negative t is clamped to 0 (Källberg eq.1), and t > 1 (normalisation noise of unit vectors) to
// 1. The clamped value is rounded to nearest-even into the input format.
// 2^e for -1022 <= e <= 1023, built from its bits: exact, and cheaper than ldexp in hot loops.
inline double pow2(int e) {
  const std::uint64_t bits = static_cast<std::uint64_t>(e + 1023) << 52;
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

inline std::int64_t quantize_input(double t, const QFormat& in) {
  const double c = t <= 0.0 ? 0.0 : (t >= 1.0 ? 1.0 : t);
  if (in.frac_bits >= 0 && in.frac_bits <= 52 && in.raw_one() != 0) {
    // c * 2^F is exact and below 2^53; nearbyint rounds half to even in the default rounding
    // mode, which is exactly kRndConv, and 1.0 is representable so nothing saturates.
    return static_cast<std::int64_t>(std::nearbyint(c * pow2(in.frac_bits)));
  }
  return Fixed::from_double(c, in, Quant::kRndConv, Overflow::kSat).raw();
}
inline double input_value(std::int64_t raw, const QFormat& in) {
  return std::ldexp(static_cast<double>(raw), -in.frac_bits);
}

// The comparator threshold for one slot, in the input format. tau is rounded DOWN (floor) so the
// fixed-point comparator never skips a t that the float test t <= tau would keep: its skip set is a
// subset of Källberg's. always_skip puts the threshold at the top of the format, which every input
// meets;
// tau < 0 (a Gaussian lobe visible at every angle) gives -1, which no input meets.
inline std::int64_t tau_threshold_raw(const MaterialParams& m, const QFormat& in) {
  if (m.always_skip || m.tau >= 1.0) return in.raw_max();
  if (m.tau < 0.0) return -1;
  return Fixed::from_double(m.tau, in, Quant::kTrn, Overflow::kSat).raw();
}

// The root of the u scaler (Hast's tau, the origin of the Horner variable u): the comparator
// threshold clamped at 0, because max(0,t)^n has no lobe below t = 0 even when the material's
// threshold is "never skip" (-1).
inline std::int64_t root_threshold_raw(const MaterialParams& m, const QFormat& in) {
  const std::int64_t raw = tau_threshold_raw(m, in);
  return raw < 0 ? 0 : raw;
}

// TauComparator datapath: skip the highlight when t <= tau (Källberg eq.5).
inline bool tau_skip(std::int64_t t_raw, std::int64_t tau_raw) {
  return t_raw <= tau_raw;
}

// Rounds a non-negative value right by `shift` bits to nearest, ties up (SC_RND). Every unit's
// final rounding uses it: the ½-ulp term of each error budget.
inline std::int64_t round_nearest(std::int64_t v, int shift) {
  return round_shift(v, shift, Quant::kRnd);
}

}  // namespace glint
