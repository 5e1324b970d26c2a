#include "units/lut/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "units/keys.h"

namespace glint {
namespace {

// |t^n - chord| at its extreme on the segment [a, a + h]: t^n is convex (n >= 1) or concave
// (n < 1), so the extreme is where n t^(n-1) equals the chord slope.
double segment_chord_error(double a, double h, double n) {
  const double b = a + h;
  const double fa = std::pow(a, n), s = (std::pow(b, n) - fa) / h;
  double x = n == 1.0 ? a : std::pow(s / n, 1.0 / (n - 1.0));
  x = std::isfinite(x) ? std::clamp(x, a, b) : a;
  return std::fabs(fa + s * (x - a) - std::pow(x, n));
}

// The largest segment_chord_error over the segments [t0 + j h, t0 + (j + 1) h], j < count: the
// same value as evaluating every segment (a maximum does not depend on the order), but most
// segments are skipped because they provably cannot reach it.
//
// A segment's true chord error is at most h^2/8 max|f''| on it, and |f''| = n |n - 1| t^(n-2) is
// monotone: increasing for n > 2 (the last segment has the largest bound), decreasing for n < 2
// (the first). The segments are visited from that end, so each one's bound also bounds every
// segment still to come, and the walk stops once the bound is below the largest value found.
// The computed value may exceed the true error by its rounding: every term is in [0, 1] (t, t^n
// and s (x - a) <= t^n(b) - t^n(a)), so a few 2^-53 (pow within 1 ulp, four roundings);
// kRoundingMargin is 2^-40, hundreds of times that. The bound's own rounding is covered by
// scaling it by 1 + 2^-30.
double max_chord_error(double t0, double h, std::size_t count, double n) {
  // n = 1: every chord is t itself and each segment computes exactly 0 (pow(a, 1) = a, x = a).
  if (n == 1.0) return 0.0;
  constexpr double kRoundingMargin = 0x1p-40, kBoundScale = 1 + 0x1p-30;
  const bool rising = n > 2.0;  // |f''| increasing: visit the segments from the last
  const double scale = h * h / 8 * n * std::fabs(n - 1) * kBoundScale;
  double worst = 0;
  for (std::size_t step = 0; step < count; ++step) {
    const std::size_t j = rising ? count - 1 - step : step;
    const double a = t0 + h * static_cast<double>(j);
    const double bound = scale * std::pow(rising ? a + h : a, n - 2) + kRoundingMargin;
    if (bound < worst) break;  // this segment and every later one stay below worst
    worst = std::max(worst, segment_chord_error(a, h, n));
  }
  return worst;
}

}  // namespace

LutUnit::LutUnit(const LutConfig& cfg, const MaterialParams& m) : cfg_(cfg) {
  check_format(cfg.in);
  check_format(cfg.out);
  if (cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0 || cfg.in.frac_bits < 1)
    // not from a spec: read_common_keys refuses such formats
    throw std::invalid_argument("lut: input and output formats must represent 1.0");
  // not from a spec: the key reader takes bits in 1..16 only
  if (cfg.bits < 1 || cfg.bits > 16) throw std::invalid_argument("lut: bits must be in 1..16");
  const bool table_frac_given = cfg_.table_frac >= 0 && !cfg.table_frac_auto;
  if (cfg_.table_frac < 0) cfg_.table_frac = cfg.out.frac_bits + 2;
  const std::string table_frac = auto_value(table_frac_given, cfg_.table_frac);
  if (cfg_.table_frac < cfg.out.frac_bits || cfg_.table_frac > 40)
    // refusal: lut.table_frac
    throw std::invalid_argument(fmt::format(
        "lut: {}: table_frac must be in {}..40 (at least the output's fraction bits)",
        key_values({{"table_frac", table_frac}, {"out", cfg.out.name()}}), cfg.out.frac_bits));
  // not from a spec: every material's shininess (or a Gaussian lobe's equivalent n) is > 0
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
  if (2 * (cfg_.table_frac + 1) + r_bits_ > 62)
    // refusal: lut.interpolation
    throw std::invalid_argument(fmt::format(
        "lut: {}: {} input bits below the {}-bit table index interpolate entries of {} fraction "
        "bits: the product would be {} bits wide, more than 62 (lower table_frac, raise bits or "
        "narrow the input)",
        key_values({{"table_frac", table_frac},
                    {"bits", std::to_string(cfg.bits)},
                    {"in", cfg.in.name()}}),
        r_bits_, cfg.bits, cfg_.table_frac, 2 * (cfg_.table_frac + 1) + r_bits_));

  // Keep entries 0, 2^pad, ..., 2^bits (all of them when pad = 0), then the padding entry that
  // lets the interpolation read k + 1 at the last node (with a zero remainder).
  const std::size_t kept = (std::size_t{1} << (cfg.bits - pad_)) + 1;
  table_.resize(kept + 1);
  for (std::size_t k = 0; k < kept; ++k) {
    table_[k] = static_cast<std::uint32_t>(compute_entry(static_cast<std::int64_t>(k) << pad_));
  }
  table_[kept] = table_[kept - 1];

  const double t0 = std::ldexp(static_cast<double>(std::min(t0_raw_, one_in_)), -fi);
  const double h = (1.0 - t0) * std::ldexp(1.0, -cfg.bits);
  chord_ = h > 0 ? max_chord_error(t0, h, std::size_t{1} << cfg.bits, n_) : 0.0;
  bound_ = chord_ + std::ldexp(0.5, -cfg_.table_frac) + std::ldexp(0.5, -cfg.out.frac_bits);
}

std::int64_t LutUnit::compute_entry(std::int64_t j) const {
  const std::int64_t last = std::int64_t{1} << cfg_.bits;
  const double t0 = std::ldexp(static_cast<double>(std::min(t0_raw_, one_in_)), -cfg_.in.frac_bits);
  const double h = (1.0 - t0) * std::ldexp(1.0, -cfg_.bits);
  const double t = j >= last ? 1.0 : t0 + h * static_cast<double>(j);
  return std::llround(std::ldexp(std::pow(t, n_), cfg_.table_frac));
}

std::int64_t LutUnit::entry(std::int64_t j) const {
  const std::int64_t last = std::int64_t{1} << cfg_.bits;
  if (j >= last) return table_[table_.size() - 2];  // the last node (and its padding copy)
  if ((j & ((std::int64_t{1} << pad_) - 1)) == 0)
    return table_[static_cast<std::size_t>(j >> pad_)];
  return compute_entry(j);
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
  const std::int64_t v = t - t0_raw_;  // as eval: pad > 0 means a zero remainder
  const std::int64_t k = v >> r_bits_;
  const long double a = table_[k], b = table_[k + 1];
  const long double r = std::ldexp(static_cast<long double>(v & r_mask_), -r_bits_);
  return static_cast<double>(std::ldexp(a + (b - a) * r, -cfg_.table_frac));
}

double LutUnit::float_model(double t) const {
  return interp_exact(t);
}

}  // namespace glint
