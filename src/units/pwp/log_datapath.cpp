#include "units/pwp/log_datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "units/keys.h"
#include "units/n_register.h"
#include "units/pwp/segment_fit.h"

namespace glint {
namespace {

int clog2_int(int x) {
  int b = 0;
  while ((1 << b) < x) ++b;
  return b;
}

// Integer bits (with the sign) of a register holding magnitudes up to `bound` at `frac` bits.
int signed_int_bits(std::int64_t bound, int frac) {
  int bits = 1;
  while (bits - 1 + frac < 62 && (std::int64_t{1} << (bits - 1 + frac)) <= bound) ++bits;
  return bits;
}

// The extra bits the monotone check may add before the build gives up (never needed so far).
constexpr int kMaxExtra = 6;

std::string spec_keys(const PwpLogSpec& s) {
  return key_values({{"domain", "log"},
                     {"in", s.in.name()},
                     {"out", s.out.name()},
                     {"n", s.n_format.name()},
                     {"segments", std::to_string(s.segments)},
                     {"degree", std::to_string(s.degree)}});
}

// f on [a, b] as quantized segments of a table: `count` segments, ends T_k = f(a_k) at `frac`
// bits (the caller's f has exact ends where the table needs them), minimax in between.
template <class F>
void fit_table(F f, double lo, double hi, std::size_t count, int degree, int frac,
               std::vector<std::int64_t>& q_out, std::vector<double>& fit_out, int& chords) {
  const std::size_t stride = static_cast<std::size_t>(degree) + 1;
  q_out.assign(count * stride, 0);
  fit_out.assign(count * stride, 0.0);
  const double h = (hi - lo) / static_cast<double>(count);
  const auto at = [&](std::size_t k) { return k >= count ? hi : lo + h * static_cast<double>(k); };
  std::vector<std::int64_t> ends(count + 1);
  for (std::size_t k = 0; k <= count; ++k) ends[k] = std::llround(std::ldexp(f(at(k)), frac));
  const std::function<double(double)> target = f;
  for (std::size_t k = 0; k < count; ++k) {
    std::int64_t* q = &q_out[k * stride];
    double* r = &fit_out[k * stride];
    const std::vector<double> fit = fit_segment_of(target, at(k), at(k + 1), degree);
    std::copy(fit.begin(), fit.end(), r);
    const auto place = [&] {
      std::int64_t rest = q[0] = ends[k];
      for (int j = 2; j <= degree; ++j) rest += q[j];
      q[1] = ends[k + 1] - rest;
    };
    for (int j = 2; j <= degree; ++j) q[j] = std::llround(std::ldexp(fit[j], frac));
    place();
    if (pwp_nondecreasing(q, degree)) continue;
    ++chords;
    for (int j = 2; j <= degree; ++j) q[j] = 0;
    place();
    std::fill(r, r + stride, 0.0);
    r[0] = f(at(k));
    r[1] = f(at(k + 1)) - r[0];
  }
}

// |acc| bound of Horner over a table: sum_j |c_j| plus one LSB a rounding.
int acc_bits(const std::vector<std::int64_t>& c, std::size_t stride, int frac, int d) {
  std::int64_t bound = 0;
  for (std::size_t k = 0; k + stride <= c.size(); k += stride) {
    std::int64_t s = 0;
    for (std::size_t j = 0; j < stride; ++j) s += std::abs(c[k + j]);
    bound = std::max(bound, s);
  }
  return signed_int_bits(bound + d, frac);
}

}  // namespace

PwpLogWidths pwp_log_widths(const PwpLogSpec& s) {
  const int fo = s.out.frac_bits;
  return {fo + 3 + s.n_format.int_bits + clog2_int(s.degree), fo + 3, fo + (s.degree >= 3 ? 3 : 2)};
}

PwpLogTables::PwpLogTables(const PwpLogSpec& sp) : spec(sp) {
  fi = sp.in.frac_bits;
  fo = sp.out.frac_bits;
  d = sp.degree;
  stride = static_cast<std::size_t>(d) + 1;
  ebits = clog2_int(fi + 1);
  // Before anything reads 2^fi codes (PwpUnit refuses the same input again, later).
  if (fi > kPwpLogMaxInFrac)
    // refusal: pwp.log_in
    throw std::invalid_argument(fmt::format(
        "pwp: {}: at most {} fraction bits (the build proves lg2 monotone on every mantissa "
        "code)",
        key_values({{"domain", "log"}, {"in", sp.in.name()}}), kPwpLogMaxInFrac));
  if (fo > kPwpLogMaxOutFrac)
    // refusal: pwp.log_out
    throw std::invalid_argument(fmt::format(
        "pwp: {}: at most {} output fraction bits with domain=log (the build proves ex2 "
        "monotone on every code of y's fraction, {} bits beyond the output's)",
        key_values({{"domain", "log"}, {"out", sp.out.name()}}), kPwpLogMaxOutFrac, 3));
  for (int x = 0;; ++x) {
    if (!set_widths(x))
      // refusal: pwp.log_width
      throw std::invalid_argument(fmt::format(
          "pwp: {}: a register of the log domain (lg2's {} fraction bits by its {}-bit offset, n "
          "times log2 t, or ex2's {} fraction bits by its {}-bit offset) would be wider than 62 "
          "bits (narrow out, in or n, or raise segments)",
          spec_keys(sp), fl, rl, fe, re));
    fit_tables();
    if (monotone()) break;
    if (x == kMaxExtra)
      // not from a spec: no spec has needed an extra bit (tests/units/test_pwp_log.cpp)
      throw std::invalid_argument(
          fmt::format("pwp: {}: lg2 or ex2 steps back between neighbouring codes", spec_keys(sp)));
  }
}

bool PwpLogTables::set_widths(int extra_bits) {
  extra = extra_bits;
  const PwpLogWidths w = pwp_log_widths(spec);
  fl = w.fl + extra;
  fy = w.fy;
  fe = w.fe + extra;
  sl = std::min(spec.segments, fi);
  rl = fi - sl;
  se = std::min(spec.segments, fy);
  re = fy - se;
  lg_half = rl > 0 ? std::int64_t{1} << (rl - 1) : 0;
  ex_half = re > 0 ? std::int64_t{1} << (re - 1) : 0;
  lg_mask = (std::int64_t{1} << rl) - 1;
  ex_mask = (std::int64_t{1} << re) - 1;
  // acc (|c| sum < 4 for lg2, < 8 for ex2) times x, and the n product (log2 t >= -fi).
  return fl + 3 + rl <= 62 && fe + 4 + re <= 62 && spec.n_format.width() + fl + ebits + 2 <= 62;
}

void PwpLogTables::fit_tables() {
  lg_chords = ex_chords = 0;
  fit_table([](double u) { return u >= 1.0 ? 1.0 : std::log2(1.0 + u); }, 0.0, 1.0, lg_segments(),
            d, fl, lg, lg_fit, lg_chords);
  fit_table([](double u) { return u >= 1.0 ? 2.0 : std::exp2(u); }, 0.0, 1.0, ex_segments(), d, fe,
            ex, ex_fit, ex_chords);
  lg_acc_int = acc_bits(lg, stride, fl, d);
  ex_acc_int = acc_bits(ex, stride, fe, d);
  ex_slope = 0;
  for (std::size_t k = 0; k < ex.size(); k += stride) {
    double s = 0;
    for (std::size_t j = 1; j < stride; ++j)
      s += static_cast<double>(j) * std::fabs(std::ldexp(static_cast<double>(ex[k + j]), -fe));
    ex_slope = std::max(ex_slope, s * static_cast<double>(ex_segments()));
  }
}

bool PwpLogTables::monotone() const {
  // Lg's datapath value (PwpLogPath::run) on every mantissa code.
  std::int64_t prev = 0;
  for (std::int64_t mf = 0; mf < (std::int64_t{1} << fi); ++mf) {
    const std::int64_t k = mf >> rl, x = mf & lg_mask;
    const std::int64_t* c = &lg[static_cast<std::size_t>(k) * stride];
    std::int64_t acc = c[d];
    for (int j = d - 1; j >= 1; --j) acc = ((acc * x + lg_half) >> rl) + c[j];
    const std::int64_t v = (acc * x + c[0] * (std::int64_t{1} << rl) + lg_half) >> rl;
    if (v < prev) return false;
    prev = v;
  }
  if (prev > (std::int64_t{1} << fl)) return false;
  // Ex's exact last-stage value on every code of yf.
  const std::int64_t one = std::int64_t{1} << (fe + re);
  prev = one;
  for (std::int64_t yf = 0; yf < (std::int64_t{1} << fy); ++yf) {
    const std::int64_t k = yf >> re, x = yf & ex_mask;
    const std::int64_t* c = &ex[static_cast<std::size_t>(k) * stride];
    std::int64_t acc = c[d];
    for (int j = d - 1; j >= 1; --j) acc = ((acc * x + ex_half) >> re) + c[j];
    const std::int64_t v = acc * x + c[0] * (std::int64_t{1} << re);
    if (v < prev || (yf == 0 && v != one)) return false;
    prev = v;
  }
  return prev <= 2 * one;
}

PwpLogPath::PwpLogPath(std::shared_ptr<const PwpLogTables> tables, const MaterialParams& m)
    : t_(std::move(tables)) {
  const PwpLogTables& T = *t_;
  const QFormat& nf = T.spec.n_format;
  if (!(m.shininess > 0) || m.shininess > nf.max_value())
    // refusal: pwp.log_n
    throw std::invalid_argument(fmt::format(
        "pwp: {}: shininess {} outside the n register (at most {:.6g})",
        key_values({{"domain", "log"}, {"n", nf.name()}}), m.shininess, nf.max_value()));
  n_ = m.shininess;
  n_raw_ = quantize_n(n_, nf);
  one_in_ = T.spec.in.raw_one();
  one_out_ = T.spec.out.raw_one();
  y_shift_ = nf.frac_bits + T.fl - T.fy;
  y_half_ = y_shift_ > 0 ? std::int64_t{1} << (y_shift_ - 1) : 0;
  const double dl = T.d * std::ldexp(1.0, -(T.fl + 1));
  const double dy = shininess_q() * dl + std::ldexp(1.0, -(T.fy + 1));
  bound_ulps_ = 0.5 + (T.d - 1) * std::ldexp(1.0, -(T.fe + 1 - T.fo)) +
                0.5 * T.ex_slope * std::ldexp(dy, T.fo);
}

double PwpLogPath::shininess_q() const {
  return input_value(n_raw_, t_->spec.n_format);
}

namespace {

// Horner on one segment's coefficients (quantized: scaled by 2^-frac) at x, in long double.
template <class C>
long double poly(const C* c, std::size_t stride, long double x, long double scale) {
  long double p = 0;
  for (std::size_t j = stride; j-- > 0;) p = p * x + static_cast<long double>(c[j]);
  return p * scale;
}

// G(y) = Ex(frac y) 2^floor(y), clamped to [0, 1]; `ex` the segments in the real unit.
template <class C>
double ex_of(long double y, const C* ex, std::size_t segments, std::size_t stride,
             long double scale) {
  if (y >= 0) return 1.0;
  const long double yi = std::floor(y), yf = y - yi;
  const long double pos = yf * static_cast<long double>(segments);
  const std::size_t k = std::min(static_cast<std::size_t>(pos), segments - 1);
  const long double v = poly(&ex[k * stride], stride, pos - static_cast<long double>(k), scale);
  return static_cast<double>(std::clamp(std::ldexp(v, static_cast<int>(yi)), 0.0L, 1.0L));
}

}  // namespace

double PwpLogPath::model(std::int64_t t_raw) const {
  const PwpLogTables& T = *t_;
  if (t_raw <= 0) return 0.0;
  if (t_raw >= one_in_) return 1.0;
  const int e = 63 - __builtin_clzll(static_cast<unsigned long long>(t_raw));
  const std::int64_t big_e = T.fi - e;
  const std::int64_t mf = (t_raw << big_e) - one_in_;
  const std::size_t k = static_cast<std::size_t>(mf >> T.rl);
  const long double x = std::ldexp(static_cast<long double>(mf & T.lg_mask), -T.rl);
  const long double lg = poly(&T.lg[k * T.stride], T.stride, x, std::ldexp(1.0L, -T.fl));
  const long double y =
      static_cast<long double>(shininess_q()) * (lg - static_cast<long double>(big_e));
  return ex_of(y, T.ex.data(), T.ex_segments(), T.stride, std::ldexp(1.0L, -T.fe));
}

double PwpLogPath::float_model(double t) const {
  const PwpLogTables& T = *t_;
  if (t <= 0) return 0.0;
  if (t >= 1) return 1.0;
  int ex = 0;
  const double m = std::frexp(t, &ex);  // t = m 2^ex, m in [0.5, 1)
  const double u = 2 * m - 1;
  const double pos = u * static_cast<double>(T.lg_segments());
  const std::size_t k = std::min(static_cast<std::size_t>(pos), T.lg_segments() - 1);
  const long double lg = poly(&T.lg_fit[k * T.stride], T.stride,
                              static_cast<long double>(pos - static_cast<double>(k)), 1.0L);
  const long double y = static_cast<long double>(n_) * (lg + (ex - 1));
  return ex_of(y, T.ex_fit.data(), T.ex_segments(), T.stride, 1.0L);
}

}  // namespace glint
