// pwp's key fit (units/pwp/fit_engine.h): per segment, Sollya's fpminimax fit replaces glint's
// rounded Remez fit where it is certainly better (fit=best) or wherever it is valid (fit=sollya).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fit/sollya_fit.h"
#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

MaterialParams material(double n) {
  const TauResult t = tau_power(n, 1e-3, 1.0);
  MaterialParams m(n, t.tau, t.always_skip);
  m.name = "m" + std::to_string(static_cast<int>(n));
  return m;
}

struct Built {
  std::unique_ptr<SpecularUnit> unit;
  nlohmann::json slot;
  double code_error = 0;  // max |model - t^n| over every input code above t0
};

Built build(const std::string& spec, const MaterialParams& m) {
  Built b;
  b.unit = make_unit(parse_unit_spec(spec), {m});
  b.slot = b.unit->describe().at("slots").at(0);
  const QFormat in = b.unit->in_format();
  for (std::int64_t code = b.slot.at("t0_raw").get<std::int64_t>() + 1; code <= in.raw_one();
       ++code)
    b.code_error = std::max(b.code_error, std::fabs(b.unit->model(0, code) -
                                                    std::pow(input_value(code, in), m.shininess)));
  return b;
}

// Every input code: eval within the datapath budget of model, non-decreasing, 0 at 0, 1.0 at 1.
void expect_contract(const Built& b, const std::string& what) {
  const QFormat in = b.unit->in_format(), out = b.unit->out_format();
  const double ulp = std::ldexp(1.0, -out.frac_bits);
  const double budget = b.unit->datapath_bound_ulps(0) * ulp * (1 + 1e-12);
  std::int64_t prev = 0;
  int steps_back = 0;
  double worst = 0;
  for (std::int64_t code = 0; code <= in.raw_one(); ++code) {
    const std::int64_t y = b.unit->eval(0, code);
    steps_back += y < prev;
    prev = y;
    worst = std::max(worst, std::fabs(std::ldexp(static_cast<double>(y), -out.frac_bits) -
                                      b.unit->model(0, code)));
  }
  EXPECT_EQ(steps_back, 0) << what;
  EXPECT_LE(worst, budget) << what;
  EXPECT_EQ(b.unit->eval(0, 0), 0) << what;
  EXPECT_EQ(b.unit->eval(0, in.raw_one()), out.raw_one()) << what;
}

// Every register of the stage layout, by name and format: the datapath's shape.
std::vector<std::string> registers(const SpecularUnit& u) {
  std::vector<std::string> r;
  for (const Stage& s : u.stages().stages())
    for (const StageRegister& g : s.registers)
      r.push_back(s.name + "." + g.name + " " + g.format.name());
  return r;
}

struct Case {
  double n;
  std::string keys;
};

// Six (n, segments, degree, coef_frac) cases at 16 input bits. fit=best is never worse than glint's
// over every input code, holds the contract exhaustively and stays monotone; its registers are
// glint's (cost and RTL unchanged); where it keeps Sollya's segments the slot says so, with a
// certified sup norm that Sollya recomputes here from no more than the slot's own figures. Sollya
// wins on some of them (few coefficient bits, degree 3).
TEST(PwpFitEngine, BestIsNoWorseThanGlint) {
  int slots_with_sollya = 0;
  for (const Case& c : {Case{50, "degree=3"}, Case{50, "degree=3,coef_frac=12"},
                        Case{20, "degree=3,segments=2"}, Case{128, "degree=2,coef_frac=13"},
                        Case{50, "degree=3,segments=6,skip=off"}, Case{8, "degree=2,segments=3"}}) {
    const std::string base = "pwp:in=uq1.16," + c.keys;
    SCOPED_TRACE(testing::Message() << "n " << c.n << ", " << base);
    const MaterialParams m = material(c.n);
    const Built glint = build(base + ",fit=glint", m);
    const Built best = build(base, m);
    EXPECT_EQ(glint.slot.at("fit_engine"), "glint");
    EXPECT_EQ(glint.slot.at("sollya_segments"), 0);
    EXPECT_LE(best.code_error, glint.code_error);
    expect_contract(best, base);
    EXPECT_EQ(registers(*glint.unit), registers(*best.unit));
    const int sollya = best.slot.at("sollya_segments").get<int>();
    EXPECT_LE(sollya, best.slot.at("fitted_segments").get<int>());
    EXPECT_EQ(best.slot.at("fit_engine"), sollya > 0 ? "sollya" : "glint");
    EXPECT_EQ(best.slot.contains("sup_norm"), sollya > 0);
    if (sollya > 0) {
      ++slots_with_sollya;
      EXPECT_LE(best.slot.at("sup_norm").at("lo").get<double>(),
                best.slot.at("sup_norm").at("hi").get<double>());
    }
  }
  EXPECT_GE(slots_with_sollya, 2);
}

// fit=sollya takes Sollya's fit on every segment where it is valid, better or not (fpminimax's
// lattice search is not always the grid's best point): the unit still holds its contract over
// every input code, stays monotone, and keeps glint's registers.
TEST(PwpFitEngine, SollyaHoldsTheContract) {
  for (const Case& c : {Case{50, "degree=3"}, Case{20, "degree=3,coef_frac=12,segments=3"}}) {
    const std::string base = "pwp:in=uq1.16," + c.keys;
    SCOPED_TRACE(testing::Message() << "n " << c.n << ", " << base);
    const MaterialParams m = material(c.n);
    const Built glint = build(base + ",fit=glint", m);
    const Built sollya = build(base + ",fit=sollya", m);
    expect_contract(sollya, base + ",fit=sollya");
    EXPECT_EQ(registers(*glint.unit), registers(*sollya.unit));
    EXPECT_GT(sollya.slot.at("sollya_segments").get<int>(), 0);
    EXPECT_EQ(sollya.slot.at("fit_engine"), "sollya");
  }
}

}  // namespace
}  // namespace glint
