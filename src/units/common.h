// What every specular datapath unit shares: the per-material constants it is built for, the input
// front end that turns a float t into the unit's input format, and the tau comparator.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "fixed/fixed_point.h"

namespace glint {

// One "slot" of a unit: a material, or a light x material pair when lights are coloured. Plain data
// derived from the vector header (or later a scene); the unit quantizes what it needs.
struct MaterialParams {
  MaterialParams() = default;
  MaterialParams(double n, double threshold, bool skip_always = false)
      : shininess(n), tau(threshold), always_skip(skip_always) {}

  double shininess = 1.0;    // exponent n (gaussian lobes: equivalent 2/omega^2)
  double tau = 0.0;          // skip threshold, Källberg eq.5 (or eq.9); may be < 0
  bool always_skip = false;  // c_y <= eps: the lobe is never perceptible
  // eps_K / c_y: the largest scalar lobe value the eye cannot see (Källberg eq.4 solved for the
  // lobe). Each unit's comparator skips only where its own output is at most this level
  // (unit_threshold_raw). < 0: not given, tau^n stands in (the float lobe at tau, the same level
  // for power lobes).
  double level = -1.0;
  std::string name;  // how errors name the slot: "material 'm'" or "light 2 x material 'm'"
};

// Default formats: 16-bit input and output, enough for 8-bit display output with guard bits.
inline constexpr QFormat kDefaultIn = uq(1, 15);
inline constexpr QFormat kDefaultOut = uq(1, 15);

// 2^e for -1022 <= e <= 1023, built from its bits: exact, and cheaper than ldexp in hot loops.
inline double pow2(int e) {
  const std::uint64_t bits = static_cast<std::uint64_t>(e + 1023) << 52;
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

// t <= 0 ? 0 : (t >= 1 ? 1 : t), NaN kept, except that -0 stays -0 (which every caller rounds
// to the code of 0). With SSE2 it is maxsd and minsd: GCC made the plain form, and std::max and
// std::min too, a branch on t <= 0, which a stream of t either side of 0 takes at random.
inline double clamp01(double t) {
#if defined(__SSE2__)
  // maxsd/minsd give their second operand when either is NaN, and 0 > t, 1 < t in this order.
  const __m128d c = _mm_min_sd(_mm_set_sd(1.0), _mm_max_sd(_mm_setzero_pd(), _mm_set_sd(t)));
  return _mm_cvtsd_f64(c);
#else
  return t <= 0.0 ? 0.0 : (t >= 1.0 ? 1.0 : t);
#endif
}

// Front end: t = r.v or n.h arrives as a float in [-1, 1 + 1e-3]. The unit computes max(0, t)^n, so
// negative t is clamped to 0 (Källberg eq.1), and t > 1 (normalisation noise of unit vectors) to
// 1. The clamped value is rounded to nearest-even into the input format.
class InputQuantizer {
 public:
  explicit InputQuantizer(const QFormat& in)
      : in_(in),
        exact_(in.frac_bits >= 0 && in.frac_bits <= 52 && in.raw_one() != 0),
        scale_(exact_ ? pow2(in.frac_bits) : 0.0) {}

  std::int64_t operator()(double t) const {
    if (exact_) {
      const double c = clamp01(t);
      // c * 2^F is exact and at most 2^52, and 1.0 is representable so nothing saturates.
      // Adding and taking away 2^52 rounds it to an integer, half to even (the sum lies in
      // [2^52, 2^53], where doubles are the integers), in the default rounding mode, which is
      // exactly kRndConv: what std::nearbyint does, without its library call.
      const double x = c * scale_;
      return static_cast<std::int64_t>((x + 0x1.0p52) - 0x1.0p52);
    }
    return Fixed::from_double(clamp01(t), in_, Quant::kRndConv, Overflow::kSat).raw();
  }

 private:
  QFormat in_;
  bool exact_;
  double scale_;
};

// One t through a format's front end; loops over many rows keep an InputQuantizer instead (its
// format's checks and scale worked out once).
inline std::int64_t quantize_input(double t, const QFormat& in) {
  return InputQuantizer(in)(t);
}
inline double input_value(std::int64_t raw, const QFormat& in) {
  return std::ldexp(static_cast<double>(raw), -in.frac_bits);
}

// The float test's threshold in the input format, for a comparator that must never skip a real t
// that Källberg's t <= tau keeps. t is rounded to nearest, so every real t that lands on code T
// lies below (T + ½) 2^-F: the largest safe code is floor(tau 2^F - ½), not floor(tau 2^F) (that
// one would skip t up to half a step above tau). always_skip puts the threshold at the top of the
// format, which every input meets; tau < 0 (a Gaussian lobe visible at every angle) gives -1,
// which no input meets.
inline std::int64_t tau_threshold_raw(const MaterialParams& m, const QFormat& in) {
  if (m.always_skip) return in.raw_max();
  if (m.tau < 0.0) return -1;
  if (m.tau >= 1.0) return in.raw_one() - 1;  // t = 1 exactly is never skipped by t <= tau < 1
  const double scaled = std::ldexp(m.tau, in.frac_bits) - 0.5;
  return scaled < 0.0 ? -1 : static_cast<std::int64_t>(std::floor(scaled));
}

// The level below which a slot's lobe is imperceptible, as a raw code of the output format
// (floor: out <= limit means out * c_y <= eps).
inline std::int64_t imperceptible_raw(const MaterialParams& m, const QFormat& out) {
  const double level =
      m.level >= 0.0 ? m.level : (m.tau > 0.0 ? std::pow(std::min(m.tau, 1.0), m.shininess) : 0.0);
  return static_cast<std::int64_t>(std::floor(std::ldexp(std::min(level, 1.0), out.frac_bits)));
}

// A unit's own comparator threshold for one slot (Källberg §3: combining the skip with another
// formula "assumes a corresponding derivation of tau"): the largest input code T <=
// tau_threshold_raw(m) at which the unit's own output is still imperceptible, eval(T) <= level.
// The first bound keeps the skip set inside the float test's on real t; the second keeps a unit
// that overshoots t^n (Schlick) from being cut off by a visible step. The unit's output is
// monotone in t (tests prove it on every input), so a bisection finds T and every skipped input's
// output is at most eval(T). eval(0) = 0 for every unit, so T >= 0 whenever tau_threshold_raw is.
template <class Eval>
std::int64_t unit_threshold_raw(const MaterialParams& m, const QFormat& in, const QFormat& out,
                                const Eval& eval) {
  const std::int64_t top = tau_threshold_raw(m, in);
  if (m.always_skip || top < 0) return top;
  const std::int64_t limit = imperceptible_raw(m, out);
  if (eval(top) <= limit) return top;
  std::int64_t lo = -1, hi = top;  // eval(lo) <= limit (lo = -1: nothing), eval(hi) > limit
  while (hi - lo > 1) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    (eval(mid) <= limit ? lo : hi) = mid;
  }
  return lo;
}

// The root of the u scaler (Hast's tau, the origin of the Horner variable u): the comparator
// threshold clamped at 0, because max(0,t)^n has no lobe below t = 0 even when the material's
// threshold is "never skip" (-1).
inline std::int64_t root_threshold_raw(const MaterialParams& m, const QFormat& in) {
  // An always-skipped material has no threshold inside the lobe (c_y <= eps): its root is 0, so a
  // unit built without the comparator (skip=off) still computes the whole lobe and f(1) = 1.
  if (m.always_skip) return 0;
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
