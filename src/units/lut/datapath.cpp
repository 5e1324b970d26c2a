#include "units/lut/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace glint {

LutUnit::LutUnit(const LutConfig& cfg, const MaterialParams& m) : cfg_(cfg) {
  check_format(cfg.in);
  check_format(cfg.out);
  if (cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0 || cfg.in.frac_bits < 1)
    throw std::invalid_argument("lut: input and output formats must represent 1.0");
  if (cfg.bits < 1 || cfg.bits > 16) throw std::invalid_argument("lut: bits must be in 1..16");
  if (cfg_.table_frac < 0) cfg_.table_frac = cfg.out.frac_bits + 2;
  if (cfg_.table_frac < cfg.out.frac_bits || cfg_.table_frac > 40)
    throw std::invalid_argument("lut: table_frac must be in out.frac_bits..40");
  if (!(m.shininess > 0)) throw std::invalid_argument("lut: shininess must be > 0");
  n_ = m.shininess;
  const int fi = cfg.in.frac_bits;
  one_in_ = cfg.in.raw_one();
  one_out_ = cfg.out.raw_one();
  tau_raw_ = cfg.skip ? tau_threshold_raw(m, cfg.in) : -1;
  // Span: with skipping, the largest s with 1 - 2^-s <= tau_q (t <= tau_q never reaches the
  // table); never finer than the input LSB.
  s_ = 0;
  if (tau_raw_ > 0) {
    while (s_ < fi && one_in_ - (one_in_ >> (s_ + 1)) <= tau_raw_) ++s_;
  }
  t0_raw_ = s_ == 0 ? 0 : one_in_ - (one_in_ >> s_);
  if (tau_raw_ >= one_in_) t0_raw_ = one_in_;  // always skip: nothing reaches the table
  const int v_bits = fi - s_;                  // t - t0 < 2^v_bits
  r_bits_ = std::max(0, v_bits - cfg.bits);
  pad_ = std::max(0, cfg.bits - v_bits);
  r_mask_ = (std::int64_t{1} << r_bits_) - 1;
  out_shift_ = r_bits_ + cfg_.table_frac - cfg.out.frac_bits;
  if (2 * (cfg_.table_frac + 1) + r_bits_ > 62) throw std::invalid_argument("lut: too wide");

  const std::size_t entries = (std::size_t{1} << cfg.bits) + 1;
  const double t0 = std::ldexp(static_cast<double>(std::min(t0_raw_, one_in_)), -fi);
  const double h = (1.0 - t0) / static_cast<double>(entries - 1);
  table_.resize(entries + 1);
  for (std::size_t j = 0; j < entries; ++j) {
    const double t = j + 1 == entries ? 1.0 : t0 + h * static_cast<double>(j);
    table_[j] = std::llround(std::ldexp(std::pow(t, n_), cfg_.table_frac));
  }
  table_[entries] = table_[entries - 1];  // read with a zero remainder at t = 1

  // Chord error per segment: t^n is convex (n >= 1) or concave (n < 1), so the extreme of
  // t^n - chord is where n t^(n-1) equals the chord slope.
  chord_ = 0;
  for (std::size_t j = 0; j + 1 < entries && h > 0; ++j) {
    const double a = t0 + h * static_cast<double>(j), b = a + h;
    const double fa = std::pow(a, n_), s = (std::pow(b, n_) - fa) / h;
    double x = n_ == 1.0 ? a : std::pow(s / n_, 1.0 / (n_ - 1.0));
    x = std::isfinite(x) ? std::clamp(x, a, b) : a;
    chord_ = std::max(chord_, std::fabs(fa + s * (x - a) - std::pow(x, n_)));
  }
  bound_ = chord_ + std::ldexp(0.5, -cfg_.table_frac) + std::ldexp(0.5, -cfg.out.frac_bits);
}

double LutUnit::interp_exact(double t) const {
  const double t0 = std::ldexp(static_cast<double>(t0_raw_), -cfg_.in.frac_bits);
  if (t <= t0 || t0 >= 1.0) return 0.0;
  t = std::min(t, 1.0);
  const double pos = (t - t0) / (1.0 - t0) * std::ldexp(1.0, cfg_.bits);
  const double j = std::min(std::floor(pos), std::ldexp(1.0, cfg_.bits) - 1);
  const double h = (1.0 - t0) * std::ldexp(1.0, -cfg_.bits);
  const double a = std::pow(t0 + j * h, n_), b = std::pow(t0 + (j + 1) * h, n_);
  return a + (b - a) * (pos - j);
}

double LutUnit::model(std::int64_t t_raw) const {
  if (t_raw <= t0_raw_) return 0.0;
  const std::int64_t t = t_raw > one_in_ ? one_in_ : t_raw;
  const std::int64_t v = (t - t0_raw_) << pad_;
  const std::int64_t i = v >> r_bits_;
  const long double a = table_[i], b = table_[i + 1];
  const long double r = std::ldexp(static_cast<long double>(v & r_mask_), -r_bits_);
  return static_cast<double>(std::ldexp(a + (b - a) * r, -cfg_.table_frac));
}

double LutUnit::float_model(double t) const {
  return interp_exact(t);
}

}  // namespace glint
