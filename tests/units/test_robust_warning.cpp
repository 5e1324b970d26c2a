// method=robust on t^n: bisquare weights assume the residuals are noise, and on the noise-free
// function they are the polynomial's bias, so the weights can drop the samples where t^n is
// steepest (fit.h, robust_rejects_samples). glint fit and a horner build warn when the robust fit
// came out much worse than least squares on the same samples, and stay quiet where it did not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fit/fit.h"
#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/warning.h"

namespace glint {
namespace {

FitOptions options(double n, int degree, FitMethod method, FitDomain domain) {
  FitOptions o;
  o.shininess = n;
  o.degree = degree;
  o.method = method;
  o.domain = domain;
  if (domain == FitDomain::kTau) o.tau = tau_power(n, 1e-3, 1.0).tau;
  return o;
}

// The largest |P - t^n| over the full domain's samples x_i = i/N (fit.h).
double on_samples(const FitResult& r, int samples) {
  double worst = 0;
  for (int i = 1; i <= samples; ++i) {
    const double x = static_cast<double>(i) / samples;
    worst = std::max(worst, std::fabs(horner(r.coeffs, x) - std::pow(x, r.shininess)));
  }
  return worst;
}

// The case: n = 20, degree 4, 1000 samples, full domain (Öztürk's setting).
TEST(RobustWarning, FitFlagsTheRejectedHighlight) {
  FitOptions o = options(20, 4, FitMethod::kRobust, FitDomain::kFull);
  o.samples = 1000;
  const FitResult robust = fit_power(o);
  o.method = FitMethod::kLeastSquares;
  const FitResult ls = fit_power(o);
  EXPECT_TRUE(robust_rejects_samples(robust));
  EXPECT_FALSE(robust_rejects_samples(ls));
  EXPECT_NEAR(robust.sample_max_error, on_samples(robust, 1000), 1e-12);
  EXPECT_NEAR(robust.ls_sample_max_error, on_samples(ls, 1000), 1e-12);
  EXPECT_GT(robust.sample_max_error, 0.99);  // the whole highlight
  EXPECT_LT(robust.ls_sample_max_error, 0.3);
}

// Where robust stays near least squares (a low n, whose bias is spread out; horner's constrained
// default on the tau domain), nothing is flagged.
TEST(RobustWarning, FitQuietWhereRobustIsHarmless) {
  for (FitDomain d : {FitDomain::kFull, FitDomain::kTau}) {
    for (int p = 1; p <= 6; ++p) {
      const FitResult r = fit_power(options(5, p, FitMethod::kRobust, d));
      EXPECT_FALSE(robust_rejects_samples(r)) << to_string(d) << " degree " << p;
      EXPECT_LE(r.sample_max_error, 1.25 * r.ls_sample_max_error + 1e-12) << p;
    }
  }
  FitOptions o = options(50, 4, FitMethod::kRobust, FitDomain::kTau);
  o.constrain_one = o.constrain_zero = true;
  EXPECT_FALSE(robust_rejects_samples(fit_power(o)));
}

std::vector<MaterialParams> material(double n) {
  MaterialParams m{n, tau_power(n, 1e-3, 1.0).tau, false};
  m.name = "material 'm'";
  return {m};
}

TEST(RobustWarning, HornerBuildWarnsOnce) {
  std::vector<std::string> got;
  set_warning_sink([&](const std::string& w) { got.push_back(w); });
  // Degree 1, unconstrained: the robust line misses the highlight; building it again (a sweep
  // does) says nothing new.
  make_unit(parse_unit_spec("horner:method=robust,degree=1,constrain=off"), material(50));
  ASSERT_EQ(got.size(), 1u);
  for (const char* part : {"unit 'horner'", "key 'method' = 'robust'", "degree 1", "t^50",
                           "material 'm'", "method=ls"})
    EXPECT_NE(got[0].find(part), std::string::npos) << part << " in: " << got[0];
  make_unit(parse_unit_spec("horner:method=robust,degree=1,constrain=off"), material(50));
  EXPECT_EQ(got.size(), 1u);
  // Least squares, and robust where the constraints and the monotone refit leave it close to
  // least squares (the default degree on [tau, 1]), warn of nothing.
  make_unit(parse_unit_spec("horner:method=ls,degree=1,constrain=off"), material(50));
  make_unit(parse_unit_spec("horner:method=robust"), material(50));
  EXPECT_EQ(got.size(), 1u) << got.back();
  set_warning_sink({});
}

}  // namespace
}  // namespace glint
