// The accuracy contract of every datapath unit, exhaustively over all 2^16 inputs of the default
// 16-bit input format (uq1.15, including the raws above 1.0 that the front end clamps):
//  - Schlick is correctly rounded (<= ½ ulp of its real-valued model at the quantized t and n);
//  - Hast, Horner and pwp are faithful (< 1 ulp of their real-valued models at the quantized input
//    and coefficients; pwp within its stated budget when a guard is given);
//  - pow, lut and sfu stay within the bound they state against t^n itself on every computed input;
//  - every unit is monotone non-decreasing in t, returns exactly 1.0 at t = 1 (Schlick, Hast, the
//    constrained fits, pow, lut, sfu, pwp), and exactly 0 where it skips;
//  - every unit's comparator skips only inputs that Källberg's float test skips on real t, and
//    only where the unit's own output is imperceptible (Källberg §3).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "code_sweep.h"
#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

constexpr std::int64_t kInputs = std::int64_t{1} << 16;

MaterialParams material(double n, double c_y = 1.0, double eps = 1e-3) {
  const TauResult t = tau_power(n, eps, c_y);
  MaterialParams m{n, t.never_skip ? -1.0 : t.tau, t.always_skip};
  m.level = t.eps / c_y;
  return m;
}

using Sweep = test::CodeSweep;

// Every code below 2^16 (codes above the input's 1.0 read as 1.0).
Sweep sweep(const SpecularUnit& u, std::size_t slot, double n) {
  return test::sweep_codes(u, slot, n, kInputs - 1);
}

const double kShininess[] = {1, 2, 3.5, 5, 10, 20, 50, 100, 200, 500, 1000};

std::unique_ptr<SpecularUnit> build(const std::string& spec, const MaterialParams& m) {
  return make_unit(parse_unit_spec(spec), {m});
}

void expect_common(const Sweep& s, const SpecularUnit& u, const std::string& what) {
  EXPECT_EQ(s.first_nonmonotone, -1) << what << ": not monotone at raw t " << s.first_nonmonotone;
  EXPECT_EQ(s.nonzero_skipped, 0) << what << ": skipped inputs must give exactly 0";
  EXPECT_EQ(s.at_one, u.out_format().raw_one()) << what << ": f(1) must be exactly 1.0";
}

TEST(ExhaustiveUnits, SchlickCorrectlyRounded) {
  for (double n : kShininess) {
    for (double cy : {1.0, 0.25}) {
      for (const char* skip : {"on", "off"}) {
        const auto u = build(std::string("schlick:skip=") + skip, material(n, cy));
        const Sweep s = sweep(*u, 0, n);
        const std::string what = u->canonical_spec() + " n=" + std::to_string(n);
        EXPECT_LE(s.max_ulps, 0.5 + 1e-9) << what;
        expect_common(s, *u, what);
      }
    }
  }
}

TEST(ExhaustiveUnits, HastFaithful) {
  for (double n : kShininess) {
    for (int d = 2; d <= 5; ++d) {
      const auto u = build("hast:d=" + std::to_string(d), material(n));
      const Sweep s = sweep(*u, 0, n);
      const std::string what = u->canonical_spec() + " n=" + std::to_string(n);
      EXPECT_LT(s.max_ulps, 1.0) << what;
      expect_common(s, *u, what);
    }
  }
}

TEST(ExhaustiveUnits, HastNearOneTauStaysAccurate) {
  // tau -> 1 is where kappa (rho - tau)^d would overflow or vanish: the scaled form must not.
  for (double tau : {0.99, 0.999, 0.9999}) {
    const auto u = build("hast:d=5", MaterialParams{1000, tau, false});
    const Sweep s = sweep(*u, 0, 1000);
    EXPECT_LT(s.max_ulps, 1.0) << "tau " << tau;
    expect_common(s, *u, "tau near one");
  }
}

TEST(ExhaustiveUnits, HornerFaithfulConstrainedAndMonotone) {
  // Every fit horner builds is monotone by construction (src/fit/monotone.h: the clamped
  // polynomial is checked exactly and refitted under slope constraints where minimax is not), and
  // the datapath adds no step back of its own: Öztürk's full-domain fits and ours on [tau, 1],
  // least squares, robust and minimax, constrained or not.
  for (double n : {2.0, 10.0, 20.0, 50.0, 200.0}) {
    for (int p : {2, 3, 4, 5, 6}) {
      for (const char* method : {"ls", "minimax", "robust"}) {
        for (const char* domain : {"tau", "full"}) {
          for (const char* constrain : {"on", "off"}) {
            const std::string spec = std::string("horner:degree=") + std::to_string(p) +
                                     ",method=" + method + ",domain=" + domain +
                                     ",constrain=" + constrain;
            const auto u = build(spec, material(n));
            const Sweep s = sweep(*u, 0, n);
            const std::string what = spec + " n=" + std::to_string(n);
            EXPECT_LT(s.max_ulps, 1.0) << what;
            EXPECT_EQ(s.nonzero_skipped, 0) << what;
            EXPECT_EQ(s.first_nonmonotone, -1) << what;
            if (std::string(constrain) == "on") {
              EXPECT_EQ(s.at_one, u->out_format().raw_one()) << what;
            }
          }
        }
      }
    }
  }
}

