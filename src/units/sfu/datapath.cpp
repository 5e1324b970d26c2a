#include "units/sfu/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "units/keys.h"
#include "units/n_register.h"

namespace glint {

std::uint32_t sfu_to_fp32(std::int64_t v, int frac) {
  if (v <= 0) return 0;
  const int lead = 63 - __builtin_clzll(static_cast<unsigned long long>(v));
  const std::uint32_t exp = static_cast<std::uint32_t>(127 + lead - frac);
  const std::uint32_t sig = static_cast<std::uint32_t>(v << (23 - lead));  // v < 2^24
  return exp << 23 | (sig & 0x7fffffu);
}

std::int64_t sfu_to_fixed(std::uint32_t x, const QFormat& out) {
  const int e = static_cast<int>(x >> 23 & 0xff);
  if (e == 0) return 0;  // zero (the SFU flushes denormals)
  const std::int64_t sig = 0x800000 | (x & 0x7fffff);
  // x = sig 2^(e - 150): the code is sig 2^(e - 150 + G), shifted right by s.
  const int s = 150 - e - out.frac_bits;
  std::int64_t raw;
  if (s <= 0)
    raw = sig << -s;  // x <= 1 keeps this under 2^(G + 1)
  else if (s > 30)
    raw = 0;  // sig < 2^24: below a quarter of the output's ulp
  else
    raw = round_shift(sig, s, Quant::kRndConv);
  return std::min(raw, out.raw_one());
}

SfuUnit::SfuUnit(const SfuConfig& cfg, const MaterialParams& m) : cfg_(cfg) {
  check_format(cfg.in);
  check_format(cfg.out);
  check_format(cfg.n_format);
  if (cfg.in.frac_bits > kSfuMaxInFrac)
    // refusal: sfu.in
    throw std::invalid_argument(
        fmt::format("sfu: {}: t enters the SFU as an fp32, exact only up to {} fraction bits",
                    key_values({{"in", cfg.in.name()}}), kSfuMaxInFrac));
  if (cfg.n_format.width() > kSfuMaxNWidth)
    // refusal: sfu.n_width
    throw std::invalid_argument(fmt::format(
        "sfu: {}: n enters the FMUL as an fp32, exact only for a register of at most {} bits "
        "(this one is {})",
        key_values({{"n", cfg.n_format.name()}}), kSfuMaxNWidth, cfg.n_format.width()));
  if (!(m.shininess > 0) || m.shininess > cfg.n_format.max_value())
    // refusal: sfu.n
    throw std::invalid_argument(fmt::format(
        "sfu: {}: shininess {} outside the n register (at most {:.6g})",
        key_values({{"n", cfg.n_format.name()}}), m.shininess, cfg.n_format.max_value()));
  n_ = m.shininess;
  n_raw_ = quantize_n(n_, cfg.n_format);
  n_fp32_ = sfu_to_fp32(n_raw_, cfg.n_format.frac_bits);
  one_in_ = cfg.in.raw_one();
  double worst = 0;
  for (std::int64_t t = 1; t <= one_in_; ++t)
    worst = std::max(
        worst, std::fabs(static_cast<double>(eval(t)) - std::ldexp(model(t), cfg.out.frac_bits)));
  bound_ulps_ = worst;
}

double SfuUnit::shininess_q() const {
  return std::ldexp(static_cast<double>(n_raw_), -cfg_.n_format.frac_bits);
}

double SfuUnit::model(std::int64_t t_raw) const {
  if (t_raw <= 0) return 0;
  return std::pow(input_value(std::min(t_raw, one_in_), cfg_.in), shininess_q());
}

}  // namespace glint
