#include "units/pwp/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "units/keys.h"
#include "units/pwp/segment_fit.h"

namespace glint {
namespace {

// Integer bits (with the sign) of a register holding magnitudes up to `bound` at `frac` bits.
int signed_int_bits(std::int64_t bound, int frac) {
  int bits = 1;
  while (bits - 1 + frac < 62 && (std::int64_t{1} << (bits - 1 + frac)) <= bound) ++bits;
  return bits;
}

// Steps of the blend towards the chord that repairs a segment whose quantized polynomial is not
// monotone (a power of two: the blend is a shift).
constexpr int kBlendShift = 4, kBlendSteps = 1 << kBlendShift;

}  // namespace

// P(x) = c0 + c1 x + c2 x^2 + c3 x^3 (integer coefficients, one scale) non-decreasing on [0, 1]:
// P' = c1 + 2 c2 x + 3 c3 x^2 >= 0 there. P' is at most quadratic: its minimum is at an end, or
// at the vertex x* = -c2 / (3 c3) when c3 > 0 and x* lies inside, where P'(x*) = c1 - c2^2 / (3
// c3).
bool pwp_nondecreasing(const std::int64_t* c, int degree) {
  const __int128 c1 = c[1], c2 = degree >= 2 ? c[2] : 0, c3 = degree >= 3 ? c[3] : 0;
  if (c1 < 0 || c1 + 2 * c2 + 3 * c3 < 0) return false;
  if (c3 > 0 && c2 < 0 && -c2 < 3 * c3) return 3 * c1 * c3 >= c2 * c2;
  return true;
}

int pwp_coef_frac(const PwpConfig& c) {
  return c.coef_frac >= 0 ? c.coef_frac : c.out.frac_bits + 2;
}

int pwp_min_guard(const PwpConfig& c) {
  int g = 0;
  while ((c.degree - 1) * std::ldexp(1.0, -(g + 1)) > 0.25) ++g;
  return std::max(g, pwp_coef_frac(c) - c.out.frac_bits);
}

PwpLogSpec pwp_log_spec(const PwpConfig& c) {
  return {c.in, c.out, c.n_format, c.segments, c.degree};
}

PwpUnit::PwpUnit(const PwpConfig& cfg, const MaterialParams& m,
                 std::shared_ptr<const PwpLogTables> log_tables)
    : cfg_(cfg) {
  check_format(cfg.in);
  check_format(cfg.out);
  if (cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0 || cfg.in.frac_bits < 1)
    // not from a spec: read_common_keys refuses such formats
    throw std::invalid_argument("pwp: input and output formats must represent 1.0");
  if (cfg.in.frac_bits > kPwpMaxInFrac)
    // refusal: pwp.in
    throw std::invalid_argument(fmt::format(
        "pwp: key 'in' = '{}': at most {} fraction bits (the build proves the output monotone on "
        "every input code)",
        cfg.in.name(), kPwpMaxInFrac));
  if (cfg.log_domain) {
    if (log_tables == nullptr) log_tables = std::make_shared<const PwpLogTables>(pwp_log_spec(cfg));
    log_.emplace(std::move(log_tables), m);
    return;
  }
  if (cfg.degree < 1 || cfg.degree > 3 || cfg.segments < 0 || cfg.segments > 10)
    // not from a spec: the key reader takes degree in 1..3 and segments in 0..10 only
    throw std::invalid_argument("pwp: degree must be in 1..3 and segments in 0..10");
  // not from a spec: every material's shininess (or a Gaussian lobe's equivalent n) is > 0
  if (!(m.shininess > 0)) throw std::invalid_argument("pwp: shininess must be > 0");
  cfg_.coef_frac = pwp_coef_frac(cfg);
  guard_given_ = cfg.guard >= 0 && !cfg.guard_auto;
  const int guard = cfg.guard >= 0 ? cfg.guard : pwp_min_guard(cfg_);
  const int cf = cfg_.coef_frac;
  if (cf > kPwpMaxCoefFrac)
    // refusal: pwp.coef_frac
    throw std::invalid_argument(fmt::format(
        "pwp: {}: at most {} coefficient fraction bits (the fits' coefficients, up to 2^7 in "
        "magnitude, then stay well inside 64-bit integers)",
        key_values({{"coef_frac", auto_value(!cfg.coef_frac_auto, cf)}, {"out", cfg.out.name()}}),
        kPwpMaxCoefFrac));
  n_ = m.shininess;
  const int fi = cfg.in.frac_bits;
  one_in_ = cfg.in.raw_one();
  one_out_ = cfg.out.raw_one();

  // Span as lut's: the largest s0 with 1 - 2^-s0 <= tau_q; always skipped: nothing reaches it.
  const std::int64_t tau_raw = cfg.skip ? tau_threshold_raw(m, cfg.in) : -1;
  s0_ = 0;
  if (tau_raw > 0) {
    while (s0_ < fi && one_in_ - (one_in_ >> (s0_ + 1)) <= tau_raw) ++s0_;
  }
  t0_raw_ = s0_ == 0 ? 0 : one_in_ - (one_in_ >> s0_);
  if (tau_raw >= one_in_) t0_raw_ = one_in_;
  const int v_bits = fi - s0_;
  sb_ = std::min(cfg.segments, v_bits);
  rb_ = v_bits - sb_;
  x_mask_ = (std::int64_t{1} << rb_) - 1;
  x_scale_ = std::ldexp(1.0L, -rb_);
  c_scale_ = std::ldexp(1.0L, -cf);

  // The segment ends' t^n at cf bits: T_k, k = 0..K, T_K = 1.0.
  const std::size_t count = segment_count();
  const double t0 = std::ldexp(static_cast<double>(std::min(t0_raw_, one_in_)), -fi);
  const double h = std::ldexp(1.0 - t0, -sb_);
  const auto end = [&](std::size_t k) {
    return k >= count ? 1.0 : t0 + h * static_cast<double>(k);
  };
  std::vector<std::int64_t> ends(count + 1);
  for (std::size_t k = 0; k <= count; ++k)
    ends[k] = std::llround(std::ldexp(std::pow(end(k), n_), cf));

  const int d = cfg.degree;
  stride_ = static_cast<std::size_t>(d) + 1;
  c_raw_.assign(count * stride_, 0);
  c_fit_.assign(count * stride_, 0.0);
  repair_.assign(count, 0);
  for (std::size_t k = 0; k < count; ++k) {
    std::int64_t* q = &c_raw_[k * stride_];
    double* f = &c_fit_[k * stride_];
    // The chord from T_k to T_{k+1}: monotone, because T is.
    std::vector<double> chord(stride_, 0.0);
    chord[0] = std::pow(end(k), n_);
    chord[1] = std::pow(end(k + 1), n_) - chord[0];
    // c_0 = T_k, c_j (j >= 2) as given, c_1 the rest of T_{k+1}.
    const auto place = [&] {
      std::int64_t rest = q[0] = ends[k];
      for (int j = 2; j <= d; ++j) rest += q[j];
      q[1] = ends[k + 1] - rest;
    };
    // One code a segment (rb = 0): x is always 0, the polynomial is its c_0.
    if (rb_ == 0 || t0_raw_ >= one_in_) {
      std::copy(chord.begin(), chord.end(), f);
      place();
      continue;
    }
    std::vector<double> fit = fit_segment(n_, end(k), end(k + 1), d);
    // A fit of a rise normalised to [0, 1] has coefficients of a few units; one that is not finite
    // or far beyond (Remez gone astray) is replaced by the chord.
    if (!std::all_of(fit.begin(), fit.end(),
                     [](double v) { return std::isfinite(v) && std::fabs(v) < 0x1p7; }))
      fit = chord;
    std::vector<std::int64_t> high(stride_, 0);
    for (int j = 2; j <= d; ++j) high[j] = std::llround(std::ldexp(fit[j], cf));
    // Not monotone once quantized: blended towards the chord, (1 - i/16) fit + (i/16) chord, at the
    // least i that is (i = 16: the chord). The error stays within the blend of the two.
    for (int i = 0; i <= kBlendSteps; ++i) {
      for (int j = 2; j <= d; ++j)
        q[j] = (high[j] * (kBlendSteps - i) + kBlendSteps / 2) >> kBlendShift;
      place();
      const double w = static_cast<double>(i) / kBlendSteps;
      for (std::size_t j = 0; j < stride_; ++j) f[j] = (1 - w) * fit[j] + w * chord[j];
      if (pwp_nondecreasing(q, d)) {
        blended_ += i > 0;
        chords_ += i == kBlendSteps;
        repair_[k] = i == kBlendSteps ? 2 : (i > 0 ? 1 : 0);
        break;
      }
    }
  }
  set_guard(guard);
}

double PwpUnit::segment_start(std::size_t k) const {
  const double t0 = std::ldexp(static_cast<double>(t0_raw_), -cfg_.in.frac_bits);
  return t0 + std::ldexp(1.0 - t0, -sb_) * static_cast<double>(k);
}

double PwpUnit::segment_end(std::size_t k) const {
  return k + 1 >= segment_count() ? 1.0 : segment_start(k + 1);
}

std::vector<double> PwpUnit::segment_fit(std::size_t k) const {
  const auto* f = &c_fit_[k * stride_];
  return {f, f + stride_};
}

void PwpUnit::replace_segment(std::size_t k, const std::vector<std::int64_t>& raw) {
  blended_ -= repair_[k] > 0;
  chords_ -= repair_[k] == 2;
  repair_[k] = 0;
  for (std::size_t j = 0; j < stride_; ++j) {
    c_raw_[k * stride_ + j] = raw[j];
    c_fit_[k * stride_ + j] = static_cast<double>(static_cast<long double>(raw[j]) * c_scale_);
  }
}

void PwpUnit::set_guard(int guard) {
  const int cf = cfg_.coef_frac, fo = cfg_.out.frac_bits;
  cfg_.guard = guard;
  fa_ = fo + guard;
  const auto keys = [&] {
    return key_values({{"in", cfg_.in.name()},
                       {"out", cfg_.out.name()},
                       {"segments", std::to_string(cfg_.segments)},
                       {"coef_frac", auto_value(!cfg_.coef_frac_auto, cf)},
                       {"guard", auto_value(guard_given_, guard)}});
  };
  if (fa_ < cf)
    // refusal: pwp.guard
    throw std::invalid_argument(fmt::format(
        "pwp: {}: the accumulator's {} fraction bits (the output's {} and {} guard bits) cannot "
        "add the coefficients' {} exactly (raise guard to at least {})",
        keys(), fa_, fo, guard, cf, cf - fo));
  align_ = fa_ - cf;
  // |acc| <= sum_j max |c_j| plus one LSB a rounding, over every segment.
  std::int64_t bound = 0;
  for (std::size_t k = 0; k < segment_count(); ++k) {
    std::int64_t s = 0;
    for (std::size_t j = 0; j < stride_; ++j) s += std::abs(c_raw_[k * stride_ + j]);
    bound = std::max(bound, s);
  }
  const bool fits = align_ + signed_int_bits(bound, cf) + cf < 62;
  acc_int_ = fits ? signed_int_bits((bound << align_) + cfg_.degree, fa_) : 62;
  if (!fits || acc_int_ + fa_ + rb_ > 62)
    // refusal: pwp.width
    throw std::invalid_argument(fmt::format(
        "pwp: {}: the product acc x ({} accumulator bits, {} fraction bits, times the {}-bit "
        "offset below the segment index) would be wider than 62 bits (lower guard, coef_frac or "
        "out, raise segments or narrow the input)",
        keys(), acc_int_ + fa_, fa_, rb_));
  c0_shift_ = align_ + rb_;
  out_shift_ = fa_ + rb_ - fo;
  half_x_ = rb_ > 0 ? std::int64_t{1} << (rb_ - 1) : 0;
  half_out_ = out_shift_ > 0 ? std::int64_t{1} << (out_shift_ - 1) : 0;
}

bool PwpUnit::output_monotone() const {
  if (log_) return true;  // proven for every n by the shared tables (log_datapath.h)
  std::int64_t prev = 0;
  for (std::int64_t t = t0_raw_ + 1; t <= one_in_; ++t) {
    const std::int64_t y = eval(t);
    if (y < prev) return false;
    prev = y;
  }
  return true;
}

double PwpUnit::datapath_bound_ulps() const {
  if (log_) return log_->datapath_bound_ulps();
  return 0.5 + (cfg_.degree - 1) * std::ldexp(1.0, -(cfg_.guard + 1));
}

double PwpUnit::model(std::int64_t t_raw) const {
  if (log_) return log_->model(t_raw);
  if (t_raw <= t0_raw_) return 0.0;
  if (t_raw >= one_in_) return 1.0;
  const std::int64_t v = t_raw - t0_raw_;
  const std::size_t k = static_cast<std::size_t>(v >> rb_);
  // In units of 2^-cf, scaled once: the integer coefficients and x are exact in long double.
  const long double x = static_cast<long double>(v & x_mask_) * x_scale_;
  long double p = 0;
  for (std::size_t j = stride_; j-- > 0;)
    p = p * x + static_cast<long double>(c_raw_[k * stride_ + j]);
  return static_cast<double>(std::clamp(p * c_scale_, 0.0L, 1.0L));
}

double PwpUnit::float_model(double t) const {
  if (log_) return log_->float_model(t);
  const double t0 = std::ldexp(static_cast<double>(t0_raw_), -cfg_.in.frac_bits);
  if (t <= t0 || t0 >= 1.0) return 0.0;
  if (t >= 1.0) return 1.0;
  const double pos = std::ldexp((t - t0) / (1.0 - t0), sb_);
  const double kf = std::min(std::floor(pos), static_cast<double>(segment_count() - 1));
  const double x = pos - kf;
  const std::size_t k = static_cast<std::size_t>(kf);
  double p = 0;
  for (std::size_t j = stride_; j-- > 0;) p = p * x + c_fit_[k * stride_ + j];
  return std::clamp(p, 0.0, 1.0);
}

}  // namespace glint
