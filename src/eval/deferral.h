// The deferral policy of the evaluation engine: which rows' float references may go uncomputed,
// and why the statistics still come out as if every one had been computed.
//
// Most requests of a real stream are skipped far below the highlight, and their reference (libm's
// pow) would be the engine's largest cost. A skipped row's result is 0, so its reference enters
// the statistics as its error: the total, skip and weighted maxima, the sum of squares and the
// display mismatch count. The policy leaves a reference uncomputed (kDeferredReference) when it is
// at most a bound 2^e and taking it for 0 can change none of them.
//
// Why that is exact (a row "settled" is one whose reference, at most 2^e, is taken for 0):
// - Maxima keep the first row that reached the largest value (strict >). A settled row only
//   enters maxima that already hold a larger value from an earlier row of the same run
//   (SettledRows::scalars, weighted): with its true reference it would not move them either, and
//   the merged maximum is at least the run's.
// - The sum of squares is a sequential fold. A square x^2 leaves a sum S as it is when below half
//   an ulp of S, 2^(ilogb(S) - 53) (round to nearest); x <= 2^e does for 2e <= ilogb(S) - 54
//   (exponent_absorbed_by). Squares are non-negative and round to nearest is monotone, so the sum
//   only grows and a bound absorbed at the start of a window stays absorbed to the stream's end.
//   At the least bound, 2^-40, a run's own error of at least 2^-13 (square 2^-26, whose half ulp
//   is 2^-80) absorbs it even before the lane's sum does.
// - The display code of a reference at most 2^e is 0, as the result's, while 2^e * display <
//   0.5: the cap of allowed_deferral_exponent.
// - The lane, not the shared pass, decides: a deferred reference of a row that is not settled is
//   computed by the lane (the same reference_value, the same bits), so one lane's weak bound
//   never costs another lane its exactness.
// tests/eval/test_engine.cpp holds each step to hand-checked values and the engine to the
// row-at-a-time path, which never defers.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace glint {

struct SlotMap;
class LaneAccumulator;

// The reference of a row the shared pass deferred (a lobe is never negative).
inline constexpr double kDeferredReference = -1.0;
// The least deferral bound, 2^kDeferredExponent, where every lane starts: a run's own rows settle
// it (SettledRows).
inline constexpr int kDeferredExponent = -40;
inline constexpr double kDeferredBound = 0x1.0p-40;

// Per slot, the largest t at or below which the slot's reference is surely at most 2^exponent
// (libm's pow within an ulp, a margin beside); 0 for lobes it does not bound (Gaussian ones).
std::vector<double> deferred_t(const SlotMap& slots, int exponent = kDeferredExponent);

// The largest e for which a square of at most (2^e)^2 leaves the sum of squares `sum_sq` as it is;
// INT_MIN while the sum is 0 or subnormal.
int exponent_absorbed_by(double sum_sq);

// The largest e a lane whose sum of squares is `sum_sq` allows from here on: absorbed by the sum,
// capped where a reference of 2^e could round to a display code above 0 (display_scale = 2^bits -
// 1), never below kDeferredExponent.
int allowed_deferral_exponent(double sum_sq, double display_scale);

// Within one run of one lane: whether a skipped row whose reference is at most the bound 2^e
// changes nothing, given the largest values of the run's earlier rows.
class SettledRows {
 public:
  // sum_absorbs: the lane's sum of squares before this window absorbs the bound's square.
  SettledRows(int exponent, bool sum_absorbs);
  double bound() const { return bound_; }
  // The total and skip maxima hold more than the bound, and the sum absorbs its square: the sum
  // before the window, or at the least bound the run's largest total error (kSumFloor).
  bool scalars(double total_max, double skip_max) const {
    const bool sum = sum_absorbs_ | (least_ & (total_max >= kSumFloor));
    return sum & (total_max > bound_) & (skip_max > bound_);
  }
  // The weighted maximum holds more than the bound times `weight`: the most a reference at the
  // bound can reach on the pixel (the encoding's slope times the slot's largest channel weight).
  bool weighted(double weighted_max, double weight) const { return weighted_max > bound_ * weight; }

  // An error whose square, 2^-26, has half an ulp (2^-80) above the least bound's square.
  static constexpr double kSumFloor = 0x1.0p-13;

 private:
  double bound_;
  bool sum_absorbs_, least_;
};

// The engine's side: between windows (no lane working), the least exponent every lane allows,
// given to every lane, and per slot the largest t the shared pass defers.
class SharedDeferral {
 public:
  void update(const std::vector<LaneAccumulator*>& lanes, std::size_t slots);
  // INT_MIN before the first update.
  int exponent() const { return exponent_; }
  // Per slot, the largest t whose reference the shared pass defers: the smallest of the lanes'
  // drop_t (every lane skips such rows, references at most the bound); 0 for none. A lane that
  // computed them would make each pow call in the middle of its rows, where the shared pass makes
  // them back to back.
  const std::vector<double>& defer_t() const { return defer_t_; }

 private:
  int exponent_ = std::numeric_limits<int>::min();
  std::vector<double> defer_t_;
};

}  // namespace glint
