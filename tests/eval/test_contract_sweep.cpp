// The contract's sweep beyond kExactInputBits (eval/contract_sweep.h): the enclosure turns the
// sampled codes into bounds, and where it refines to the end, into the exact maxima over every
// code.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

#include "eval/contract.h"
#include "eval/contract_sweep.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "test_support.h"
#include "units/catalogue.h"

namespace glint {
namespace {

struct Parts {
  double input = 0, parameter = 0, approximation = 0;
};

// Every code one by one: the definition the sweep must meet.
Parts brute_force(const SlotFunctions& fn, std::int64_t first, std::int64_t one, double h) {
  Parts p;
  for (std::int64_t c = first; c <= one; ++c) {
    const double t = static_cast<double>(c) * h;
    const double m = fn.model(c), f = fn.float_model(t), r = fn.ref(t);
    const double bottom = c == 0 ? fn.ref(-1.0) : fn.ref(t - 0.5 * h);
    p.input = std::max({p.input, r - bottom, fn.ref(t + 0.5 * h) - r});
    p.parameter = std::max(p.parameter, std::fabs(m - f));
    p.approximation = std::max(p.approximation, std::fabs(f - r));
  }
  return p;
}

// The old estimate: the evenly spaced codes alone (no 1.0 unless the step lands on it).
Parts sampled(const SlotFunctions& fn, std::int64_t first, std::int64_t one, double h,
              std::int64_t limit) {
  const std::int64_t step = (one - first + 1 + limit - 1) / limit;
  Parts p;
  for (std::int64_t c = first; c <= one; c += step) {
    const double t = static_cast<double>(c) * h;
    const double m = fn.model(c), f = fn.float_model(t), r = fn.ref(t);
    p.parameter = std::max(p.parameter, std::fabs(m - f));
    p.approximation = std::max(p.approximation, std::fabs(f - r));
  }
  return p;
}

// A table of t^n rounded to 2^-12 read by linear interpolation (model), the exact chord (float
// model) and t^n: monotone, with errors that peak between any coarse samples.
SlotFunctions synthetic(double n, int in_bits) {
  const double h = std::ldexp(1.0, -in_bits);
  const auto chord = [n](double t, bool rounded) {
    const double seg = 1.0 / 64, k = std::min(std::floor(t / seg), 63.0);
    const auto node = [&](double x) {
      const double v = std::pow(x, n);
      return rounded ? std::round(std::ldexp(v, 12)) / 4096 : v;
    };
    const double a = node(k * seg), b = node((k + 1) * seg);
    return a + (b - a) * (t / seg - k);
  };
  return {[=](std::int64_t c) { return chord(static_cast<double>(c) * h, true); },
          [=](double t) { return chord(std::clamp(t, 0.0, 1.0), false); },
          [=](double t) { return t > 0 ? std::pow(std::min(t, 1.0), n) : 0.0; }};
}

TEST(ContractSweep, RefinedEnclosureGivesTheExactMaxima) {
  const int bits = 18;
  const std::int64_t one = std::int64_t{1} << bits, first = one / 2;
  const double h = std::ldexp(1.0, -bits);
  int short_of_it = 0;
  for (const double n : {0.5, 3.0, 50.0}) {
    SCOPED_TRACE(n);
    const SlotFunctions fn = synthetic(n, bits);
    const Parts truth = brute_force(fn, first, one, h);
    const SweptParts got = sweep_parts(fn, first, one, h, true, 1025);
    EXPECT_TRUE(got.certified);
    EXPECT_TRUE(got.tight);
    EXPECT_EQ(got.parameter, truth.parameter);
    EXPECT_EQ(got.approximation, truth.approximation);
    EXPECT_EQ(got.input, truth.input);
    EXPECT_LT(got.evaluations, static_cast<std::uint64_t>(one - first + 1));
    // The samples alone fall short of the maxima.
    const Parts old = sampled(fn, first, one, h, 1025);
    short_of_it += old.parameter < truth.parameter;
    short_of_it += old.approximation < truth.approximation;
  }
  EXPECT_GT(short_of_it, 0);
}

TEST(ContractSweep, OutOfBudgetTheEnclosuresStillBound) {
  const int bits = 18;
  const std::int64_t one = std::int64_t{1} << bits, first = 0;
  const double h = std::ldexp(1.0, -bits);
  const SlotFunctions fn = synthetic(50.0, bits);
  const Parts truth = brute_force(fn, first, one, h);
  const SweptParts got = sweep_parts(fn, first, one, h, true, 1025, 64);
  EXPECT_TRUE(got.certified);
  EXPECT_FALSE(got.tight);
  EXPECT_LE(got.evaluations, 1025u + 2 + 64);
  EXPECT_GE(got.parameter, truth.parameter);
  EXPECT_GE(got.approximation, truth.approximation);
  EXPECT_GE(got.input, truth.input);
}

TEST(ContractSweep, NotMonotoneStaysAnEstimate) {
  const int bits = 16;
  const std::int64_t one = std::int64_t{1} << bits;
  const SweptParts got =
      sweep_parts(synthetic(5.0, bits), 0, one, std::ldexp(1.0, -bits), false, 1025);
  EXPECT_FALSE(got.certified);
  // Every code at most sample_limit: exhaustive, monotone or not.
  EXPECT_TRUE(
      sweep_parts(synthetic(5.0, bits), 0, one, std::ldexp(1.0, -bits), false, one + 1).certified);
}

// A wide-input slot of a real unit: its certified bound against every code above the threshold.
struct WideCase {
  const char* spec;
  const char* material;
};

TEST(ContractSweep, WideInputSlotsBoundEveryCode) {
  int short_of_it = 0;  // parts whose old estimate (the evenly spaced codes) missed the maximum
  for (const WideCase& w :
       {WideCase{"lut:in=uq1.24", "material m specular=1,1,1 lobe=phong shininess=50"},
        WideCase{"horner:in=uq1.22", "material m specular=1,1,1 lobe=blinn shininess=20"},
        WideCase{"pow:in=uq1.22", "material m specular=0.8,0.8,0.8 lobe=gaussian roughness=0.3"}}) {
    SCOPED_TRACE(w.spec);
    std::istringstream text(std::string("glint-vectors 1\neps 1e-3\nlights 1\n") + w.material +
                            "\ncolumns t material\ndata\n");
    VectorReader reader(text, "wide");
    const SlotMap slots = make_slots(reader.header());
    const std::unique_ptr<SpecularUnit> unit = make_unit(parse_unit_spec(w.spec), slots);
    ASSERT_TRUE(unit->models_monotone(0));
    const auto start = std::chrono::steady_clock::now();
    const SlotContract c = slot_contract(*unit, 0, slots);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: contract %.0f ms\n", w.spec, ms);
    EXPECT_TRUE(c.exact);
    const QFormat in = unit->in_format();
    const std::int64_t one = in.raw_one(), first = std::min(c.threshold_raw, one) + 1;
    ASSERT_GT(one - first + 1, (std::int64_t{1} << kExactInputBits) + 1) << "not sampled";
    const SlotFunctions fn{[&](std::int64_t code) { return unit->model(0, code); },
                           [&](double t) { return unit->float_model(0, t); },
                           [&](double t) { return reference_value(slots, 0, std::max(t, -1.0)); }};
    const Parts truth = brute_force(fn, first, one, in.ulp());
    EXPECT_GE(c.bound.parameter, truth.parameter);
    EXPECT_GE(c.bound.approximation, truth.approximation);
    EXPECT_GE(c.bound.input, truth.input);
    const Parts old = sampled(fn, first, one, in.ulp(), (std::int64_t{1} << kExactInputBits) + 1);
    short_of_it += old.parameter < truth.parameter;
    short_of_it += old.approximation < truth.approximation;
    std::printf(
        "  parameter: old %.6g, true %.6g, bound %.6g; approximation: old %.6g, true "
        "%.6g, bound %.6g\n",
        old.parameter, truth.parameter, c.bound.parameter, old.approximation, truth.approximation,
        c.bound.approximation);
  }
  EXPECT_GT(short_of_it, 0);
}

// eval's text tables mark an uncertified slot's bounds "~", with the note under the table; a
// certified slot's are stated unmarked.
TEST(EvalTable, MarksEstimatedBounds) {
  UnitStats s;
  s.name = "x";
  SlotContract c;
  c.bound.approximation = 0.01;
  c.exact = false;
  s.slots = {c};
  for (const std::string& text : {format_eval_table({s}), format_parts_table({s})}) {
    EXPECT_NE(text.find("~2.55"), std::string::npos) << text;
    EXPECT_NE(text.find(kEstimateNote), std::string::npos) << text;
  }
  s.slots[0].exact = true;
  EXPECT_EQ(format_eval_table({s}).find('~'), std::string::npos);
  EXPECT_EQ(format_parts_table({s}).find('~'), std::string::npos);
}

}  // namespace
}  // namespace glint
