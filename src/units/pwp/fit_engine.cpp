#include "units/pwp/fit_engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "fit/sollya_fit.h"
#include "units/memo.h"

namespace glint {

PwpFitEngine parse_pwp_fit_engine(std::string_view text) {
  if (text == "best") return PwpFitEngine::kBest;
  if (text == "glint") return PwpFitEngine::kGlint;
  if (text == "sollya") return PwpFitEngine::kSollya;
  // not from a spec: the key reader accepts PwpKeys::kFits only
  throw std::invalid_argument(fmt::format("pwp: unknown fit engine '{}'", text));
}

namespace {

std::uint64_t bits_of(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

int magnitude_bits(std::int64_t v) {
  int bits = 0;
  for (std::uint64_t m = static_cast<std::uint64_t>(v < 0 ? -v : v); m != 0; m >>= 1) ++bits;
  return bits;
}

// The registers the glint fits built: each bank's widest magnitude and sign, and the accumulator's
// largest sum of magnitudes (datapath.cpp, set_guard), over every group.
struct Widths {
  std::vector<int> bank_bits;
  std::vector<bool> bank_signed;
  std::int64_t acc_bound = 0;

  bool hold(const std::vector<std::int64_t>& raw) const {
    std::int64_t sum = 0;
    for (std::size_t j = 0; j < raw.size(); ++j) {
      if (magnitude_bits(raw[j]) > bank_bits[j] || (raw[j] < 0 && !bank_signed[j])) return false;
      sum += raw[j] < 0 ? -raw[j] : raw[j];
    }
    return sum <= acc_bound;
  }
};

Widths widths_of(const std::vector<PwpUnit>& units, int degree) {
  Widths w;
  w.bank_bits.assign(static_cast<std::size_t>(degree) + 1, 0);
  w.bank_signed.assign(w.bank_bits.size(), false);
  for (const PwpUnit& u : units) {
    for (std::size_t k = 0; k < u.segment_count(); ++k) {
      std::int64_t sum = 0;
      for (int j = 0; j <= degree; ++j) {
        const std::int64_t c = u.coeff(k, j);
        auto& bits = w.bank_bits[static_cast<std::size_t>(j)];
        bits = std::max(bits, magnitude_bits(c));
        if (c < 0) w.bank_signed[static_cast<std::size_t>(j)] = true;
        sum += c < 0 ? -c : c;
      }
      w.acc_bound = std::max(w.acc_bound, sum);
    }
  }
  return w;
}

std::vector<std::int64_t> raw_of(const PwpUnit& u, std::size_t k) {
  std::vector<std::int64_t> raw;
  for (int j = 0; j <= u.config().degree; ++j) raw.push_back(u.coeff(k, j));
  return raw;
}

// t^n on one segment at x = i / points, i = 0..points, computed once: the errors of the
// polynomials compared there (errors of the coefficients as held exactly, in long double; of real
// coefficients in double).
class Samples {
 public:
  Samples(double n, double a, double b, int points) {
    for (int i = 0; i <= points; ++i) {
      x_.push_back(static_cast<double>(i) / points);
      f_.push_back(std::pow(a + (b - a) * x_.back(), n));
    }
  }
  double error(const std::vector<std::int64_t>& raw, int cf) const {
    const long double scale = std::ldexp(1.0L, -cf);
    long double worst = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      long double p = 0;
      for (std::size_t j = raw.size(); j-- > 0;) p = p * x_[i] + static_cast<long double>(raw[j]);
      worst = std::max(worst, std::fabs(p * scale - f_[i]));
    }
    return static_cast<double>(worst);
  }
  double error(const std::vector<double>& c) const {
    double worst = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      double p = 0;
      for (std::size_t j = c.size(); j-- > 0;) p = p * x_[i] + c[j];
      worst = std::max(worst, std::fabs(p - f_[i]));
    }
    return worst;
  }

