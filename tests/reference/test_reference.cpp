// The double-precision reference models against the papers' own statements.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "reference/reference.h"

namespace glint {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Lobe, ToStringAndParseRoundTrip) {
  for (Lobe l : {Lobe::kPhong, Lobe::kBlinn, Lobe::kGaussian}) {
    EXPECT_EQ(parse_lobe(to_string(l)), l);
  }
  EXPECT_STREQ(to_string(Lobe::kBlinn), "blinn");
  EXPECT_THROW(parse_lobe("cook-torrance"), std::invalid_argument);
  EXPECT_THROW(parse_lobe(""), std::invalid_argument);
}

// Källberg eq.3/eq.6 use Rec.709 weights; they must sum to 1 so that white has luminance 1 and
// eps means the same thing for every material.
TEST(Luminance, Rec709WeightsSumToOneAndWhiteIsOne) {
  EXPECT_NEAR(kLumaR + kLumaG + kLumaB, 1.0, 1e-15);
  EXPECT_NEAR(luminance(Rgb{1, 1, 1}), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(luminance(Rgb{1, 0, 0}), 0.2126);
  EXPECT_DOUBLE_EQ(luminance(Rgb{0, 1, 0}), 0.7152);
  EXPECT_DOUBLE_EQ(luminance(Rgb{0, 0, 1}), 0.0722);
}

TEST(Luminance, CyPerLightAndPerMaterial) {
  const Rgb m{0.8, 0.5, 0.2};
  const Rgb i{0.5, 1.0, 2.0};
  // Eq.3: per-channel products, then the luminance weights.
  EXPECT_NEAR(c_y(i, m), 0.2126 * 0.4 + 0.7152 * 0.5 + 0.0722 * 0.4, 1e-15);
  // Eq.6 is eq.3 with white 100% lights.
  EXPECT_DOUBLE_EQ(c_y(m), c_y(Rgb{1, 1, 1}, m));
}

TEST(Glossy, ClampedPower) {
  EXPECT_EQ(glossy_scalar(-0.5, 2.0), 0.0);
  EXPECT_EQ(glossy_scalar(0.0, 50.0), 0.0);
  EXPECT_EQ(glossy_scalar(-0.5, 2.5), 0.0);  // no NaN from pow of a negative base
  EXPECT_DOUBLE_EQ(glossy_scalar(1.0, 50.0), 1.0);
  EXPECT_DOUBLE_EQ(glossy_scalar(0.5, 3.0), 0.125);
  const Rgb s = glossy_term(0.5, 2.0, Rgb{1, 0.5, 2}, Rgb{0.4, 1, 0.5});
  EXPECT_DOUBLE_EQ(s.r, 0.25 * 0.4);
  EXPECT_DOUBLE_EQ(s.g, 0.25 * 0.5);
  EXPECT_DOUBLE_EQ(s.b, 0.25 * 1.0);
  const Rgb z = glossy_term(-0.1, 2.0, Rgb{1, 1, 1}, Rgb{1, 1, 1});
  EXPECT_EQ(z.r + z.g + z.b, 0.0);
}

// Källberg §2: alpha = 50, eps = 1e-3, i = m = 1 gives tau ~ 0.87.
TEST(TauPower, PaperExample) {
  const TauResult r = tau_power(50.0, 1e-3, 1.0);
  EXPECT_FALSE(r.always_skip);
  EXPECT_FALSE(r.never_skip);
  EXPECT_NEAR(r.tau, 0.871, 5e-4);
  EXPECT_NEAR(r.tau, std::pow(1e-3, 1.0 / 50.0), 1e-15);
  EXPECT_EQ(r.c_y, 1.0);
  EXPECT_EQ(r.eps, 1e-3);
}

// Eq.4 is an equality at tau: the lobe luminance there is exactly eps.
TEST(TauPower, BoundaryEquality) {
  for (double n : {1.0, 2.0, 7.5, 50.0, 300.0, 2000.0}) {
    for (double cy : {0.01, 0.3, 1.0, 4.0}) {
      const TauResult r = tau_power(n, 1e-3, cy);
      ASSERT_FALSE(r.always_skip);
      const double s = glossy_scalar(r.tau, n) * cy;
      EXPECT_NEAR(s, 1e-3, 1e-12) << "n=" << n << " c_y=" << cy;
      // Just below tau the lobe is under eps, just above it is over.
      EXPECT_LE(glossy_scalar(r.tau * (1 - 1e-9), n) * cy, 1e-3);
      EXPECT_GT(glossy_scalar(std::min(1.0, r.tau * (1 + 1e-6)), n) * cy, 1e-3);
      EXPECT_TRUE(r.skip(r.tau));
      EXPECT_FALSE(r.skip(std::min(1.0, r.tau + 1e-6)));
    }
  }
}

// Källberg §2 end: eps_n = eps/n for n lights, so tau drops accordingly.
TEST(TauPower, LightsDivideEps) {
  const TauResult one = tau_power(50.0, 1e-3, 1.0, 1);
  const TauResult four = tau_power(50.0, 1e-3, 1.0, 4);
  EXPECT_DOUBLE_EQ(four.eps, 2.5e-4);
  EXPECT_NEAR(four.tau, std::pow(2.5e-4, 1.0 / 50.0), 1e-15);
  EXPECT_LT(four.tau, one.tau);  // a smaller eps skips less: the threshold moves down
  // Four lobes each skipped at eps/4 sum to at most eps.
  EXPECT_NEAR(4.0 * glossy_scalar(four.tau, 50.0), 1e-3, 1e-12);
}

TEST(TauPower, DimLobeAlwaysSkips) {
  for (double cy : {0.0, 5e-4, 1e-3}) {
    const TauResult r = tau_power(50.0, 1e-3, cy);
    EXPECT_TRUE(r.always_skip) << cy;
    EXPECT_FALSE(r.never_skip);
    EXPECT_EQ(r.tau, 1.0);
    EXPECT_TRUE(r.skip(1.0));
    EXPECT_TRUE(r.skip(-1.0));
  }
  // With K lights each lobe gets eps/K, so a lobe negligible on its own may need shading.
  EXPECT_TRUE(tau_power(50.0, 1e-3, 5e-4, 1).always_skip);
  EXPECT_FALSE(tau_power(50.0, 1e-3, 5e-4, 10).always_skip);
}

TEST(TauPower, RejectsBadInputs) {
  EXPECT_THROW(tau_power(0.0, 1e-3, 1.0), std::invalid_argument);
  EXPECT_THROW(tau_power(-2.0, 1e-3, 1.0), std::invalid_argument);
  EXPECT_THROW(tau_power(NAN, 1e-3, 1.0), std::invalid_argument);
  EXPECT_THROW(tau_power(50.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(tau_power(50.0, -1e-3, 1.0), std::invalid_argument);
  EXPECT_THROW(tau_power(50.0, 1e-3, -0.1), std::invalid_argument);
  EXPECT_THROW(tau_power(50.0, 1e-3, 1.0, 0), std::invalid_argument);
}

TEST(Gaussian, LobeShape) {
  EXPECT_DOUBLE_EQ(gaussian_lobe(1.0, 0.3), 1.0);
  EXPECT_DOUBLE_EQ(gaussian_lobe(1.0 + 1e-12, 0.3), 1.0);  // clamped, no NaN
  const double phi = 0.2;
  EXPECT_NEAR(gaussian_lobe(std::cos(phi), 0.4), std::exp(-0.25), 1e-12);
  EXPECT_NEAR(gaussian_lobe(-1.0, 1.0), std::exp(-kPi * kPi), 1e-15);
  EXPECT_THROW(gaussian_lobe(0.5, 0.0), std::invalid_argument);
}

// Eq.9 at equality: the lobe at tau is exactly eps/c_y.
TEST(Gaussian, TauBoundaryEquality) {
  for (double omega : {0.05, 0.2, 0.5, 1.0}) {
    for (double cy : {0.01, 0.5, 1.0}) {
      const TauResult r = tau_gaussian(omega, 1e-3, cy);
      ASSERT_FALSE(r.always_skip);
      ASSERT_FALSE(r.never_skip);
      EXPECT_NEAR(gaussian_lobe(r.tau, omega), 1e-3 / cy, 1e-9 * 1e-3 / cy)
          << "omega=" << omega << " c_y=" << cy;
      EXPECT_LE(gaussian_lobe(r.tau - 1e-6, omega) * cy, 1e-3);
    }
  }
}

TEST(Gaussian, DimLobeAlwaysSkips) {
  EXPECT_TRUE(tau_gaussian(0.3, 1e-3, 0.0).always_skip);
  EXPECT_TRUE(tau_gaussian(0.3, 1e-3, 1e-3).always_skip);
  EXPECT_EQ(tau_gaussian(0.3, 1e-3, 1e-4).tau, 1.0);
}

// Eq.8's angle beyond pi: no direction is dim enough, so the lobe is never skipped (eq.9 would
// wrap round and skip everything past cos(angle)).
TEST(Gaussian, AngleBeyondPiNeverSkips) {
  // omega = 2 (outside the paper's (0, 1], accepted): 2 sqrt(ln 1000) = 5.26 > pi.
  const TauResult r = tau_gaussian(2.0, 1e-3, 1.0);
  EXPECT_TRUE(r.never_skip);
  EXPECT_FALSE(r.always_skip);
  EXPECT_EQ(r.tau, -1.0);
  EXPECT_FALSE(r.skip(-1.0));
  EXPECT_FALSE(r.skip(0.0));
  // And indeed the lobe is above eps even facing away.
  EXPECT_GT(gaussian_lobe(-1.0, 2.0), 1e-3);
  // Within the paper's omega range the angle exceeds pi only for enormous c_y/eps.
  EXPECT_TRUE(tau_gaussian(1.0, 1e-6, 1e3).never_skip);   // sqrt(ln 1e9) = 4.55 > pi
  EXPECT_FALSE(tau_gaussian(1.0, 1e-3, 1.0).never_skip);  // sqrt(ln 1e3) = 2.63 < pi
}

// cos^n(phi) ~ exp(-n phi^2/2) near the peak, so n = 2/omega^2 gives a matching lobe.
TEST(Gaussian, EquivalentShininess) {
  EXPECT_DOUBLE_EQ(gaussian_equivalent_shininess(0.2), 50.0);
  for (double omega : {0.05, 0.1, 0.2}) {
    const double n = gaussian_equivalent_shininess(omega);
    for (double phi : {0.1 * omega, 0.5 * omega, omega}) {
      const double a = glossy_scalar(std::cos(phi), n);
      const double b = gaussian_lobe(std::cos(phi), omega);
      EXPECT_NEAR(a, b, 0.01) << "omega=" << omega << " phi=" << phi;
    }
  }
  EXPECT_THROW(gaussian_equivalent_shininess(0.0), std::invalid_argument);
}

TEST(Schlick, EndpointsAndDominance) {
  for (double n : {1.0, 2.0, 3.3, 10.0, 50.0, 128.0, 500.0, 1000.0}) {
    EXPECT_EQ(schlick(0.0, n), 0.0);
    EXPECT_DOUBLE_EQ(schlick(1.0, n), 1.0);
    EXPECT_EQ(schlick(-0.3, n), 0.0);
    // S_n(t) >= t^n on (0, 1) for n >= 1 (see reference.h for the proof).
    for (int i = 1; i < 4000; ++i) {
      const double t = i / 4000.0;
      ASSERT_GE(schlick(t, n) * (1 + 1e-14), std::pow(t, n)) << "n=" << n << " t=" << t;
    }
  }
  EXPECT_DOUBLE_EQ(schlick(0.5, 1.0), 0.5);  // n = 1 is the identity
  EXPECT_THROW(schlick(0.5, 0.0), std::invalid_argument);
}

TEST(Hast, EndpointsRootsAndForms) {
  for (double tau : {0.0, 0.5, 0.87, 0.92, 0.99}) {
    for (int d = 2; d <= 5; ++d) {
      EXPECT_NEAR(hast(1.0, tau, d), 1.0, 1e-12);
      EXPECT_DOUBLE_EQ(hast_scaled(1.0, tau, d), 1.0);
      EXPECT_EQ(hast(tau, tau, d), 0.0);
      EXPECT_EQ(hast(tau - 0.1, tau, d), 0.0);
      EXPECT_EQ(hast_scaled(tau - 0.1, tau, d), 0.0);
      EXPECT_EQ(hast(-1.0, tau, d), 0.0);
      double prev = 0.0;
      for (int i = 1; i <= 1000; ++i) {
        const double rho = tau + (1.0 - tau) * i / 1000.0;
        const double a = hast(rho, tau, d);
        const double b = hast_scaled(rho, tau, d);
        ASSERT_NEAR(a, b, 1e-13 * std::max(1.0, b)) << "tau=" << tau << " d=" << d;
        ASSERT_GT(a, prev);  // increasing above the root
        prev = a;
      }
    }
  }
  // The kappa form overflows where the scaled form does not.
  EXPECT_TRUE(std::isnan(hast(0.995, 0.99, 200)) || std::isinf(hast(0.995, 0.99, 200)));
  EXPECT_NEAR(hast_scaled(0.995, 0.99, 200), std::pow(0.5, 200), 1e-70);
  EXPECT_THROW(hast(0.5, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(hast_scaled(0.5, 0.5, 0), std::invalid_argument);
}

TEST(Horner, MatchesNaiveSum) {
  const std::vector<double> c{0.3, -1.25, 2.0, 0.5, -0.75, 0.125};
  for (double x : {-1.5, -0.3, 0.0, 0.25, 0.87, 1.0, 2.0}) {
    double naive = 0.0;
    for (std::size_t k = 0; k < c.size(); ++k) naive += c[k] * std::pow(x, static_cast<int>(k));
    EXPECT_NEAR(horner(c, x), naive, 1e-13) << x;
  }
  EXPECT_EQ(horner(std::vector<double>{}, 0.5), 0.0);
  EXPECT_EQ(horner(std::vector<double>{4.0}, 0.5), 4.0);
}

}  // namespace
}  // namespace glint
