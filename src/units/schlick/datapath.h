// Schlick's rational approximation S(t) = t / (n - n t + t) with a real divider.
//
// Datapath: D = n (1 - t) + t is formed exactly (one multiplier, one adder, no rounding), then one
// integer division Q = T 2^(Fn + Fo) / D, rounded to nearest. Hardware: a restoring or
// non-restoring divider producing Fo + 2 quotient bits (the last one decides the rounding).
//
// Error budget (against the real-valued S at the quantized t and n): the numerator and denominator
// are exact and the quotient is correctly rounded, so the whole budget is the final ½ ulp. The
// float model error S(t) - t^n is Schlick's own and is reported separately.
#pragma once

#include <cstdint>

#include "units/common.h"

namespace glint {

struct SchlickConfig {
  QFormat in = kDefaultIn;
  QFormat out = kDefaultOut;
  QFormat n_format = uq(14, 4);  // shininess register: n <= 16383.9375 in steps of 1/16
  bool skip = true;
};

class SchlickUnit {
 public:
  SchlickUnit(const SchlickConfig& cfg, const MaterialParams& m);

  // Bit-accurate result for an input already in cfg.in (any raw; > 1.0 is clamped to 1.0).
  std::int64_t eval(std::int64_t t_raw) const {
    const std::int64_t t = t_raw > one_in_ ? one_in_ : (t_raw < 0 ? 0 : t_raw);
    if (t == 0) return 0;
    // D and the numerator are exact integers well below 2^53 (checked in the constructor), so a
    // double quotient is within one of the true floor; the remainder fixes it exactly.
    const std::int64_t den = n_raw_ * (one_in_ - t) + (t << n_frac_);
    const std::int64_t num = t << num_shift_;
    std::int64_t q = static_cast<std::int64_t>(static_cast<double>(num) / static_cast<double>(den));
    std::int64_t r = num - q * den;
    if (r < 0) {
      --q;
      r += den;
    } else if (r >= den) {
      ++q;
      r -= den;
    }
    q += (2 * r >= den) ? 1 : 0;  // round to nearest, ties up
    return q > out_max_ ? out_max_ : q;
  }
  // Real-valued model at the quantized input and shininess.
  double model(std::int64_t t_raw) const;
  // Float approximation at the exact t and shininess (for the model error).
  double float_model(double t) const;

  std::int64_t tau_raw() const { return tau_raw_; }
  double shininess_q() const;
  std::int64_t n_raw() const { return n_raw_; }
  const SchlickConfig& config() const { return cfg_; }

 private:
  SchlickConfig cfg_;
  double n_ = 1.0;
  std::int64_t n_raw_ = 0, one_in_ = 0, out_max_ = 0, tau_raw_ = -1;
  int n_frac_ = 0, num_shift_ = 0;
};

}  // namespace glint