 private:
  std::vector<double> x_, f_;
};

// How much lower the error of the grid's points next to glint's is, at best, on the samples: each
// free coefficient c_j (j >= 2) moved by at most one step, c_1 taking the rest so that the ends
// stay. The error is convex in the free coefficients (a maximum of absolute values of affine
// functions), so at degree 2 (one free coefficient) a walk that goes on while it improves finds
// the grid's best point (up to kWalk steps): no gain there, no Sollya fit can pass fit=best's
// comparison on these samples. At degree 3 it is the first look fpminimax's lattice search takes.
double neighbour_gain(const std::vector<std::int64_t>& held, int cf, const Samples& at) {
  constexpr int kWalk = 64;
  const double glint_error = at.error(held, cf);
  const int free = static_cast<int>(held.size()) - 2;
  double lowest = glint_error;
  if (free == 1) {
    for (const int step : {-1, 1}) {
      std::vector<std::int64_t> c = held;
      for (int i = 0; i < kWalk; ++i) {
        c[2] += step;
        c[1] -= step;
        const double e = at.error(c, cf);
        if (!(e < lowest)) break;
        lowest = e;
      }
    }
    return glint_error - lowest;
  }
  int combos = 1;
  for (int j = 0; j < free; ++j) combos *= 3;
  for (int m = 0; m < combos; ++m) {
    std::vector<std::int64_t> c = held;
    for (int j = 0, r = m; j < free; ++j, r /= 3) {
      const int step = r % 3 - 1;
      c[static_cast<std::size_t>(j) + 2] += step;
      c[1] -= step;
    }
    lowest = std::min(lowest, at.error(c, cf));
  }
  return glint_error - lowest;
}

using SegmentKey = std::tuple<std::uint64_t, std::uint64_t, std::uint64_t, int,
                              std::vector<std::int64_t>, std::vector<std::uint64_t>>;

FixedPointFit sollya_segment(double n, double a, double b, int cf, std::int64_t end0,
                             std::int64_t end1, const std::vector<double>& start) {
  static Memo<SegmentKey, FixedPointFit> memo;
  std::vector<std::uint64_t> s;
  for (double c : start) s.push_back(bits_of(c));
  const int degree = static_cast<int>(start.size()) - 1;
  return memo.get({bits_of(n), bits_of(a), bits_of(b), cf, {end0, end1, degree}, s}, [&] {
    // fpminimax's interpolation points: the interior extrema of the real fit's error (Chebyshev
    // points make up the count), which it would otherwise search for itself.
    constexpr int kPoints = 1 << 8;
    std::vector<double> e(kPoints + 1), points;
    for (int i = 0; i <= kPoints; ++i) {
      const double x = static_cast<double>(i) / kPoints;
      double p = 0;
      for (std::size_t j = start.size(); j-- > 0;) p = p * x + start[j];
      e[static_cast<std::size_t>(i)] = std::fabs(p - std::pow(a + (b - a) * x, n));
    }
    for (std::size_t i = 1; i < kPoints; ++i)
      if (e[i] > e[i - 1] && e[i] >= e[i + 1]) points.push_back(static_cast<double>(i) / kPoints);
    for (int k = 0; static_cast<int>(points.size()) < degree - 1; ++k)
      points.push_back(0.5 - 0.5 * std::cos(M_PI * (k + 0.5) / degree));
    std::sort(points.begin(), points.end());
    return fit_segment_fixed_point(n, a, b, degree, cf, end0, end1, start, points);
  });
}

CertifiedSupNorm segment_norm(const std::vector<std::int64_t>& raw, int cf, double n, double a,
                              double b) {
  static Memo<SegmentKey, CertifiedSupNorm> memo;
  return memo.get({bits_of(n), bits_of(a), bits_of(b), cf, raw, {}},
                  [&] { return certified_segment_sup_norm(raw, cf, n, a, b); });
}

// eval() non-decreasing over segment k's codes and one code either side.
bool segment_output_monotone(const PwpUnit& u, std::size_t k) {
  const std::int64_t width = std::int64_t{1} << u.offset_bits();
  const std::int64_t one = u.config().in.raw_one();
  const std::int64_t lo =
      std::max(u.t0_raw(), u.t0_raw() + static_cast<std::int64_t>(k) * width - 1);
  const std::int64_t hi = std::min(one, u.t0_raw() + static_cast<std::int64_t>(k + 1) * width);
  std::int64_t prev = u.eval(lo);
  for (std::int64_t t = lo + 1; t <= hi; ++t) {
    const std::int64_t y = u.eval(t);
    if (y < prev) return false;
    prev = y;
  }
  return true;
}

// At most this many segments a datapath group get fpminimax's search under fit=best, those where
// Sollya could win the most (header).
constexpr std::size_t kBestTries = 4;

void choose_for_unit(PwpFitEngine engine, PwpUnit& u, const Widths& widths) {
  PwpFitRecord rec;
  const int d = u.config().degree, cf = u.config().coef_frac;
  const double n = u.shininess();
  if (d < 2 || u.offset_bits() == 0 || u.t0_raw() >= u.config().in.raw_one()) {
    u.set_fit_record(rec);
    return;
  }
  const bool best = engine == PwpFitEngine::kBest;
  const long double scale = std::ldexp(1.0L, -cf);
  // The segment's input codes, x = r 2^-rb, where there are at most 2^10 of them (Sollya's segment
  // is then no worse than glint's on any input); else 2^10 + 1 points of x.
  const int points = 1 << std::min(u.offset_bits(), 10);
  struct Try {
    std::size_t k;
    double gain;  // how much lower Sollya's error could be
  };
  std::vector<Try> tries;
  for (std::size_t k = 0; k < u.segment_count(); ++k) {
    const double a = u.segment_start(k), b = u.segment_end(k);
    const double fa = std::pow(a, n), fb = std::pow(b, n);
    if (!(fb > fa)) continue;  // flat in double precision: glint's fit is the chord
    ++rec.fitted;
    if (engine == PwpFitEngine::kGlint) continue;
    if (n != std::floor(n) && a < 1.0 / 16) continue;  // t^n's branch point (header)
    if (!best) {
      tries.push_back({k, 0.0});
      continue;
    }
    const std::vector<std::int64_t> held = raw_of(u, k);
    std::int64_t sum = 0;
    for (std::int64_t c : held) sum += c;
    const double floor =
        static_cast<double>(std::max(std::fabs(static_cast<long double>(held[0]) * scale - fa),
                                     std::fabs(static_cast<long double>(sum) * scale - fb)));
    // Every segment with these ends errs by at least floor, and by at least the real minimax
    // fit's error (with exact ends) less the ends' rounding (header).
    const Samples at(n, a, b, points);
    const double lowest = std::max(floor, at.error(u.segment_fit(k)) - floor);
    const double gain = at.error(held, cf) - lowest;
    const double worth = std::ldexp(1.0, -(cf + 4));
    if (gain <= worth || neighbour_gain(held, cf, at) <= worth) continue;
    tries.push_back({k, gain});
  }
  if (best && tries.size() > kBestTries) {
    std::partial_sort(tries.begin(), tries.begin() + kBestTries, tries.end(),
                      [](const Try& x, const Try& y) {
                        return x.gain > y.gain || (x.gain == y.gain && x.k < y.k);
                      });
    tries.resize(kBestTries);
    std::sort(tries.begin(), tries.end(), [](const Try& x, const Try& y) { return x.k < y.k; });
  }
  for (const Try& t : tries) {
    const std::size_t k = t.k;
    const double a = u.segment_start(k), b = u.segment_end(k);
    const std::vector<std::int64_t> held = raw_of(u, k);
    std::int64_t sum = 0;
    for (std::int64_t c : held) sum += c;
    const FixedPointFit f = sollya_segment(n, a, b, cf, held[0], sum, u.segment_fit(k));
    if (!f.ok || f.raw == held) continue;
    if (!pwp_nondecreasing(f.raw.data(), d) || !widths.hold(f.raw)) continue;
    if (best) {
      const Samples at(n, a, b, points);
      if (at.error(f.raw, cf) >= at.error(held, cf)) continue;
    }
    const CertifiedSupNorm s = segment_norm(f.raw, cf, n, a, b);
    if (!s.ok) continue;
    if (best) {
      const CertifiedSupNorm g = segment_norm(held, cf, n, a, b);
      if (!g.ok || !(s.hi < g.lo)) continue;
    }
    PwpUnit trial = u;
    trial.replace_segment(k, f.raw);
    if (!segment_output_monotone(trial, k)) continue;
    u = std::move(trial);
    ++rec.sollya;
    rec.sup_lo = std::max(rec.sup_lo, s.lo);
    rec.sup_hi = std::max(rec.sup_hi, s.hi);
  }
  u.set_fit_record(rec);
}

}  // namespace

void choose_pwp_fit_engines(PwpFitEngine engine, std::vector<PwpUnit>& units) {
  if (units.empty()) return;
  const Widths widths = widths_of(units, units.front().config().degree);
  for (PwpUnit& u : units) {
    choose_for_unit(engine, u, widths);
    if (u.fit_record().sollya > 0) u.set_guard(u.config().guard);
  }
}

}  // namespace glint
