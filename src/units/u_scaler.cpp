#include "units/u_scaler.h"

#include <fmt/format.h>

#include <stdexcept>

namespace glint {

UScaler::UScaler(const QFormat& in, std::int64_t root_raw, int fh, const std::string& keys,
                 const std::string& root) {
  // (t - root) k needs Wi + k_int + fk bits, k_int >= 1: refuse what cannot fit before any shift
  // by those widths (a shift by 63 or more would be undefined, and k's width search endless).
  if (fh < 0 || in.width() + 1 + (fh + 2) > 62) {
    // refusal: u_scaler.width
    throw std::invalid_argument(fmt::format(
        "u scaler: {}: (t - root) k would be at least {} bits wide ({}-bit input, k with {} "
        "fraction bits), more than 62",
        keys.empty() ? "input " + in.name() : keys, in.width() + 1 + (fh + 2), in.width(), fh + 2));
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
    // refusal: u_scaler.k
    throw std::invalid_argument(fmt::format(
        "u scaler: {}{}: k = 1/(1 - root) for root {:.9g} needs {} integer bits, so (t - root) k "
        "would be {} bits wide, more than 62 (a narrower input or output, or a lower root)",
        keys.empty() ? "input " + in.name() : keys, root.empty() ? "" : ", " + root,
        std::ldexp(static_cast<double>(root_raw_), -in.frac_bits), k_int_,
        in.width() + k_int_ + fk_));
  }
}

}  // namespace glint