TEST(ExhaustiveUnits, HornerDefaultMonotone) {
  // The default configuration (degree-4 constrained minimax on [tau, 1]) is monotone.
  for (double n : kShininess) {
    const auto u = build("horner", material(n));
    const Sweep s = sweep(*u, 0, n);
    expect_common(s, *u, u->canonical_spec() + " n=" + std::to_string(n));
  }
}

TEST(ExhaustiveUnits, PowWithinStatedBound) {
  for (double n : kShininess) {
    for (const char* skip : {"on", "off"}) {
      const auto u = build(std::string("pow:skip=") + skip, material(n));
      const Sweep s = sweep(*u, 0, n);
      const std::string what = u->canonical_spec() + " n=" + std::to_string(n);
      EXPECT_LE(s.max_abs_vs_pow, u->error_bound(0)) << what;
      expect_common(s, *u, what);
    }
  }
  // The supported range: the bound stays under ½ LSB of an 8-bit display up to n = 512 and under
  // 1 LSB up to n = 1024.
  EXPECT_LT(build("pow", material(512))->error_bound(0), 0.5 / 255);
  EXPECT_LT(build("pow", material(1024))->error_bound(0), 1.0 / 255);
}

TEST(ExhaustiveUnits, LutWithinStatedBound) {
  for (double n : kShininess) {
    for (int bits : {4, 6, 8}) {
      for (const char* skip : {"on", "off"}) {
        const auto u = build("lut:bits=" + std::to_string(bits) + ",skip=" + skip, material(n));
        const Sweep s = sweep(*u, 0, n);
        const std::string what = u->canonical_spec() + " n=" + std::to_string(n);
        EXPECT_LE(s.max_abs_vs_pow, u->error_bound(0)) << what;
        // The datapath against the exact interpolation of its rounded entries: one final rounding.
        EXPECT_LE(s.max_ulps, 0.5 + 1e-9) << what;
        expect_common(s, *u, what);
      }
    }
  }
}

TEST(ExhaustiveUnits, SfuWithinStatedBound) {
  for (double n : kShininess) {
    for (const char* skip : {"on", "off"}) {
      const auto u = build(std::string("sfu:skip=") + skip, material(n));
      const Sweep s = sweep(*u, 0, n);
      const std::string what = u->canonical_spec() + " n=" + std::to_string(n);
      EXPECT_LE(s.max_abs_vs_pow, u->error_bound(0)) << what;
      EXPECT_LE(s.max_ulps, u->datapath_bound_ulps(0) + 1e-9) << what;
      expect_common(s, *u, what);
    }
  }
  // What the hardware gives up to n = 1000: well inside ½ LSB of an 8-bit display.
  EXPECT_LT(build("sfu", material(1000))->error_bound(0), 0.1 / 255);
}

// pwp at its default and at eleven other specs: every segment count from one segment to 2^10,
// every degree, skip off (the span is all of [0, 1]), narrow and wide outputs, given coefficient
// widths and guards (a guard of 0 at degree 3 is refused where its output would step back: it is
// not in the list).
const char* const kPwpSpecs[] = {"pwp",
                                 "pwp:degree=1",
                                 "pwp:degree=3",
                                 "pwp:segments=0,degree=3",
                                 "pwp:segments=2",
                                 "pwp:segments=6,degree=1",
                                 "pwp:segments=8",
                                 "pwp:segments=10,degree=3",
                                 "pwp:skip=off",
                                 "pwp:skip=off,segments=6,degree=3",
                                 "pwp:out=uq1.10,segments=3",
                                 "pwp:out=uq1.20,coef_frac=24,degree=3",
                                 "pwp:coef_frac=15,guard=0,degree=1",
                                 "pwp:guard=8,degree=3"};

