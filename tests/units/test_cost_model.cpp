// The area / critical-path / energy proxies (src/cost_model.h): they follow each unit's datapath
// and widths, grow where the hardware grows, and the JSON form carries every field.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"
#include "units/lut/datapath.h"
#include "units/pow/datapath.h"
#include "units/slot_plan.h"

namespace glint {
namespace {

MaterialParams material(double n, double eps = 1e-3) {
  const TauResult t = tau_power(n, eps, 1.0);
  return MaterialParams{n, t.never_skip ? -1.0 : t.tau, t.always_skip};
}

// capacity > 0: a chip of that many slots and materials (--chip ram:materials=N,slots=N), whose n
// register is the key's whole format.
std::unique_ptr<SpecularUnit> build(const std::string& spec,
                                    const std::vector<double>& shininess = {50},
                                    std::size_t capacity = 0) {
  std::vector<MaterialParams> slots;
  for (double n : shininess) slots.push_back(material(n));
  SlotPlan plan = SlotPlan::per_slot(slots);
  plan.slot_capacity = plan.group_capacity = capacity;
  return make_unit(parse_unit_spec(spec), plan);
}

UnitCost cost(const std::string& spec, const std::vector<double>& shininess = {50}) {
  return unit_cost(*build(spec, shininess));
}

std::vector<const Primitive*> find(const UnitCost& c, const std::string& kind,
                                   const std::string& where_part = "") {
  std::vector<const Primitive*> out;
  for (const Primitive& p : c.inventory)
    if (p.kind == kind && p.where.find(where_part) != std::string::npos) out.push_back(&p);
  return out;
}

double area_where(const UnitCost& c, const std::string& where_part) {
  double a = 0;
  for (const Primitive& p : c.inventory)
    if (p.where.find(where_part) != std::string::npos) a += p.ge;
  return a;
}

const StageDelay& stage(const UnitCost& c, const std::string& name) {
  for (const StageDelay& s : c.stages)
    if (s.stage == name) return s;
  throw std::runtime_error("no stage " + name);
}

const std::vector<std::string> kUnits = {"schlick", "hast", "horner", "pow", "lut", "sfu", "pwp"};

TEST(CostModel, DelayFormulas) {
  // The fitted depths (cost_model.h): logarithmic in the width, never below one gate.
  const CostConstants& k = cost_constants();
  EXPECT_DOUBLE_EQ(adder_delay(16), k.add_depth0 + 4 * k.add_depth_log);
  EXPECT_GT(adder_delay(33), adder_delay(17));
  EXPECT_LT(adder_delay(41) - adder_delay(21), adder_delay(21) - adder_delay(4));
  EXPECT_GE(adder_delay(1), 1);
  EXPECT_DOUBLE_EQ(multiplier_delay(16, 18), multiplier_delay(18, 16));
  EXPECT_GT(multiplier_delay(18, 16), adder_delay(34));  // the tree before the final adder
  EXPECT_GT(multiplier_delay(33, 33), multiplier_delay(33, 17));
  // A row: the subtractor of the D + 1-bit remainder and its borrow, then the restore mux.
  EXPECT_EQ(divider_row_delay(33), adder_delay(35) + 1);
  EXPECT_EQ(table_delay(1), 0);  // a one-entry ROM is a constant
  EXPECT_GT(table_delay(257), table_delay(65));
  EXPECT_EQ(mux_delay(2), 1);  // one $_MUX_
  EXPECT_GT(mux_delay(8), mux_delay(4));
}

TEST(CostModel, RomCostFollowsContents) {
  // A constant or two-entry table is wiring; a ramp's low bits are address bits (free); random
  // contents cost more than a smooth table of the same size.
  EXPECT_EQ(rom_ge({5}, 8), 0);
  EXPECT_EQ(rom_ge({0, 255}, 8), 0);
  std::vector<std::int64_t> ramp, noise;
  std::uint64_t x = 1;
  for (int i = 0; i < 64; ++i) {
    ramp.push_back(i * 4);
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    noise.push_back(static_cast<std::int64_t>(x >> 56));
  }
  EXPECT_EQ(rom_ge(ramp, 8), 0);
  EXPECT_GT(rom_ge(noise, 8), 64 * 8 * 0.3);
  EXPECT_GT(multiplier_ge(24, 24, true), multiplier_ge(24, 24, false));
}

TEST(CostModel, InventoryIsConsistent) {
  const std::vector<std::string> specs = {"schlick",
                                          "schlick:divider=iterative",
                                          "schlick:skip=off",
                                          "hast",
                                          "hast:d=1",
                                          "hast:d=2",
                                          "horner",
                                          "horner:domain=full",
                                          "horner:degree=1",
                                          "pow",
                                          "lut",
                                          "lut:bits=3",
                                          "pwp",
                                          "pwp:degree=1",
                                          "pwp:degree=3,segments=6"};
  for (const auto& spec : specs) {
    for (const std::vector<double>& slots : {std::vector<double>{50}, {10, 50, 200}}) {
      SCOPED_TRACE(spec + " slots " + std::to_string(slots.size()));
      const UnitCost c = cost(spec, slots);
      ASSERT_FALSE(c.inventory.empty());
      double sum = 0;
      for (const Primitive& p : c.inventory) {
        EXPECT_GT(p.ge, 0) << p.kind << " " << p.where;
        EXPECT_GE(p.count, 1) << p.where;
        EXPECT_GT(p.width_a, 0) << p.where;
        EXPECT_FALSE(p.where.empty());
        sum += p.ge;
      }
      EXPECT_NEAR(c.area_ge, sum, 1e-9 * sum);
      ASSERT_FALSE(c.stages.empty());
      double worst = 0;
      for (const StageDelay& s : c.stages) {
        EXPECT_GE(s.delay, cost_constants().reg_delay) << s.stage;
        worst = std::max(worst, s.delay);
      }
      EXPECT_EQ(c.critical_path, worst);
      EXPECT_EQ(stage(c, c.critical_stage).delay, c.critical_path);
      EXPECT_EQ(c.stages.front().stage, "comparator");
      EXPECT_GT(c.ops_per_computed.at("reg_bits"), 0);
      EXPECT_GT(c.ops_per_request.at("reg_bits"), 0);
    }
  }
}

TEST(CostModel, StagesFollowTiming) {
  for (const auto& name : kUnits) {
    SCOPED_TRACE(name);
    const auto u = build(name);
    const UnitCost c = unit_cost(*u);
    // Comparator stage + one entry per unit stage.
    EXPECT_EQ(c.stages.size(), static_cast<std::size_t>(u->timing().latency) + 1);
    // No colour stage: the lane ends at the unit's last stage, as `glint rtl` writes it.
    for (const StageDelay& s : c.stages) EXPECT_EQ(s.stage.find("colour"), std::string::npos);
    for (const Primitive& p : c.inventory) EXPECT_EQ(p.where.find("colour"), std::string::npos);
  }
}

TEST(CostModel, AreaGrowsWithOutputWidth) {
  for (const auto& name : kUnits) {
    SCOPED_TRACE(name);
    const UnitCost wide = cost(name + ":out=uq1.15");
    const UnitCost narrow = cost(name + ":out=uq1.11");
    EXPECT_GT(wide.area_ge, narrow.area_ge);
    EXPECT_GE(wide.critical_path, narrow.critical_path);
  }
  // Where the output width sets the datapath width, the growth is far from marginal.
  EXPECT_GT(cost("schlick:out=uq1.15").area_ge, 1.15 * cost("schlick:out=uq1.11").area_ge);
  EXPECT_GT(cost("hast:out=uq1.15").area_ge, 1.3 * cost("hast:out=uq1.11").area_ge);
}

TEST(CostModel, AreaGrowsWithHastExponent) {
  double prev = 0;
  for (int d = 1; d <= 8; ++d) {
    const UnitCost c = cost("hast:d=" + std::to_string(d));
    EXPECT_GT(c.area_ge, prev) << "d = " << d;
    prev = c.area_ge;
    // d - 1 chain multipliers of (fh + 1)^2, fh = out.frac_bits + guard.
    const auto u = build("hast:d=" + std::to_string(d));
    const int fh = 15 + u->describe()["config"]["guard"].get<int>();
    const auto chain = find(c, "multiplier", "chain");
    ASSERT_EQ(chain.size(), static_cast<std::size_t>(d - 1));
    for (const Primitive* p : chain) {
      EXPECT_EQ(p->width_a, fh + 1);
      EXPECT_EQ(p->width_b, fh + 1);
    }
    EXPECT_EQ(c.ops_per_computed.at("mul"), d);  // u scaler + chain
  }
}

TEST(CostModel, AreaGrowsWithHornerDegree) {
  double prev = 0;
  // A chip of three slots (--chip ram:materials=3,slots=3): every coefficient is a loaded table
  // (sized to a scene, a coefficient every material shares is a constant, and a shared c_p makes
  // stage 2's multiplier one by a constant; cost_model.h).
  for (int p = 1; p <= 6; ++p) {
    const UnitCost c = unit_cost(*build("horner:degree=" + std::to_string(p), {10, 20, 50}, 3));
    EXPECT_GT(c.area_ge, prev) << "degree " << p;
    prev = c.area_ge;
    EXPECT_EQ(find(c, "multiplier", "acc u").size(), static_cast<std::size_t>(p));
    EXPECT_EQ(find(c, "adder", "+ c_").size(), static_cast<std::size_t>(p));
    const auto coef = find(c, "table", "coefficient");
    ASSERT_EQ(coef.size(), 1u);
    EXPECT_EQ(coef[0]->count, p + 1);
    EXPECT_EQ(c.ops_per_computed.at("mul"), p + 1);  // + the u scaler on the tau domain
  }
  // The full domain has no u scaler.
  const UnitCost full = unit_cost(*build("horner:domain=full", {10, 20, 50}, 3));
  EXPECT_TRUE(find(full, "multiplier", "u scaler").empty());
  EXPECT_EQ(full.ops_per_computed.at("mul"), 4);
}

// With the scene's coefficients in ROMs, the first multiply-add multiplies u by the register
// that holds c_p, whose constant bits Yosys removes: a product of u and the bits some c_p sets,
// unsigned when every c_p is non-negative, narrower than the loaded chip's signed product of the
// coefficient's width. A c_k that is 0 in every group (c_0 of a fit held to 0 at u = 0) is added
// by no adder. A loaded chip (tables=ram) builds both.
TEST(CostModel, HornerFirstProductAndZeroCoefficientFollowTheRom) {
  const std::vector<double> shin = {10, 20, 50};
  const auto rom = build("horner:degree=3", shin), ram = build("horner:degree=3,tables=ram", shin);
  const nlohmann::json d = rom->describe();
  int cw = 0;
  std::int64_t cp_any = 0;
  bool c0_zero = true, cp_non_negative = true;
  for (const auto& slot : d["slots"]) {
    const auto raw = slot["coefficients_raw"].get<std::vector<std::int64_t>>();
    ASSERT_EQ(raw.size(), 4u);
    c0_zero = c0_zero && raw[0] == 0;
    cp_non_negative = cp_non_negative && raw[3] >= 0;
    cp_any |= raw[3];
    const std::string f = slot["coefficient_format"].get<std::string>();
    cw = std::max(cw,
                  std::stoi(f.substr(2, f.find('.') - 2)) + std::stoi(f.substr(f.find('.') + 1)));
  }
  ASSERT_TRUE(c0_zero);  // constrain=on (the default) holds p(0) = 0
  ASSERT_TRUE(cp_non_negative);
  const UnitCost cr = unit_cost(*rom), cm = unit_cost(*ram);
  const auto mr = find(cr, "multiplier", "stage 2: acc u");
  const auto mm = find(cm, "multiplier", "stage 2: acc u");
  ASSERT_EQ(mr.size(), 1u);
  ASSERT_EQ(mm.size(), 1u);
  EXPECT_EQ(mr[0]->width_b, __builtin_popcountll(static_cast<unsigned long long>(cp_any)));
  EXPECT_EQ(mm[0]->width_a, cw);  // the coefficient's width, not the accumulator's
  EXPECT_LT(mr[0]->ge, mm[0]->ge);
  EXPECT_TRUE(find(cr, "adder", "+ c_0").empty());
  EXPECT_EQ(find(cm, "adder", "+ c_0").size(), 1u);
  EXPECT_EQ(find(cr, "adder", "+ c_1").size(), 1u);
}

TEST(CostModel, LutTableDoublesWithBits) {
  const UnitCost b6 = cost("lut:bits=6");
  const UnitCost b7 = cost("lut:bits=7");
  EXPECT_GT(b7.area_ge, b6.area_ge);
  // An even and an odd bank, each of 2^(bits-1) + 1 entries of the real contents (what the RTL
  // writes).
  const auto t6 = find(b6, "table", "t^n table");
  const auto t7 = find(b7, "table", "t^n table");
  ASSERT_EQ(t6.size(), 2u);
  ASSERT_EQ(t7.size(), 2u);
  EXPECT_EQ(t6[0]->width_a, 33);
  EXPECT_EQ(t7[0]->width_a, 65);
  EXPECT_EQ(t6[0]->width_b, 15 + 2 + 1);  // table_frac (out + 2) + the bit of 1.0
  // A smooth table's cost grows with its entries, less than in proportion to its bits (its
  // decision diagram shares the slowly varying high bits).
  const double ratio = (t7[0]->ge + t7[1]->ge) / (t6[0]->ge + t6[1]->ge);
  EXPECT_GT(ratio, 1.2);
  EXPECT_LT(ratio, 2.2);
}

// pwp: one coefficient bank per coefficient, 2^segments rows per datapath group, each read in
// the stage that adds its coefficient; one multiply-add per degree. On a loaded chip (three
// materials, tables=ram) the banks are registers whatever their contents, so the lane grows with
// both keys.
TEST(CostModel, PwpBanksFollowSegmentsAndDegree) {
  const std::vector<double> shin = {10, 20, 50};
  double prev = 0;
  for (int d = 1; d <= 3; ++d) {
    const UnitCost c = unit_cost(*build("pwp:degree=" + std::to_string(d), shin, 3));
    EXPECT_GT(c.area_ge, prev) << "degree " << d;
    prev = c.area_ge;
    const auto banks = find(c, "table", "coefficient bank");
    ASSERT_EQ(banks.size(), static_cast<std::size_t>(d + 1));
    for (const Primitive* b : banks) {
      EXPECT_EQ(b->width_a, 16);  // 2^4 rows, the default segments
      EXPECT_EQ(b->count, 3);     // one per material
    }
    EXPECT_EQ(find(c, "multiplier", "acc x").size(), static_cast<std::size_t>(d));
    EXPECT_EQ(c.ops_per_computed.at("mul"), d);
    EXPECT_EQ(c.stages.size(), static_cast<std::size_t>(d + 2));  // comparator, lookup, d macs
  }
  prev = 0;
  for (int seg = 2; seg <= 6; ++seg) {
    const UnitCost c = unit_cost(*build("pwp:segments=" + std::to_string(seg), shin, 3));
    EXPECT_GT(c.area_ge, prev) << "segments " << seg;
    prev = c.area_ge;
    for (const Primitive* b : find(c, "table", "coefficient bank")) EXPECT_EQ(b->width_a, 1 << seg);
  }
  // The higher coefficients are smaller: c_2's bank is narrower than c_0's (t^n at coef_frac).
  const UnitCost def = cost("pwp");
  EXPECT_LT(find(def, "table", "bank c_2")[0]->width_b, find(def, "table", "bank c_0")[0]->width_b);
}

// Banks: the two nodes a request reads (j and j + 1) are one even and one odd entry, so the lut's
// t^n table and pow's log2 and exp2 tables are an even and an odd ROM, each read once, priced
// from their own contents; with the two muxes that order the words, less than the one table
// read at two addresses (two ROMs of every entry) that the RTL wrote before.
TEST(CostModel, TablesReadTwiceAreBanked) {
  const double n = 50;
  const MaterialParams m = material(n);
  LutConfig lc;
  lc.table_frac = 17;  // the default: out (uq1.15) + 2
  const LutUnit lut(lc, m);
  const int bits = lc.bits, tw = lc.table_frac + 1;
  // The RTL's case ROMs ({group, j} and {group, j / 2}), one group: padded with zeros.
  std::vector<std::int64_t> all, even, odd;
  for (std::int64_t j = 0; j <= (std::int64_t{1} << bits) + 1; ++j) {
    all.push_back(lut.entry(j));
    (j % 2 == 0 ? even : odd).push_back(lut.entry(j));
  }
  all.resize(std::size_t{1} << (bits + 1), 0);
  even.resize(std::size_t{1} << bits, 0);
  odd.resize(std::size_t{1} << bits, 0);
  const UnitCost c = cost("lut", {n});
  const auto e = find(c, "table", "t^n table, even bank");
  const auto o = find(c, "table", "t^n table, odd bank");
  ASSERT_EQ(e.size(), 1u);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_DOUBLE_EQ(e[0]->ge, rom_ge(even, tw));
  EXPECT_DOUBLE_EQ(o[0]->ge, rom_ge(odd, tw));
  const double order = area_where(c, "bank swap");
  EXPECT_DOUBLE_EQ(order, 2 * tw * cost_constants().mux2_ge);
  EXPECT_LT(e[0]->ge + o[0]->ge + order, 2 * rom_ge(all, tw));

  const UnitCost pc = cost("pow", {n});
  const PowTables tabs{PowConfig{}};
  for (const auto& [name, words, w] :
       {std::tuple{"log2 table", tabs.log_table, tabs.log_frac + 1},
        std::tuple{"exp2 table", tabs.exp_table, tabs.exp_frac + 2}}) {
    SCOPED_TRACE(name);
    std::vector<std::int64_t> pe, po;
    for (std::size_t j = 0; j < words.size(); ++j) (j % 2 == 0 ? pe : po).push_back(words[j]);
    const auto be = find(pc, "table", std::string(name) + " (ROM, even bank)");
    const auto bo = find(pc, "table", std::string(name) + " (ROM, odd bank)");
    ASSERT_EQ(be.size(), 1u);
    ASSERT_EQ(bo.size(), 1u);
    EXPECT_EQ(be[0]->width_a, static_cast<int>(pe.size()));
    EXPECT_DOUBLE_EQ(be[0]->ge, rom_ge(pe, w));
    EXPECT_DOUBLE_EQ(bo[0]->ge, rom_ge(po, w));
    const double swap = area_where(pc, std::string(name) + ": nodes in order");
    EXPECT_DOUBLE_EQ(swap, 2 * w * cost_constants().mux2_ge);
    EXPECT_LT(be[0]->ge + bo[0]->ge + swap, 2 * rom_ge(words, w));
  }
}

TEST(CostModel, LutTableScalesWithSlots) {
  const UnitCost one = cost("lut", {50});
  double prev = 0;
  for (const auto& shin : {std::vector<double>{50}, {10, 50}, {5, 20, 50, 200}}) {
    const UnitCost c = cost("lut", shin);
    const auto t = find(c, "table", "t^n table");
    ASSERT_EQ(t.size(), 2u);  // the even and the odd bank
    EXPECT_EQ(t[0]->count, static_cast<int>(shin.size()));
    EXPECT_EQ(t[0]->width_a, 33);
    EXPECT_GT(t[0]->ge, prev);  // more materials' contents in one ROM
    prev = t[0]->ge;
    EXPECT_GE(c.area_ge, one.area_ge);
  }
  // A chip of fixed capacity holds its tables in registers with a write port: per bit, more
  // than any ROM of the same size.
  const UnitCost ram = unit_cost(*build("lut", {5, 20, 50, 200}, 4));
  const auto tr = find(ram, "table", "t^n table");
  ASSERT_EQ(tr.size(), 1u);  // banked odd/even: priced as one array of every entry
  EXPECT_GT(tr[0]->ge, 4 * 65 * 18 * cost_constants().dff_ge);
  // pow's tables are fixed-function ROMs: they do not scale with the slots.
  const UnitCost pow1 = cost("pow", {50}), pow4 = cost("pow", {5, 20, 50, 200});
  const auto rom1 = find(pow1, "table", "ROM");
  const auto rom4 = find(pow4, "table", "ROM");
  ASSERT_EQ(rom1.size(), 4u);  // log2 and exp2, an even and an odd bank each
  ASSERT_EQ(rom4.size(), 4u);
  double a1 = 0, a4 = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    a1 += rom1[i]->ge;
    a4 += rom4[i]->ge;
  }
  EXPECT_EQ(a1, a4);
}

// tables=ram: the same results, a canonical spec that says so (tables=rom, the default, is left
// out), and every per-slot table priced as registers with a write port (at least ram_bit_ge a
// stored bit), so the lane costs more than with ROMs of its contents.
TEST(CostModel, TablesRamPricesRegistersAndKeepsResults) {
  const std::vector<double> shin = {10, 50, 200};
  for (const std::string& u : kUnits) {
    const auto rom = build(u, shin), ram = build(u + ":tables=ram", shin);
    EXPECT_TRUE(ram->tables_ram()) << u;
    EXPECT_FALSE(rom->tables_ram()) << u;
    EXPECT_NE(ram->canonical_spec().find("tables=ram"), std::string::npos) << u;
    EXPECT_EQ(rom->canonical_spec().find("tables"), std::string::npos) << u;
    for (std::size_t s = 0; s < shin.size(); ++s)
      for (std::int64_t t = 0; t <= rom->in_format().raw_one(); t += 37)
        ASSERT_EQ(ram->eval_with_skip(s, t), rom->eval_with_skip(s, t)) << u << " " << t;
    const UnitCost cr = unit_cost(*rom), cm = unit_cost(*ram);
    EXPECT_GT(cm.area_ge, cr.area_ge) << u;
    int per_slot = 0;
    for (const Primitive& p : cm.inventory) {
      if (p.kind != "table" || (p.where.find("per slot") == std::string::npos &&
                                p.where.find("per datapath group") == std::string::npos))
        continue;
      ++per_slot;
      EXPECT_GE(p.ge, p.width_a * p.width_b * p.count * cost_constants().ram_bit_ge)
          << u << ": " << p.where;
    }
    EXPECT_GE(per_slot, 2) << u << ": the tau table and the datapath's";
  }
}

// sfu: the SFU's two tables are 64 x 52-bit ROMs whatever the materials; n's fp32 significand is a
// constant multiplier for one material and a full 24 x 24 one when the chip loads n; the lane's
// price comes with the share of a GPU's SFU, stated apart from it.
TEST(CostModel, SfuTablesFixedAndFmulFollowsN) {
  const UnitCost one = cost("sfu"), three = cost("sfu", {10, 50, 200});
  for (const UnitCost* c : {&one, &three}) {
    const auto tables = find(*c, "table", "-bit table (A, B, C)");
    ASSERT_EQ(tables.size(), 2u);
    for (const Primitive* t : tables) {
      EXPECT_EQ(t->width_a, 64);
      EXPECT_EQ(t->width_b, 52);
    }
  }
  EXPECT_LT(area_where(one, "stage 2: fp32 significand"),
            0.5 * area_where(cost("sfu:tables=ram"), "stage 2: fp32 significand"));
  EXPECT_EQ(find(cost("sfu:tables=ram"), "multiplier", "24 x 24").size(), 1u);
  const auto share = build("sfu")->describe()["elaboration"]["hardware_share"];
  EXPECT_EQ(share["table_words_used"], 128);
  EXPECT_EQ(share["table_words"], 448);
  EXPECT_NE(share["statement"].get<std::string>().find("not this lane's price"), std::string::npos);
  EXPECT_FALSE(build("pow")->describe()["elaboration"].contains("hardware_share"));
}

TEST(CostModel, SchlickDividerWidths) {
  // A chip of fixed capacity holds any n of the key's format: uq14.4, 18 bits.
  const UnitCost fixed = unit_cost(*build("schlick", {50}, 1));
  const auto div = find(fixed, "divider");
  ASSERT_EQ(div.size(), 1u);
  EXPECT_EQ(div[0]->width_a, 15 + 2);   // quotient bits: out.frac_bits + 2
  EXPECT_EQ(div[0]->width_b, 18 + 15);  // D: n register (uq14.4) + input fraction bits
  const auto mul = find(fixed, "multiplier");
  ASSERT_EQ(mul.size(), 1u);
  EXPECT_EQ(mul[0]->width_a, 18);
  EXPECT_EQ(mul[0]->width_b, 16);
  // A wider n register widens the multiplier and the divider.
  const UnitCost wide_n = unit_cost(*build("schlick:n=uq16.6", {50}, 1));
  EXPECT_EQ(find(wide_n, "divider")[0]->width_b, 22 + 15);
  EXPECT_GT(wide_n.area_ge, fixed.area_ge);

  // Sized to the scene, the register holds n = 50 (110010b, exact in uq14.4) in 6 bits: uq6.0, so
  // D = n (1 - t) + t has 6 + 15 bits.
  const UnitCost c = cost("schlick");
  EXPECT_EQ(find(c, "divider")[0]->width_b, 6 + 15);
  // One material: n is a constant, its table wiring, the multiplier one by 50 = 11001b << 1.
  const auto by_n = find(c, "multiplier", "by a constant");
  ASSERT_EQ(by_n.size(), 1u);
  EXPECT_EQ(by_n[0]->width_a, 16);
  EXPECT_EQ(by_n[0]->width_b, 5);
  EXPECT_TRUE(find(c, "table", "n table").empty());
  // Two materials: the n ROM's bits set in either (50 | 20 = 110110b) are the tree's rows.
  const UnitCost two = cost("schlick", {50, 20});
  EXPECT_EQ(find(two, "multiplier")[0]->width_a, 16);
  EXPECT_EQ(find(two, "multiplier")[0]->width_b, 4);
  // The key's format still decides where the scene's n is not exact in it: 50.03 is 50.0 in
  // uq14.4 (6 bits) but 50.03125 (110010.00001b, uq6.5) in uq16.6.
  EXPECT_EQ(find(cost("schlick", {50.03}), "divider")[0]->width_b, 6 + 15);
  EXPECT_EQ(find(cost("schlick:n=uq16.6", {50.03}), "divider")[0]->width_b, 11 + 15);
  EXPECT_GT(cost("schlick:n=uq16.6", {50.03}).area_ge, cost("schlick", {50.03}).area_ge);
}

TEST(CostModel, IterativeDividerIsSmallerWithSameSteps) {
  const UnitCost pipe = cost("schlick:divider=pipelined");
  const UnitCost iter = cost("schlick:divider=iterative");
  const double div_pipe = area_where(pipe, "divider");
  const double div_iter = area_where(iter, "divider");
  EXPECT_LT(div_iter, 0.2 * div_pipe);  // two rows + their state vs 17 rows + 17 register stages
  EXPECT_LT(iter.area_ge, 0.55 * pipe.area_ge);  // rows of one subtractor each: 0.53
  EXPECT_EQ(find(pipe, "divider")[0]->width_a, 17);
  EXPECT_EQ(find(iter, "divider")[0]->width_a, 2);
  // 17 rows pipelined; iterative, the first bit's row and the loop's (schlick's RTL).
  EXPECT_DOUBLE_EQ(find(pipe, "divider")[0]->ge, 17 * find(iter, "divider")[0]->ge / 2);
  EXPECT_EQ(pipe.ops_per_computed.at("div_step"), 17);
  EXPECT_EQ(iter.ops_per_computed.at("div_step"), pipe.ops_per_computed.at("div_step"));
  EXPECT_EQ(cost("schlick:out=uq1.11").ops_per_computed.at("div_step"), 13);
}

TEST(CostModel, PipelinedSchlickCriticalPathIsOneDividerRow) {
  const UnitCost c = cost("schlick");
  const double row = divider_row_delay(find(c, "divider")[0]->width_b);
  const double reg = cost_constants().reg_delay;
  for (int s = 2; s <= 18; ++s) EXPECT_EQ(stage(c, "stage " + std::to_string(s)).delay, row + reg);
  EXPECT_LT(c.critical_path, 17 * row);  // never the whole divider in one stage
  EXPECT_LE(c.critical_path, std::max(row + reg, stage(c, "stage 1").delay));
  // The iterative divider's loop is one row plus its load mux.
  const UnitCost it = cost("schlick:divider=iterative");
  EXPECT_EQ(stage(it, "stages 2-18 (divider loop)").delay, row + mux_delay(2) + reg);
  EXPECT_EQ(it.stages.size(), 4u);  // comparator, stage 1, loop, rounding
}

TEST(CostModel, SkipOffDropsTheComparator) {
  const UnitCost on = cost("schlick");
  const UnitCost off = cost("schlick:skip=off");
  EXPECT_EQ(find(on, "comparator", "tau").size(), 1u);
  EXPECT_TRUE(find(off, "comparator", "tau").empty());
  EXPECT_EQ(on.ops_per_request.at("compare"), 1);
  EXPECT_EQ(off.ops_per_request.count("compare"), 0u);
  EXPECT_LT(off.area_ge, on.area_ge);
  // hast keeps the per-slot root table: it is the u scaler's root, not only the threshold (three
  // materials: with one, every table is a constant, no part).
  EXPECT_EQ(find(cost("hast:skip=off", {10, 20, 50}), "table", "root").size(), 1u);
}

TEST(CostModel, OperationCounts) {
  const UnitCost pw = cost("pow");
  EXPECT_EQ(pw.ops_per_computed.at("mul"), 3);
  EXPECT_EQ(pw.ops_per_computed.at("lzd"), 1);
  EXPECT_EQ(pw.ops_per_computed.at("table_read"), 5);  // 2 log2 + 2 exp2 words + n
  const UnitCost lut = cost("lut");
  EXPECT_EQ(lut.ops_per_computed.at("mul"), 1);
  EXPECT_EQ(lut.ops_per_computed.count("div_step"), 0u);
  for (const auto& name : kUnits) {
    const UnitCost c = cost(name);
    EXPECT_EQ(c.ops_per_request.at("compare"), 1) << name;
  }
}

TEST(CostModel, JsonRoundTrip) {
  for (const auto& spec : {"schlick:divider=iterative", "horner", "lut"}) {
    SCOPED_TRACE(spec);
    const UnitCost c = cost(spec, {10, 50});
    const nlohmann::json j = c.to_json();
    for (const char* key : {"inventory", "area_ge", "critical_path", "critical_stage", "stages",
                            "ops_per_computed", "ops_per_request"})
      EXPECT_TRUE(j.contains(key)) << key;
    const UnitCost back = UnitCost::from_json(nlohmann::json::parse(j.dump()));
    ASSERT_EQ(back.inventory.size(), c.inventory.size());
    for (std::size_t i = 0; i < c.inventory.size(); ++i) {
      const Primitive &a = c.inventory[i], &b = back.inventory[i];
      EXPECT_EQ(a.kind, b.kind);
      EXPECT_EQ(a.width_a, b.width_a);
      EXPECT_EQ(a.width_b, b.width_b);
      EXPECT_EQ(a.count, b.count);
      EXPECT_EQ(a.ge, b.ge);
      EXPECT_EQ(a.where, b.where);
    }
    EXPECT_EQ(back.area_ge, c.area_ge);
    EXPECT_EQ(back.critical_path, c.critical_path);
    EXPECT_EQ(back.critical_stage, c.critical_stage);
    ASSERT_EQ(back.stages.size(), c.stages.size());
    for (std::size_t i = 0; i < c.stages.size(); ++i) {
      EXPECT_EQ(back.stages[i].stage, c.stages[i].stage);
      EXPECT_EQ(back.stages[i].delay, c.stages[i].delay);
      EXPECT_EQ(back.stages[i].path, c.stages[i].path);
    }
    EXPECT_EQ(back.ops_per_computed, c.ops_per_computed);
    EXPECT_EQ(back.ops_per_request, c.ops_per_request);
    EXPECT_EQ(back.to_json(), j);
  }
}

}  // namespace
}  // namespace glint
