// pwp's domain=log (units/pwp/log_datapath.h): its contract over every input code of in=uq1.16
// (2^16 + 1 codes) for the default and six other specs at n from 1 to 512, monotone, exact at 0
// and 1; tables shared by every material (only n per slot), widths from the output's target, the
// cost inventory's parts, and domain=t untouched by the key.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "code_sweep.h"
#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"
#include "units/pwp/datapath.h"

namespace glint {
namespace {

MaterialParams material(double n, double eps = 1e-3) {
  const TauResult t = tau_power(n, eps, 1.0);
  MaterialParams m{n, t.never_skip ? -1.0 : t.tau, t.always_skip};
  m.level = t.eps;
  m.name = "m" + std::to_string(static_cast<int>(n));
  return m;
}

std::unique_ptr<SpecularUnit> build(const std::string& spec, const std::vector<double>& ns) {
  std::vector<MaterialParams> slots;
  for (double n : ns) slots.push_back(material(n));
  return make_unit(parse_unit_spec(spec), slots);
}

using Sweep = test::CodeSweep;

// Every code of the input format, 0 .. 1.0.
Sweep sweep(const SpecularUnit& u, std::size_t slot, double n) {
  return test::sweep_codes(u, slot, n, u.in_format().raw_one());
}

const double kShininess[] = {1, 2, 5, 20, 50, 128, 512};

// The default and six others: one segment, 2^8 and 2^10 segments, every degree, narrow and wide
// outputs, skip off (t from the first code), a wider n register.
const char* const kSpecs[] = {"pwp:domain=log,in=uq1.16",
                              "pwp:domain=log,in=uq1.16,segments=0,degree=3",
                              "pwp:domain=log,in=uq1.16,segments=6,degree=1",
                              "pwp:domain=log,in=uq1.16,segments=8,degree=3,out=uq1.20",
                              "pwp:domain=log,in=uq1.16,segments=2,out=uq1.10",
                              "pwp:domain=log,in=uq1.16,skip=off,segments=10,degree=1",
                              "pwp:domain=log,in=uq1.16,n=uq14.6,out=uq1.12"};

TEST(PwpLog, WithinBudgetMonotoneExactEnds) {
  for (const char* spec : kSpecs) {
    // Every n in one unit: one datapath group each, sharing the tables.
    const std::vector<double> ns(std::begin(kShininess), std::end(kShininess));
    const auto u = build(spec, ns);
    for (std::size_t slot = 0; slot < ns.size(); ++slot) {
      const Sweep s = sweep(*u, slot, ns[slot]);
      const std::string what = u->canonical_spec() + " n=" + std::to_string(ns[slot]);
      EXPECT_LE(s.max_ulps, u->datapath_bound_ulps(slot) + 1e-9) << what;
      EXPECT_LE(u->datapath_bound_ulps(slot), 0.75 + 1e-12) << what;  // the widths' target
      EXPECT_EQ(s.first_nonmonotone, -1)
          << what << ": not monotone at raw t " << s.first_nonmonotone;
      EXPECT_EQ(s.nonzero_skipped, 0) << what;
      EXPECT_EQ(s.at_one, u->out_format().raw_one()) << what;
      EXPECT_EQ(u->eval(slot, 0), 0) << what;
    }
  }
}

TEST(PwpLog, DefaultWithinOneDisplayLsbUpTo512) {
  // 16 quadratic segments for lg2 and for ex2: under 1 LSB of an 8-bit display against t^n for
  // n up to 512, and more segments do better where the approximation dominates (large n).
  for (double n : kShininess) {
    const double def = sweep(*build("pwp:domain=log,in=uq1.16", {n}), 0, n).max_abs_vs_pow;
    EXPECT_LT(def, 1.0 / 255) << n;
    if (n < 50) continue;
    const double more =
        sweep(*build("pwp:domain=log,in=uq1.16,segments=6", {n}), 0, n).max_abs_vs_pow;
    EXPECT_LT(more, def) << n;
  }
}

TEST(PwpLog, TablesSharedOnlyNPerSlot) {
  PwpConfig c;
  c.log_domain = true;
  const PwpUnit a(c, material(5)), b(c, material(300));
  const PwpLogTables &ta = a.log_path()->tables(), &tb = b.log_path()->tables();
  EXPECT_EQ(ta.lg, tb.lg);
  EXPECT_EQ(ta.ex, tb.ex);
  EXPECT_NE(a.log_path()->n_raw(), b.log_path()->n_raw());
  // Neighbouring segments meet: Lg(0) = 0, Lg(1) = 1.0 and Ex(0) = 1.0, Ex(1) = 2.0 exactly.
  const std::size_t st = ta.stride;
  EXPECT_EQ(ta.lg[0], 0);
  EXPECT_EQ(ta.ex[0], std::int64_t{1} << ta.fe);
  for (const auto* tab : {&ta.lg, &ta.ex}) {
    const int frac = tab == &ta.lg ? ta.fl : ta.fe;
    const std::size_t count = tab->size() / st;
    for (std::size_t k = 0; k < count; ++k) {
      std::int64_t end = 0;
      for (std::size_t j = 0; j < st; ++j) end += (*tab)[k * st + j];
      const std::int64_t next = k + 1 < count ? (*tab)[(k + 1) * st]
                                              : (tab == &ta.lg ? 1 : 2) * (std::int64_t{1} << frac);
      EXPECT_EQ(end, next) << k;
    }
  }
  // One unit of three materials: the description says n is all a slot holds, and the group of
  // each slot has the same table contents (one copy in the cost inventory: ROMs).
  const auto u = build("pwp:domain=log,tables=ram", {5, 50, 300});
  const nlohmann::json d = u->describe();
  for (const auto& slot : d["slots"]) {
    EXPECT_EQ(slot["domain"], "log");
    EXPECT_NE(slot["per_slot"].get<std::string>().find("n only"), std::string::npos);
  }
  EXPECT_TRUE(d["elaboration"].contains("n_register"));
}

TEST(PwpLog, WidthsFollowTheTarget) {
  // fl = out + 3 + n's integer bits + clog2(d); fy = out + 3; fe = out + 2 (3 at degree 3).
  PwpConfig c;
  c.log_domain = true;
  const PwpLogWidths w = pwp_log_widths(pwp_log_spec(c));
  EXPECT_EQ(w.fl, 15 + 3 + 10 + 1);
  EXPECT_EQ(w.fy, 18);
  EXPECT_EQ(w.fe, 17);
  c.n_format = uq(14, 4);
  c.degree = 3;
  c.out = uq(1, 12);
  const PwpLogWidths w3 = pwp_log_widths(pwp_log_spec(c));
  EXPECT_EQ(w3.fl, 12 + 3 + 14 + 2);
  EXPECT_EQ(w3.fe, 15);
}

TEST(PwpLog, CostInventoryAndLatency) {
  for (int d = 1; d <= 3; ++d) {
    const auto u = build("pwp:domain=log,degree=" + std::to_string(d), {20, 50, 80});
    EXPECT_EQ(u->describe()["timing"]["latency"], 2 * d + 3);
    const UnitCost c = unit_cost(*u);
    int lzd = 0, horner_mul = 0, n_mul = 0, shift_out = 0, roms = 0, n_tables = 0;
    for (const Primitive& p : c.inventory) {
      lzd += p.kind == "lzd";
      horner_mul += p.kind == "multiplier" && p.where.find("acc x") != std::string::npos;
      n_mul += p.kind == "multiplier" && p.where.find("n log2 t") != std::string::npos;
      shift_out += p.kind == "shifter" && p.where.find("-yi") != std::string::npos;
      roms += p.where.find("(ROM, every material)") != std::string::npos;
      n_tables += p.where.find("n table") != std::string::npos;
      if (p.where.find("(ROM, every material)") != std::string::npos) {
        EXPECT_EQ(p.count, 1);
      }
    }
    EXPECT_EQ(lzd, 1);
    EXPECT_EQ(horner_mul, 2 * d);  // two Horner evaluators
    EXPECT_EQ(n_mul, 1);
    EXPECT_EQ(shift_out, 1);
    EXPECT_EQ(roms, 2 * (d + 1));  // every coefficient of lg2 and of ex2
    EXPECT_EQ(n_tables, 1);
  }
  // Materials add only n: three materials cost the log domain less than they cost domain=t.
  const auto area = [](const std::string& spec, const std::vector<double>& ns) {
    return unit_cost(*build(spec, ns)).area_ge;
  };
  const double log_growth =
      area("pwp:domain=log,tables=ram", {20, 50, 80}) - area("pwp:domain=log,tables=ram", {50});
  const double t_growth = area("pwp:tables=ram", {20, 50, 80}) - area("pwp:tables=ram", {50});
  EXPECT_LT(log_growth, t_growth);
}

TEST(PwpLog, DomainTUnchanged) {
  // The key at its default writes nothing: domain=t's canonical spec keeps its bytes.
  EXPECT_EQ(build("pwp", {50})->canonical_spec(), build("pwp:domain=t", {50})->canonical_spec());
  EXPECT_EQ(build("pwp:domain=t", {50})->canonical_spec().find("domain"), std::string::npos);
  EXPECT_NE(build("pwp:domain=log", {50})->canonical_spec().find("domain=log"), std::string::npos);
}

}  // namespace
}  // namespace glint
