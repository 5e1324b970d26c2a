// The shared front stage of the Hast chain and the Horner pipeline: u = (t - tau) k, k = 1/(1 -
// tau), clamped to [0, 1]. A subtractor, one multiplier and a clamp; u lands in an unsigned 1.fh
// register.
//
// k is rounded UP so that (1 - tau_q) k_q >= 1: at t = 1, u reaches 1.0 and the clamp makes it
// exactly 1.0, which is what lets both units return exactly 1.0 at t = 1. The real-valued model
// (exact()) uses the same tau_q and k_q, so the only datapath error here is the rounding of u to fh
// fraction bits: at most 2^-(fh+1).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "fixed/fixed_point.h"

namespace glint {

class UScaler {
 public:
  UScaler() = default;
  // root_raw: tau_q in the input format (<= 0: u = t, k = 1; >= 1.0: u = 0 everywhere).
  // A refusal (registers over 62 bits) names `keys`, the spec keys that set the input format and
  // fh (key_values(), units/keys.h), and `root`, where the root comes from.
  UScaler(const QFormat& in, std::int64_t root_raw, int fh, const std::string& keys = "",
          const std::string& root = "");

  std::int64_t apply(std::int64_t t_raw) const {
    if (t_raw <= root_raw_) return 0;
    const std::int64_t t = t_raw > one_in_ ? one_in_ : t_raw;
    const std::int64_t u = round_shift((t - root_raw_) * k_raw_, k_shift_, Quant::kRnd);
    return u > one_h_ ? one_h_ : u;
  }
  long double exact(std::int64_t t_raw) const {
    if (t_raw <= root_raw_) return 0.0L;
    const std::int64_t t = t_raw > one_in_ ? one_in_ : t_raw;
    return std::min(1.0L,
                    std::ldexp(static_cast<long double>(t - root_raw_) * k_raw_, -(fi_ + fk_)));
  }

  std::int64_t root_raw() const { return root_raw_; }
  std::int64_t k_raw() const { return k_raw_; }
  int k_frac() const { return fk_; }
  int k_int_bits() const { return k_int_; }
  double k_value() const { return std::ldexp(static_cast<double>(k_raw_), -fk_); }
  int fh() const { return fh_; }

 private:
  std::int64_t root_raw_ = 0, one_in_ = 0, one_h_ = 0, k_raw_ = 0;
  int fi_ = 0, fh_ = 0, fk_ = 0, k_int_ = 0, k_shift_ = 0;
};

}  // namespace glint
