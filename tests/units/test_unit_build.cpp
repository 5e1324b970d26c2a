// How units are built for many materials: pow's tables shared by every slot, lut's tables kept
// only where the inputs read them and its chord error found without visiting every segment. Each
// shortcut is held to the straightforward construction it replaces: the same outputs on every
// input code, the same staged register values, the same stated bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/horner/slots.h"
#include "units/lut/datapath.h"
#include "units/pow/datapath.h"

namespace glint {
namespace {

constexpr double kEps = 1e-3;

MaterialParams material(double n, double c_y) {
  const TauResult t = tau_power(n, kEps, c_y);
  MaterialParams m(n, t.tau, t.always_skip);
  m.level = kEps / c_y;
  return m;
}

// Materials as the build benchmark draws them (n log-uniform in [1, 1e4], c_y in [0.01, 1]), and
// a few from below 1 and around 2, where lut's chord error changes the end it is largest at.
std::vector<MaterialParams> random_materials(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> log_n(-0.5, 4.0), cy(0.01, 1.0);
  std::vector<MaterialParams> out;
  for (std::size_t i = 0; i < count; ++i)
    out.push_back(material(std::pow(10.0, log_n(rng)), cy(rng)));
  return out;
}

std::vector<MaterialParams> edge_materials() {
  std::vector<MaterialParams> out;
  // n = 2 +- 1e-9: every segment's chord error is the same to ~1e-9, below the rounding of its
  // computation, so the largest computed value may be anywhere and lut's walk must visit them all.
  for (double n : {0.3, 0.7, 1.0, 1.5, 1.99, 2.0 - 1e-9, 2.0, 2.0 + 1e-9, 2.01, 2.5, 7.0, 50.0,
                   300.0, 2000.0, 9000.0}) {
    for (double c_y : {1.0, 0.05}) out.push_back(material(n, c_y));
  }
  out.push_back(material(20.0, 5e-4));  // c_y <= eps: always skipped
  return out;
}

// Every input code of a 16-bit input register (uq1.15 reaches 2.0; codes above 1.0 clamp).
constexpr std::int64_t kCodes = std::int64_t{1} << 16;

// Records a datapath's staged values by (position, register).
struct Recorder {
  static constexpr bool kActive = true;
  std::array<std::int64_t, 32>* values;
  void operator()(int position, int reg, std::int64_t value) const {
    (*values)[static_cast<std::size_t>(position * 8 + reg)] = value;
  }
};

// ---- pow: one set of tables per unit --------------------------------------------------------

TEST(PowBuild, SlotsShareOneSetOfTables) {
  const std::vector<MaterialParams> slots = random_materials(5, 1);
  const std::vector<PowUnit> units = build_pow_units(PowConfig{}, slots);
  ASSERT_EQ(units.size(), slots.size());
  for (const PowUnit& u : units) EXPECT_EQ(u.tables().get(), units[0].tables().get());
  // A unit built alone has its own tables, with the same entries and error terms.
  const PowUnit alone(PowConfig{}, slots[0]);
  EXPECT_NE(alone.tables().get(), units[0].tables().get());
  EXPECT_EQ(alone.tables()->log_table, units[0].tables()->log_table);
  EXPECT_EQ(alone.tables()->exp_table, units[0].tables()->exp_table);
  EXPECT_EQ(alone.log_error(), units[0].log_error());
  EXPECT_EQ(alone.exp_error(), units[0].exp_error());
}

TEST(PowBuild, SharedTablesEqualOwnTablesOnEveryInput) {
  const std::vector<MaterialParams> slots = random_materials(8, 2);
  for (const PowConfig& cfg :
       {PowConfig{}, PowConfig{kDefaultIn, kDefaultOut, uq(14, 4), 5, 20, 18, 4, 22, true}}) {
    const std::vector<PowUnit> units = build_pow_units(cfg, slots);
    for (std::size_t s = 0; s < slots.size(); ++s) {
      const PowUnit alone(cfg, slots[s]);
      EXPECT_EQ(units[s].error_bound(), alone.error_bound()) << "slot " << s;
      for (std::int64_t t = 0; t < kCodes; ++t) {
        ASSERT_EQ(units[s].eval(t), alone.eval(t)) << "slot " << s << " t " << t;
      }
    }
  }
}

TEST(PowBuild, RefusesTablesOfOtherKeys) {
  const PowUnit a(PowConfig{}, material(10, 1));
  PowConfig other;
  other.log_bits = 7;
  EXPECT_THROW(PowUnit(other, material(10, 1), a.tables()), std::invalid_argument);
}

TEST(PowBuild, RefusalStillNamesTheSlot) {
  std::vector<MaterialParams> slots = random_materials(3, 3);
  slots[2].shininess = 1e6;  // outside the n register
  slots[2].name = "material 'huge'";
  try {
    build_pow_units(PowConfig{}, slots);
    FAIL() << "built a unit for n = 1e6";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("material 'huge'"), std::string::npos) << e.what();
  }
}

// ---- lut: the straightforward construction it must equal -------------------------------------

// The full ROM of 2^bits + 1 entries (and the padding copy), every one from std::pow, indexed as
// the hardware does: ((t - t0) << pad) >> r_bits.
struct FullLut {
  std::vector<std::int64_t> table;
  std::int64_t t0 = 0, one_in = 0, one_out = 0, r_mask = 0;
  int pad = 0, r_bits = 0, out_shift = 0;
  double chord = 0;

