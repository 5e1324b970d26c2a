#include "units/u_scaler.h"

#include <fmt/format.h>

#include <stdexcept>

namespace glint {

UScaler::UScaler(const QFormat& in, std::int64_t root_raw, int fh) {
  // (t - root) k needs Wi + k_int + fk bits, k_int >= 1: refuse what cannot fit before any shift
  // by those widths (a shift by 63 or more would be undefined, and k's width search endless).
  if (fh < 0 || in.width() + 1 + (fh + 2) > 62) {
    throw std::invalid_argument(fmt::format(
        "u scaler: input {} with {} fraction bits of u: registers exceed 62 bits", in.name(), fh));
  }
  fi_ = in.frac_bits;
  fh_ = fh;
  one_in_ = in.raw_one();
  one_h_ = std::int64_t{1} << fh;
  root_raw_ = std::clamp<std::int64_t>(root_raw, 0, one_in_);
  // k carries two bits beyond the u register so that its rounding stays below u's own.
  fk_ = fh + 2;
  const std::int64_t span = one_in_ - root_raw_;
  if (span > 0) {
    const __int128 num = static_cast<__int128>(1) << (fk_ + fi_);
    k_raw_ = static_cast<std::int64_t>((num + span - 1) / span);
  }
  k_int_ = 1;
  while ((std::int64_t{1} << (k_int_ + fk_)) <= k_raw_) ++k_int_;
  k_shift_ = fi_ + fk_ - fh;
  if (in.width() + k_int_ + fk_ > 62) {
    throw std::invalid_argument(fmt::format(
        "u scaler: k = 1/(1 - tau) needs {} integer bits; registers exceed 62 bits", k_int_));
  }
}

}  // namespace glint
