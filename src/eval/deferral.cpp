#include "eval/deferral.h"

#include <algorithm>
#include <cmath>

#include "eval/evaluate.h"

namespace glint {

static_assert(kDeferredBound * kDeferredBound <
                  SettledRows::kSumFloor * SettledRows::kSumFloor * 0x1.0p-53,
              "the least bound's square is below half an ulp of kSumFloor's square");

std::vector<double> deferred_t(const SlotMap& slots, int exponent) {
  std::vector<double> cut(slots.params.size(), 0.0);
  for (std::size_t s = 0; s < cut.size(); ++s) {
    if (slots.lobe[s] == Lobe::kGaussian) continue;
    // t <= 2^((e-1)/n) gives t^n <= 2^(e-1), half the bound; the factor below the exact root
    // covers exp2's and the division's rounding many times over, and libm's pow is within an ulp.
    cut[s] = std::exp2((exponent - 1.0) / slots.params[s].shininess) * (1.0 - 1e-9);
  }
  return cut;
}

// S >= 2^E (E = ilogb(S)) has half an ulp of 2^(E-53); x <= 2^e squares below it for
// 2e <= E - 54.
int exponent_absorbed_by(double sum_sq) {
  if (!(sum_sq >= std::numeric_limits<double>::min())) return std::numeric_limits<int>::min();
  return static_cast<int>(std::floor((std::ilogb(sum_sq) - 54) / 2.0));
}

int allowed_deferral_exponent(double sum_sq, double display_scale) {
  // display_scale < 2^(k+1) for k = ilogb(display_scale), so 2^e display_scale < 0.25 for
  // e <= -k - 3: the reference's display code is 0.
  const int cap = -std::ilogb(display_scale) - 3;
  return std::max(kDeferredExponent, std::min(exponent_absorbed_by(sum_sq), cap));
}

SettledRows::SettledRows(int exponent, bool sum_absorbs)
    : bound_(std::ldexp(1.0, exponent)),
      sum_absorbs_(sum_absorbs),
      least_(exponent <= kDeferredExponent) {}

void SharedDeferral::update(const std::vector<LaneAccumulator*>& lanes, std::size_t slots) {
  if (lanes.empty()) return;
  int e = std::numeric_limits<int>::max();
  for (const LaneAccumulator* lane : lanes) e = std::min(e, lane->deferred_exponent());
  for (LaneAccumulator* lane : lanes) lane->set_deferred_exponent(e);
  if (e == exponent_) return;
  exponent_ = e;
  defer_t_.assign(slots, std::numeric_limits<double>::infinity());
  for (std::size_t s = 0; s < slots; ++s) {
    for (const LaneAccumulator* lane : lanes) defer_t_[s] = std::min(defer_t_[s], lane->drop_t(s));
    defer_t_[s] = std::max(defer_t_[s], 0.0);
  }
}

}  // namespace glint