  FullLut(const LutConfig& c, const LutUnit& u, double n) {
    const int fi = c.in.frac_bits, tf = u.config().table_frac;
    t0 = u.t0_raw();
    one_in = c.in.raw_one();
    one_out = c.out.raw_one();
    const int v_bits = fi - u.span_log2();
    r_bits = std::max(0, v_bits - c.bits);
    pad = std::max(0, c.bits - v_bits);
    r_mask = (std::int64_t{1} << r_bits) - 1;
    out_shift = r_bits + tf - c.out.frac_bits;
    const std::size_t entries = (std::size_t{1} << c.bits) + 1;
    const double t0d = std::ldexp(static_cast<double>(std::min(t0, one_in)), -fi);
    const double h = (1.0 - t0d) / static_cast<double>(entries - 1);
    for (std::size_t j = 0; j < entries; ++j) {
      const double t = j + 1 == entries ? 1.0 : t0d + h * static_cast<double>(j);
      table.push_back(std::llround(std::ldexp(std::pow(t, n), tf)));
    }
    table.push_back(table.back());
    // Every segment's chord error, the extreme where n t^(n-1) equals the chord slope.
    for (std::size_t j = 0; j + 1 < entries && h > 0; ++j) {
      const double a = t0d + h * static_cast<double>(j), b = a + h;
      const double fa = std::pow(a, n), s = (std::pow(b, n) - fa) / h;
      double x = n == 1.0 ? a : std::pow(s / n, 1.0 / (n - 1.0));
      x = std::isfinite(x) ? std::clamp(x, a, b) : a;
      chord = std::max(chord, std::fabs(fa + s * (x - a) - std::pow(x, n)));
    }
  }
  // Staged values as Recorder lays them out; returns the result.
  std::int64_t run(std::int64_t t_raw, std::array<std::int64_t, 32>& v) const {
    if (t_raw <= t0) return v[16] = 0;
    const std::int64_t t = std::min(t_raw, one_in);
    const std::int64_t w = (t - t0) << pad;
    const std::int64_t i = w >> r_bits, r = w & r_mask;
    const std::int64_t a = table[static_cast<std::size_t>(i)];
    const std::int64_t b = table[static_cast<std::size_t>(i) + 1];
    v[8] = i;
    v[9] = r;
    v[10] = a;
    v[11] = b;
    const std::int64_t q =
        ((a << r_bits) + (b - a) * r + ((std::int64_t{1} << out_shift) >> 1)) >> out_shift;
    return v[16] = std::min(q, one_out);
  }
};

void expect_lut_equals_full(const LutConfig& c, const MaterialParams& m) {
  SCOPED_TRACE(testing::Message() << "bits " << c.bits << " skip " << c.skip << " n " << m.shininess
                                  << " tau " << m.tau);
  const LutUnit u(c, m);
  const FullLut full(c, u, m.shininess);
  EXPECT_EQ(u.chord_error(), full.chord);  // exactly: same segments, same arithmetic
  EXPECT_EQ(u.entries(), full.table.size() - 1);
  for (std::int64_t j = 0; j < static_cast<std::int64_t>(full.table.size()); ++j) {
    ASSERT_EQ(u.entry(j), full.table[static_cast<std::size_t>(j)]) << "entry " << j;
  }
  for (std::int64_t t = 0; t < kCodes; ++t) {
    std::array<std::int64_t, 32> got{}, want{};
    const std::int64_t result = u.run(t, Recorder{&got});
    ASSERT_EQ(result, full.run(t, want)) << "t " << t;
    ASSERT_EQ(u.eval(t), result) << "t " << t;
    ASSERT_EQ(got, want) << "staged values at t " << t;
  }
}

TEST(LutBuild, EqualsFullTableConstruction) {
  for (int bits : {6, 12, 16}) {
    for (bool skip : {true, false}) {
      for (const MaterialParams& m : edge_materials()) {
        LutConfig c;
        c.bits = bits;
        c.skip = skip;
        c.table_frac = kDefaultOut.frac_bits + 2;
        expect_lut_equals_full(c, m);
      }
    }
  }
}

TEST(LutBuild, EqualsFullTableConstructionOnRandomMaterials) {
  for (const MaterialParams& m : random_materials(24, 4)) {
    LutConfig c;
    c.bits = 16;
    c.table_frac = kDefaultOut.frac_bits + 2;
    expect_lut_equals_full(c, m);
    c.bits = 6;
    expect_lut_equals_full(c, m);
  }
}

TEST(LutBuild, KeepsOnlyTheEntriesInputsRead) {
  LutConfig c;
  c.bits = 16;
  c.table_frac = kDefaultOut.frac_bits + 2;
  for (const MaterialParams& m : edge_materials()) {
    const LutUnit u(c, m);
    const int v_bits = c.in.frac_bits - u.span_log2();  // input codes in the span: 2^v_bits
    EXPECT_EQ(u.kept_entries(), (std::size_t{1} << std::min(c.bits, v_bits)) + 1) << m.shininess;
    EXPECT_LT(u.kept_entries(), u.entries()) << m.shininess;  // 16 bits > the 15 of uq1.15
  }
}

// ---- every unit: one build for many slots equals one build per slot ---------------------------

TEST(UnitBuild, ManySlotsEqualOneSlotAtATime) {
  std::vector<MaterialParams> slots = random_materials(12, 5);
  for (const MaterialParams& m : edge_materials()) slots.push_back(m);
  for (const char* spec : {"pow", "lut", "lut:bits=16", "schlick", "hast"}) {
    SCOPED_TRACE(spec);
    const auto all = make_unit(parse_unit_spec(spec), slots);
    const nlohmann::json all_slots = all->describe()["slots"];
    for (std::size_t s = 0; s < slots.size(); ++s) {
      const auto one = make_unit(parse_unit_spec(spec), {slots[s]});
      EXPECT_EQ(all->tau_raw(s), one->tau_raw(0)) << "slot " << s;
      const double b_all = all->error_bound(s), b_one = one->error_bound(0);
      EXPECT_TRUE(b_all == b_one || (std::isnan(b_all) && std::isnan(b_one))) << "slot " << s;
      EXPECT_EQ(all_slots[s], one->describe()["slots"][0]) << "slot " << s;
      for (std::int64_t t = 0; t < kCodes; ++t) {
        ASSERT_EQ(all->eval(s, t), one->eval(0, t)) << "slot " << s << " t " << t;
      }
    }
  }
}

// ---- the contract in code: key tables and declared cases -------------------------------------

// Every unit declares its co-simulation cases (kCosimCases, src/units/<unit>/<unit>.cpp): its
// defaults, a tables=ram case (the testbench loads the RAMs) and at least one other spec, names
// unique. Each builds, and its canonical spec builds the same unit again.
TEST(DeclaredCases, EveryUnitDeclaresCasesThatBuild) {
  const std::vector<MaterialParams> slots = {material(50.0, 1.0), material(300.0, 0.2),
                                             material(20.0, 5e-4)};
  for (const UnitInfo& u : unit_catalog()) {
    bool defaults = false, ram = false;
    std::vector<std::string> names;
    for (const CosimCase& c : u.cosim_cases) {
      SCOPED_TRACE(cosim_name(u, c));
      EXPECT_EQ(std::count(names.begin(), names.end(), c.name), 0) << "declared twice";
      names.emplace_back(c.name);
      defaults |= c.spec.empty();
      ram |= c.spec.find("tables=ram") != std::string_view::npos;
      EXPECT_NE(c.input.find("--vectors traces/"), std::string_view::npos);
      const auto unit = make_unit(parse_unit_spec(cosim_spec(u, c)), slots);
      const auto again = make_unit(parse_unit_spec(unit->canonical_spec()), slots);
      EXPECT_EQ(again->canonical_spec(), unit->canonical_spec());
      EXPECT_EQ(again->describe(), unit->describe());
    }
    EXPECT_TRUE(defaults) << u.name;
    EXPECT_TRUE(ram) << u.name;
    EXPECT_GE(u.cosim_cases.size(), 3u) << u.name;
  }
}

// The canonical spec is written from the key table: at the defaults it names keys of the table
// only, in the table's order, each at the default `glint units` lists (an `auto` key at what it
// resolved to); a key it leaves out is one whose default the canonical form omits.
TEST(KeyTables, CanonicalSpecFollowsTheTable) {
  const std::vector<MaterialParams> slots = {material(50.0, 1.0)};
  for (const UnitInfo& u : unit_catalog()) {
    SCOPED_TRACE(u.name);
    const UnitSpec canonical = parse_unit_spec(make_unit({u.name, {}}, slots)->canonical_spec());
    std::size_t i = 0;
    for (const auto& [key, value] : canonical.keys) {
      for (; i < u.keys.size() && u.keys[i].key != key; ++i) {
        // The ChoiceKeys the canonical form omits at their defaults (key_table.h): tables=rom,
        // horner's fit=best.
        const std::string& left_out = u.keys[i].default_value;
        EXPECT_TRUE(left_out == "none" || left_out == "rom" || left_out == "best")
            << u.keys[i].key << " left out";
      }
      ASSERT_LT(i, u.keys.size()) << key << ": not in the table, or out of its order";
      if (u.keys[i].default_value != "auto") {
        EXPECT_EQ(value, u.keys[i].default_value) << key;
      }
      ++i;
    }
  }
}

// ---- wide input formats: built or refused, promptly ------------------------------------------

// Every unit at input formats up to the 62-bit registers either builds or refuses the format with
// std::invalid_argument, in well under a second (Release). horner's guard search multiplied a
// short span by 2^k in 64 bits until it overflowed: at in=uq1.61 the loop never ended (found by
// the units fuzz harness's seeds, tests/fuzz/regressions/units/horner_wide_input_guard_hang).
TEST(WideInputs, EveryUnitBuildsOrRefusesPromptly) {
  const std::vector<MaterialParams> slots = {material(0.5, 1.0), material(50.0, 1.0),
                                             material(5000.0, 0.2), material(20.0, 5e-4)};
  for (const char* unit : {"pow", "schlick", "hast", "horner", "lut", "horner:domain=full",
                           "hast:match=minimax", "lut:skip=off,bits=16"}) {
    for (int f : {40, 52, 57, 60, 61, 62}) {
      const std::string spec =
          std::string(unit) +
          (std::string(unit).find(':') == std::string::npos ? ":in=uq1." : ",in=uq1.") +
          std::to_string(f);
      SCOPED_TRACE(spec);
      const auto start = std::chrono::steady_clock::now();
      try {
        make_unit(parse_unit_spec(spec), slots);
      } catch (const std::invalid_argument&) {
        // refused, naming the key or the register that cannot hold it
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      EXPECT_LT(seconds, 10.0);
    }
  }
}

// horner's fits are memoized per process: each fit, asked in a sequence where every step changes
// one field of the memo's key (so a field left out of it would return the previous step's fit),
// equals fit_power run afresh, and asking again returns the same.
TEST(HornerFitMemo, EveryFieldOfTheKeyTellsFitsApart) {
  struct Ask {
    HornerFitSpec spec;
    double n, tau, min_slope;
  };
  HornerFitSpec s;
  std::vector<Ask> asks = {{s, 37, 0.8, 0}};
  const auto then = [&](auto change) {
    Ask a = asks.back();
    change(a);
    asks.push_back(a);
  };
  then([](Ask& a) { a.spec.degree = 5; });
  then([](Ask& a) { a.spec.method = FitMethod::kLeastSquares; });
  then([](Ask& a) { a.spec.constrain = false; });
  then([](Ask& a) { a.n = 38; });
  then([](Ask& a) { a.tau = 0.81; });
  then([](Ask& a) { a.min_slope = 0.05; });
  then([](Ask& a) { a.spec.tau_domain = false; });
  for (int round = 0; round < 2; ++round)
    for (const Ask& a : asks) {
      SCOPED_TRACE(testing::Message() << "round " << round << ", degree " << a.spec.degree << ", n "
                                      << a.n << ", tau " << a.tau);
      const HornerCoefficients memo = fit_slot(a.spec, a.n, a.tau, a.min_slope);
      const FitResult fresh = fit_power(horner_fit_options(a.spec, a.n, a.tau, a.min_slope));
      EXPECT_EQ(memo.c, fresh.coeffs);
      EXPECT_EQ(memo.tau_domain, a.spec.tau_domain);
    }
}

}  // namespace
}  // namespace glint
