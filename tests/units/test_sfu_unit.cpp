// The sfu unit (src/units/sfu/): its datapath is the Tesla SFU model (tesla_sfu.h, held to the
// hardware's reference vectors by test_tesla_sfu.cpp) between two conversions; here the unit
// against that model with the conversions done independently (the C++ float type and the FPU's
// round to nearest even), on every input code of small formats, its staged registers, its stated
// bound and its place outside the default set.
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "units/catalogue.h"
#include "units/sfu/tesla_sfu.h"

namespace glint {
namespace {

std::uint32_t bits_of(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
float float_of(std::uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

MaterialParams material(double n) {
  MaterialParams m{n, -1.0};  // never skips: every code reaches the datapath
  m.name = "material 'm'";
  return m;
}

struct Case {
  std::string spec;
  int in_frac, out_frac;
  double n_step;  // the n register's ulp
};

TEST(SfuUnit, EvalIsTheShaderOnEveryInputCode) {
  ASSERT_EQ(std::fegetround(), FE_TONEAREST);
  for (const Case& c : {Case{"sfu:in=uq1.12,out=uq1.10,n=uq14.4", 12, 10, 1.0 / 16},
                        Case{"sfu:in=uq1.15,out=uq1.8,n=uq10.2", 15, 8, 1.0 / 4},
                        Case{"sfu:in=uq1.10,out=uq1.23,n=uq14.4", 10, 23, 1.0 / 16}}) {
    for (double n : {1.0, 2.5, 7.3, 50.0, 128.0, 1000.0}) {
      const auto u = make_unit(parse_unit_spec(c.spec), {material(n)});
      const float nq = static_cast<float>(std::nearbyint(n / c.n_step) * c.n_step);
      std::vector<std::int64_t> staged(u->stages().size());
      const std::size_t result = u->stages().result_index();
      for (std::int64_t t = 0; t <= (std::int64_t{1} << c.in_frac); ++t) {
        const std::string what = c.spec + " n=" + std::to_string(n) + " t=" + std::to_string(t);
        const float tf = std::ldexp(static_cast<float>(t), -c.in_frac);
        const tesla_sfu::Highlight h = tesla_sfu::highlight(bits_of(tf), bits_of(nq));
        const double y = static_cast<double>(float_of(h.ex2));
        const auto want = static_cast<std::int64_t>(std::nearbyint(std::ldexp(y, c.out_frac)));
        ASSERT_EQ(u->eval(0, t), want) << what;
        u->eval_staged(0, t, staged.data());
        ASSERT_EQ(staged[result], want) << what;
        if (t == 0) continue;  // the short-cut leaves the fp32 registers at 0
        // lg2 | fmul (n, product) | pre | ex2, in the layout's order after the input stage.
        const std::int64_t regs[] = {h.lg2, bits_of(nq), h.product, h.pre, h.ex2};
        for (std::size_t r = 0; r < std::size(regs); ++r)
          ASSERT_EQ(staged[u->stages().offset(1) + r], regs[r]) << what << " register " << r;
      }
    }
  }
}

TEST(SfuUnit, StatedBoundIsTheExactMaximum) {
  for (double n : {2.5, 20.0, 300.0}) {
    const auto u = make_unit(parse_unit_spec("sfu:in=uq1.13,out=uq1.13"), {material(n)});
    double worst = 0;
    for (std::int64_t t = 0; t <= (1 << 13); ++t)
      worst = std::max(
          worst, std::fabs(static_cast<double>(u->eval(0, t)) - std::ldexp(u->model(0, t), 13)));
    EXPECT_EQ(u->datapath_bound_ulps(0), worst) << n;
    EXPECT_EQ(u->error_bound(0), std::ldexp(worst, -13)) << n;
    EXPECT_GT(worst, 0.0) << n;  // the rounding to the output alone
  }
}

TEST(SfuUnit, RefusesWhatFp32CannotHoldExactly) {
  const auto refusal = [](const std::string& spec) {
    try {
      make_unit(parse_unit_spec(spec), {material(50)});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("built");
  };
  EXPECT_NE(refusal("sfu:in=uq1.24").find("key 'in' = 'uq1.24'"), std::string::npos);
  EXPECT_NE(refusal("sfu:n=uq16.9").find("key 'n' = 'uq16.9'"), std::string::npos);
  EXPECT_EQ(refusal("sfu:in=uq1.23,n=uq16.8"), "built");
}

TEST(SfuUnit, OneUnitAwayNotInTheDefaultSet) {
  const auto all = unit_names(), defaults = default_unit_names();
  EXPECT_NE(std::find(all.begin(), all.end(), "sfu"), all.end());
  EXPECT_EQ(std::find(defaults.begin(), defaults.end(), "sfu"), defaults.end());
}

}  // namespace
}  // namespace glint
