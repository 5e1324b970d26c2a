#include "units/horner/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit/monotone.h"
#include "units/keys.h"

namespace glint {

namespace {
int guard_for(double need) {
  int g = 1;
  while (std::ldexp(1.0, g) < need) ++g;
  return g;
}
double derivative_bound(const HornerCoefficients& coeffs) {
  return slope_bound(coeffs.c);  // bound on |P'| over [0, 1]
}
// Integer bits (with the sign) of a register holding values up to `magnitude`.
int signed_int_bits(double magnitude) {
  int bits = 1;
  while (std::ldexp(1.0, bits - 1) <= magnitude) ++bits;
  return bits;
}
}  // namespace

int horner_required_guard(const HornerCoefficients& coeffs) {
  const double p = static_cast<double>(coeffs.c.size() - 1);
  // u is rounded only on the tau domain; on the full domain u = t exactly.
  return guard_for(2.0 * (p - 1.0 + (coeffs.tau_domain ? derivative_bound(coeffs) : 0.0)));
}

int horner_preferred_guard(const HornerCoefficients& coeffs) {
  const double p = static_cast<double>(coeffs.c.size() - 1);
  return guard_for(2.0 * (p - 1.0 + derivative_bound(coeffs)));
}

int horner_max_guard(const HornerCoefficients& coeffs, const MaterialParams& m, const QFormat& in,
                     const QFormat& out) {
  double sum_abs = 0;
  for (double c : coeffs.c) sum_abs += std::fabs(c);
  // Accumulator: sum |c| plus one LSB per rounding, signed, fh fraction bits, <= 62 bits.
  int fh_max = 62 - signed_int_bits(sum_abs + 1);
  if (coeffs.tau_domain) {
    // u scaler (u_scaler.cpp): (t - root) k needs in + k_int + fh + 2 <= 62 bits, k ~ 2^F / span.
    const std::int64_t span = in.raw_one() - root_threshold_raw(m, in);
    // In 128 bits and at most 62 doublings: with a wide input (uq1.61) and a short span, the
    // 64-bit product overflowed, the loop never ended and the shift reached 64 (found by the
    // units fuzz harness's seeds: tests/fuzz/regressions/units/horner_wide_input_guard_hang).
    int k_int = 1;
    while (span > 0 && k_int < 62 &&
           (static_cast<__int128>(1) << (k_int + 1)) * span <=
               2 * static_cast<__int128>(in.raw_one()))
      ++k_int;
    fh_max = std::min(fh_max, 62 - in.width() - (k_int + 1) - 2);
  }
  return fh_max - out.frac_bits;
}

HornerUnit::HornerUnit(const HornerConfig& cfg, const MaterialParams& m,
                       const HornerCoefficients& coeffs)
    : cfg_(cfg), coeffs_(coeffs) {
  check_format(cfg.in);
  check_format(cfg.out);
  if (cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0 || cfg.in.frac_bits < 0)
    // not from a spec: read_common_keys refuses such formats
    throw std::invalid_argument("horner: input and output formats must represent 1.0");
  if (coeffs.c.size() < 2 || coeffs.c.size() > 17)
    // not from a spec: the key reader takes degree in 1..10 only
    throw std::invalid_argument("horner: degree must be in 1..16");
  const bool guard_given = cfg_.guard >= 0 && !cfg.guard_auto;
  if (cfg_.guard < 0) cfg_.guard = horner_required_guard(coeffs);
  fh_ = cfg.out.frac_bits + cfg_.guard;
  one_out_ = cfg.out.raw_one();
  last_shift_ = 2 * fh_ - cfg.out.frac_bits;

  const std::int64_t tau_q = root_threshold_raw(m, cfg.in);
  // Full domain: u = t (root 0, k = 1). The comparator still uses the material's tau.
  scaler_ = UScaler(cfg.in, coeffs.tau_domain ? tau_q : 0, fh_,
                    key_values({{"in", cfg.in.name()},
                                {"out", cfg.out.name()},
                                {"guard", auto_value(guard_given, cfg_.guard)}}),
                    "the root the material's threshold (domain=tau)");
  // The fit's domain [tau_q, 1] is the u scaler's: float_model's u is the hardware's variable.
  tau_ = coeffs.tau_domain ? input_value(scaler_.root_raw(), cfg.in) : 0.0;

  // Coefficients: nearest at fh fraction bits, then repair the fit's constraints exactly.
  const std::size_t p = coeffs.c.size() - 1;
  c_raw_.resize(p + 1);
  double sum_abs = 0;
  for (std::size_t k = 0; k <= p; ++k) {
    // not from a spec: the fits of t^n on [0, 1] are finite
    if (!std::isfinite(coeffs.c[k])) throw std::invalid_argument("horner: non-finite coefficient");
    sum_abs += std::fabs(coeffs.c[k]);
  }
  if (signed_int_bits(sum_abs + static_cast<double>(p) + 1) + fh_ > 62)
    // refusal: horner.accumulator
    throw std::invalid_argument(fmt::format(
        "horner: {}: coefficients up to {:.6g} at {} fraction bits (the output's {} and {} guard "
        "bits) need an accumulator wider than 62 bits (a smaller guard, output or degree)",
        key_values({{"out", cfg.out.name()},
                    {"guard", auto_value(guard_given, cfg_.guard)},
                    {"degree", std::to_string(p)}}),
        sum_abs, fh_, cfg.out.frac_bits, cfg_.guard));
  for (std::size_t k = 0; k <= p; ++k) c_raw_[k] = std::llround(std::ldexp(coeffs.c[k], fh_));
  const std::int64_t one_h = std::int64_t{1} << fh_;
  if (coeffs.constrain_zero) c_raw_[0] = 0;
  if (coeffs.constrain_one) {
    // P(1) = sum c_k must be exactly 1.0: absorb the rounding residue in the lowest free term.
    const std::size_t free_k = coeffs.constrain_zero ? 1 : 0;
    std::int64_t rest = 0;
    for (std::size_t k = 0; k <= p; ++k)
      if (k != free_k) rest += c_raw_[k];
    c_raw_[free_k] = one_h - rest;
  }
  std::int64_t max_abs = 0, acc_bound = 0;
  for (auto c : c_raw_) {
    max_abs = std::max<std::int64_t>(max_abs, c < 0 ? -c : c);
    acc_bound += c < 0 ? -c : c;
  }
  int ci = 1;
  while ((std::int64_t{1} << (ci - 1 + fh_)) <= max_abs) ++ci;
  coeff_fmt_ = sq(ci, fh_);
  acc_int_ = 1;
  while ((std::int64_t{1} << (acc_int_ - 1 + fh_)) <= acc_bound + static_cast<std::int64_t>(p))
    ++acc_int_;
  // acc * u: acc_int + fh + (fh + 1) bits with the sign; int64 holds 63 of them.
  wide_ = acc_int_ + 2 * fh_ + 1 > 63;
  c_real_ = real_coefficients();
  half_ = fh_ > 0 ? std::int64_t{1} << (fh_ - 1) : 0;
  c0_high_ =
      shift_left(c_raw_[0], fh_) + (last_shift_ > 0 ? std::int64_t{1} << (last_shift_ - 1) : 0);
}

double HornerUnit::slope_bound() const {
  return glint::slope_bound(real_coefficients());
}

std::vector<long double> HornerUnit::real_coefficients() const {
  std::vector<long double> c(c_raw_.size());  // exact: |c_raw| < 2^62 fits a 64-bit mantissa
  for (std::size_t k = 0; k < c.size(); ++k)
    c[k] = std::ldexp(static_cast<long double>(c_raw_[k]), -fh_);
  return c;
}

double HornerUnit::datapath_bound_ulps() const {
  // p - 1 inner roundings scaled by u^k <= 1, u's rounding times |P'| <= slope_bound(), then the
  // final ½ ulp; the clamp is 1-Lipschitz. On the full domain u = t is exact only while the input
  // has no more fraction bits than u's register (fh): a wider input is rounded into it.
  double roundings = static_cast<double>(c_raw_.size()) - 2.0;
  if (coeffs_.tau_domain || cfg_.in.frac_bits > fh_) roundings += slope_bound();
  return 0.5 + roundings * std::ldexp(1.0, -(cfg_.guard + 1));
}

double HornerUnit::model(std::int64_t t_raw) const {
  const long double u = scaler_.exact(t_raw);
  long double acc = 0;
  for (std::size_t k = c_real_.size(); k-- > 0;) acc = acc * u + c_real_[k];
  return static_cast<double>(std::clamp(acc, 0.0L, 1.0L));
}

double HornerUnit::float_model(double t) const {
  t = std::clamp(t, 0.0, 1.0);
  double u = t;
  if (coeffs_.tau_domain) {
    if (t <= tau_) return 0.0;
    u = (t - tau_) / (1.0 - tau_);
  }
  double acc = 0;
  for (std::size_t k = coeffs_.c.size(); k-- > 0;) acc = acc * u + coeffs_.c[k];
  return std::clamp(acc, 0.0, 1.0);
}

}  // namespace glint
