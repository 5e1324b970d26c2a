// Sollya's fixed-point fits and certified sup norms (fit/sollya_fit.h) against fit.h's Remez fit
// rounded to the same grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "fit/fit.h"
#include "fit/monotone.h"
#include "fit/sollya_fit.h"
#include "reference/reference.h"

namespace glint {
namespace {

FitOptions tau_minimax(double n, int degree) {
  FitOptions o;
  o.shininess = n;
  o.degree = degree;
  o.method = FitMethod::kMinimax;
  o.domain = FitDomain::kTau;
  o.tau = tau_power(n, 1e-3, 1.0).tau;
  o.constrain_one = true;
  o.constrain_zero = true;
  o.monotone = true;
  return o;
}

// The Remez fit rounded as horner rounds it: nearest on the grid, c_0 = 0, c_1 absorbing the
// residue of P(1) = 1.
std::vector<std::int64_t> round_like_horner(const std::vector<double>& c, int frac_bits) {
  std::vector<std::int64_t> raw;
  for (double v : c) raw.push_back(std::llround(std::ldexp(v, frac_bits)));
  raw[0] = 0;
  std::int64_t rest = 0;
  for (std::size_t k = 2; k < raw.size(); ++k) rest += raw[k];
  raw[1] = (std::int64_t{1} << frac_bits) - rest;
  return raw;
}

// max |P - t^n| on a dense grid of u, in long double.
double grid_error(const std::vector<std::int64_t>& raw, int frac_bits, double n, double tau) {
  double worst = 0;
  for (int i = 0; i <= 20000; ++i) {
    const long double u = i / 20000.0L;
    long double p = 0;
    for (std::size_t k = raw.size(); k-- > 0;)
      p = p * u + std::ldexp((long double)raw[k], -frac_bits);
    const long double t = tau + (1.0L - tau) * u;
    worst = std::max(worst, static_cast<double>(std::fabs(p - std::pow(t, (long double)n))));
  }
  return worst;
}

struct Case {
  double n;
  int degree;
  int frac_bits;
};

// fpminimax searches the grid itself: on the same grid it is never worse than Remez rounded to
// nearest by more than the sup norm's own enclosure, and it is better where the rounding matters.
TEST(SollyaFit, NoWorseThanRoundedRemezAndCertified) {
  int better = 0;
  for (const Case& k :
       {Case{50, 4, 13}, Case{50, 6, 14}, Case{20, 8, 13}, Case{128, 5, 12}, Case{8, 3, 10}}) {
    SCOPED_TRACE(testing::Message()
                 << "n " << k.n << " degree " << k.degree << " frac " << k.frac_bits);
    FitOptions o = tau_minimax(k.n, k.degree);
    o.monotone = false;  // the real minimax fit: its error alternates, fpminimax's points
    const FitResult remez = fit_power(o);
    const FixedPointFit s = fit_power_fixed_point(o, k.frac_bits, remez.coeffs);
    ASSERT_TRUE(s.ok) << s.failure;
    ASSERT_EQ(s.raw.size(), static_cast<std::size_t>(k.degree) + 1);
    // The constraints hold exactly on the grid.
    EXPECT_EQ(s.raw[0], 0);
    std::int64_t sum = 0;
    for (std::int64_t c : s.raw) sum += c;
    EXPECT_EQ(sum, std::int64_t{1} << k.frac_bits);

    const std::vector<std::int64_t> rounded = round_like_horner(remez.coeffs, k.frac_bits);
    const CertifiedSupNorm cs = certified_sup_norm(s.raw, k.frac_bits, FitVariable::kU, k.n, o.tau);
    const CertifiedSupNorm cr =
        certified_sup_norm(rounded, k.frac_bits, FitVariable::kU, k.n, o.tau);
    ASSERT_TRUE(cs.ok);
    ASSERT_TRUE(cr.ok);
    // The enclosure holds the sampled maximum (which may lie below its lower end: a grid misses
    // the true maximum by a little).
    const double gs = grid_error(s.raw, k.frac_bits, k.n, o.tau);
    EXPECT_GE(cs.hi, gs);
    EXPECT_LE(cs.hi, cs.lo * (1 + 1e-3));
    // Never a lot worse; the unit keeps the better of the two (units/horner).
    EXPECT_LE(cs.lo, cr.hi * 1.05);
    if (cs.hi < cr.lo) ++better;
  }
  EXPECT_GE(better, 1);
}

// A piecewise polynomial's segment (units/pwp): both ends stay exactly where they are given, the
// result is on the grid, and its certified sup norm holds the error sampled on the segment.
TEST(SollyaFit, SegmentKeepsItsEndsAndIsCertified) {
  const double n = 50, a = 0.9375, b = 0.96875;
  const int frac = 12;
  const std::int64_t end0 = std::llround(std::ldexp(std::pow(a, n), frac));
  const std::int64_t end1 = std::llround(std::ldexp(std::pow(b, n), frac));
  // A start with the right ends and a curvature near t^n's: the chord bent by a parabola.
  const double rise = std::pow(b, n) - std::pow(a, n);
  const std::vector<double> start{std::pow(a, n), 0.6 * rise, 0.3 * rise, 0.1 * rise};
  for (const std::vector<double>& points : {std::vector<double>{}, {0.25, 0.75}}) {
    const FixedPointFit s = fit_segment_fixed_point(n, a, b, 3, frac, end0, end1, start, points);
    ASSERT_TRUE(s.ok) << s.failure;
    ASSERT_EQ(s.raw.size(), 4U);
    EXPECT_EQ(s.raw[0], end0);
    EXPECT_EQ(s.raw[0] + s.raw[1] + s.raw[2] + s.raw[3], end1);
    const CertifiedSupNorm c = certified_segment_sup_norm(s.raw, frac, n, a, b);
    ASSERT_TRUE(c.ok);
    double sampled = 0;
    for (int i = 0; i <= 1024; ++i) {
      const double x = i / 1024.0;
      long double p = 0;
      for (std::size_t j = 4; j-- > 0;)
        p = p * x + std::ldexp(static_cast<long double>(s.raw[j]), -frac);
      sampled = std::max(sampled, static_cast<double>(std::fabs(p - std::pow(a + (b - a) * x, n))));
    }
    EXPECT_GE(c.hi, sampled);
    EXPECT_LE(c.lo, sampled * (1 + 1e-3));
  }
  // Degree 1 has nothing to fit; too few points for the free coefficients are refused.
  EXPECT_FALSE(fit_segment_fixed_point(n, a, b, 1, frac, end0, end1, {start[0], rise}).ok);
  EXPECT_FALSE(fit_segment_fixed_point(n, a, b, 3, frac, end0, end1, start, {0.5}).ok);
}

TEST(SollyaFit, RefusesWhatItDoesNotFit) {
  FitOptions o = tau_minimax(20, 1);
  const FitResult r = fit_power(o);
  EXPECT_FALSE(fit_power_fixed_point(o, 12, r.coeffs).ok);  // P = u: nothing free
  o = tau_minimax(20, 4);
  o.method = FitMethod::kLeastSquares;
  EXPECT_FALSE(fit_power_fixed_point(o, 12, fit_power(o).coeffs).ok);
}

}  // namespace
}  // namespace glint