TEST(ExhaustiveUnits, PwpWithinBudgetMonotone) {
  for (const char* spec : kPwpSpecs) {
    for (double n : kShininess) {
      const auto u = build(spec, material(n));
      const Sweep s = sweep(*u, 0, n);
      const std::string what = u->canonical_spec() + " n=" + std::to_string(n);
      EXPECT_LE(s.max_ulps, u->datapath_bound_ulps(0) + 1e-9) << what;
      EXPECT_LT(s.max_ulps, 1.0) << what;
      expect_common(s, *u, what);
    }
  }
}

TEST(ExhaustiveUnits, PwpDegreeOneIsCorrectlyRounded) {
  // No inner rounding: the interpolation is formed exactly and rounded once, as lut's.
  for (double n : kShininess) {
    const auto u = build("pwp:degree=1", material(n));
    EXPECT_EQ(u->datapath_bound_ulps(0), 0.5);
    EXPECT_LE(sweep(*u, 0, n).max_ulps, 0.5 + 1e-9) << n;
  }
}

TEST(ExhaustiveUnits, PwpRepairedSegmentsStayMonotone) {
  // Over all of [0, 1] (skip=off) the segments far below the lobe rise by less than their minimax
  // error, and a concave lobe (n < 1) is steep at t = 0: some quantized segments are not monotone
  // there and are blended towards their chord. The unit says how many, and stays monotone.
  int blended = 0;
  for (double n : {0.3, 50.0}) {
    const auto u = build("pwp:skip=off", material(n));
    blended += u->describe()["slots"][0]["blended_segments"].get<int>();
    const Sweep s = sweep(*u, 0, n);
    EXPECT_LE(s.max_ulps, u->datapath_bound_ulps(0) + 1e-9) << n;
    expect_common(s, *u, "pwp:skip=off n=" + std::to_string(n));
  }
  EXPECT_GT(blended, 0);
}

TEST(ExhaustiveUnits, PwpDefaultWithinOneDisplayLsb) {
  // The default (16 quadratic segments over the span) against t^n itself: under 1 LSB of an 8-bit
  // display for every shininess of the list, and more segments or a higher degree do better.
  for (double n : kShininess) {
    const double def = sweep(*build("pwp", material(n)), 0, n).max_abs_vs_pow;
    EXPECT_LT(def, 1.0 / 255) << n;
    if (n < 3) continue;  // t^n with n <= degree: every fit is exact up to rounding
    EXPECT_LT(sweep(*build("pwp:degree=3", material(n)), 0, n).max_abs_vs_pow, def) << n;
    EXPECT_LT(sweep(*build("pwp:segments=6", material(n)), 0, n).max_abs_vs_pow, def) << n;
  }
}

TEST(ExhaustiveUnits, SkipInsideFloatTestAndImperceptible) {
  // Every unit's comparator threshold T: each real t that rounds to a code <= T is <= tau (the
  // float test skips it too), the unit's own output there is at most eps_K / c_y, and T is the
  // largest such code (either the float test's bound or the next code's output is visible).
  for (const char* name :
       {"pow", "schlick", "hast", "horner", "lut", "sfu", "pwp", "pwp:domain=log"}) {
    for (double n : kShininess) {
      for (double cy : {1.0, 0.01}) {
        const MaterialParams m = material(n, cy);
        const auto u = build(name, m);
        const std::int64_t top = u->tau_raw(0);
        const std::string what = std::string(name) + " n=" + std::to_string(n);
        ASSERT_GE(top, 0) << what;
        const double level = 1e-3 / cy;
        for (std::int64_t t = 0; t <= top; ++t) {
          ASSERT_LE((static_cast<double>(t) + 0.5) * std::ldexp(1.0, -15), m.tau) << what;
          ASSERT_LE(std::ldexp(static_cast<double>(u->eval(0, t)), -15), level) << what;
        }
        const bool float_bound = (static_cast<double>(top) + 1.5) * std::ldexp(1.0, -15) > m.tau;
        const bool visible_next = std::ldexp(static_cast<double>(u->eval(0, top + 1)), -15) > level;
        EXPECT_TRUE(float_bound || visible_next) << what << ": threshold " << top << " not tight";
      }
    }
  }
}

TEST(ExhaustiveUnits, AlwaysSkipWhenLobeInvisible) {
  for (const char* name :
       {"pow", "schlick", "hast", "horner", "lut", "sfu", "pwp", "pwp:domain=log"}) {
    const auto u = build(name, material(50, 5e-4));  // c_y < eps
    for (std::int64_t t = 0; t < kInputs; ++t) ASSERT_EQ(u->eval_with_skip(0, t), 0) << name;
  }
}

}  // namespace
}  // namespace glint
