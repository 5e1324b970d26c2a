// Specs at the edges of the register widths are built with their contract or refused with a
// message naming the unit; none overflows silently or reaches an undefined shift (the sanitizer
// build runs this too). Regression cases from issue 11: pow with a wide input format computed
// garbage within "its bound", and a u scaler at wide formats shifted by 64 bits and never ended.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

std::vector<MaterialParams> materials() {
  const TauResult t = tau_power(50, 1e-3, 1.0);
  return {MaterialParams{50, t.tau, false}, MaterialParams{5, -1.0, false}};
}

TEST(UnitLimits, PowWithTooManyInterpolationBitsIsRefused) {
  try {
    make_unit(parse_unit_spec("pow:in=uq1.57"), materials());
    FAIL() << "pow:in=uq1.57 was built";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pow: log2 interpolation"), std::string::npos) << e.what();
  }
  // As wide as the products allow: built, and within its stated bound against t^n.
  const auto u = make_unit(parse_unit_spec("pow:in=uq1.36"), materials());
  const QFormat in = u->in_format();
  for (std::int64_t t = in.raw_one() / 2; t <= in.raw_one(); t += in.raw_one() / 4096) {
    const double x = std::ldexp(static_cast<double>(t), -in.frac_bits);
    const double out = std::ldexp(static_cast<double>(u->eval(0, t)), -u->out_format().frac_bits);
    EXPECT_LE(std::fabs(out - std::pow(x, 50.0)), u->error_bound(0)) << "t = " << x;
  }
}

// Every width up to the format limit, for the units with a u scaler: built or refused, never hung,
// and what is built gives f(1) = 1 and outputs in [0, 1].
TEST(UnitLimits, UScalerWidthsAreBuiltOrRefused) {
  int built = 0, refused = 0;
  for (const char* unit : {"hast", "horner:degree=2"}) {
    for (int in = 8; in <= 61; in += 3) {
      for (int out = 8; out <= 61; out += 3) {
        const std::string spec = std::string(unit) +
                                 (std::string(unit).find(':') == std::string::npos ? ":" : ",") +
                                 "in=uq1." + std::to_string(in) + ",out=uq1." + std::to_string(out);
        try {
          const auto u = make_unit(parse_unit_spec(spec), materials());
          ++built;
          EXPECT_EQ(u->eval(0, u->in_format().raw_one()), u->out_format().raw_one()) << spec;
          for (std::int64_t t = 0; t <= u->in_format().raw_one();
               t += u->in_format().raw_one() / 64) {
            const std::int64_t y = u->eval(1, t);
            EXPECT_GE(y, 0) << spec;
            EXPECT_LE(y, u->out_format().raw_one()) << spec;
          }
        } catch (const std::invalid_argument& e) {
          ++refused;
          const std::string what = e.what();
          EXPECT_TRUE(what.find("hast") != std::string::npos ||
                      what.find("horner") != std::string::npos)
              << spec << ": " << what;
        }
      }
    }
  }
  EXPECT_GT(built, 10);
  EXPECT_GT(refused, 10);
}

}  // namespace
}  // namespace glint
