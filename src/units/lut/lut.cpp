// lut: keys, build, timing, stage layout, cost inventory and description of the table +
// interpolation baseline.
//
// Hardware (L = 2, II 1): stage 1 the span table (per datapath group: a material's slots share
// their table, units/slot_plan.h), the subtractor t - t0, the index shifter (the span is per
// group) and the t^n table per group (2^bits + 1) x (table_frac + 1), in an even and an odd bank
// each read once at one of the segment's ends; stage 2 the node difference, the interpolation
// multiplier (table_frac + 2) x (Fi - span - bits, widest group), the adder and the clamp.
#include "units/lut/lut.h"

#include <fmt/format.h>

#include <algorithm>

#include "units/lut/datapath.h"
#include "units/lut/rtl.h"
#include "units/unit_set.h"

namespace glint {
namespace {

struct Lut : UnitKindDefaults {
  using Config = LutConfig;
  using Datapath = LutUnit;
  static constexpr const char* kName = "lut";
  static constexpr const char* kSummary =
      "table of t^n over [t0, 1] + linear interpolation, one table per material";

  using Keys = LutKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"bits4", "bits=4,table_frac=20",
       "--vectors traces/multi_light.vec --sink-ready 0.3 --seed 5"},
      {"narrow_skip_off", "bits=9,in=uq1.7,out=uq1.10,skip=off",
       "--vectors traces/eight_lights.vec --sink-ready 0.8"},
      {"ram", "tables=ram", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"ram_bits4", "tables=ram,bits=4,table_frac=20,in=uq1.12",
       "--vectors traces/multi_light.vec --sink-ready 0.5"},
      {"chip_capacity", "bits=4,in=uq1.12",
       "--vectors traces/multi_light.vec --chip ram:materials=5,slots=12 --sink-ready 0.7"}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    LutConfig c{common.in, common.out, keys.read(Keys::bits), keys.read(Keys::table_frac),
                common.skip};
    c.table_frac_auto = c.table_frac < 0;
    if (c.table_frac < 0) c.table_frac = common.out.frac_bits + 2;
    nlohmann::json config = common_config(common);
    put_key(config, Keys::bits, c.bits);
    put_key(config, Keys::table_frac, c.table_frac);
    // index + table read, interpolation + rounding.
    const UnitTiming timing{2, 1, 0};
    // One table per datapath group, spanning from the group's smallest tau (its slots' comparators
    // let nothing lower through).
    auto units = build_per_group_bounded<LutUnit>(
        "lut", key_values({{"bits", std::to_string(c.bits)}}), c, plan.groups,
        [](const LutUnit& u) { return u.table_bytes(); });
    return make_unit_set<Lut>(common, std::move(config), c, std::move(units), plan, timing);
  }

  // Interpolation bits: Fi - span - bits, the widest over datapath groups.
  static int max_remainder_bits(const std::vector<Datapath>& units) {
    int r = 0;
    for (const LutUnit& u : units) r = std::max(r, u.remainder_bits());
    return r;
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>& units,
                                   UnitTiming) {
    const QFormat node = uq(1, c.table_frac);
    return {input_stage(),
            {"lookup",
             1,
             1,
             {{"index", uq(c.bits + 1, 0)},
              {"frac", uq(std::max(1, max_remainder_bits(units)), 0)},
              {"node_lo", node},
              {"node_hi", node}}},
            {"interp", 2, 2, {{"result", c.out}}}};
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config& c,
                   const std::vector<Datapath>& units) {
    const int bits = c.bits, tf = c.table_frac;
    const int wi = L.in.width(), fi = L.in.frac_bits, wo = L.out.width();
    const int entries = (1 << bits) + 1;
    const int tw = tf + 1;  // t^n in [0, 1]: 1.0 at the last node
    const int sbits = clog2(fi + 1);
    int r_max = 0;  // interpolation bits: fi - span - bits, widest over datapath groups
    for (const LutUnit& u : units) r_max = std::max(r_max, fi - u.span_log2() - bits);

    // Stage 1: t - t0 (t0 = 1 - 2^-span), the index field at the slot's span, the two nodes.
    // As ROMs, t0, the remainder bits and the paddings are functions of the span, which Yosys
    // folds into one table of it; as registers (tables=ram) each is its own array, as
    // units/lut/rtl.cpp loads them: t0 (wi bits), the remainder bits, the padding and (with
    // interpolation bits) the alignment.
    const Seg sp =
        L.tables_ram
            ? b.slot_table(L.groups, wi + (r_max > 0 ? 3 : 2) * sbits, 1, true,
                           "stage 1: t0, remainder-bits, padding, alignment tables (per datapath "
                           "group)")
            : b.slot_table(L.groups, sbits, 1, true, "stage 1: span table (per datapath group)");
    const Seg sub = b.adder(wi, "stage 1: t - t0");
    const Seg sh = b.shifter(wi, sbits, "stage 1: index shifter");
    // The t^n tables in an even and an odd bank (units/lut/rtl.cpp), each read once: the nodes j
    // and j + 1 of a request are one even and one odd. As ROMs, their real contents (a case ROM
    // a bank, {group, j / 2}, 2^(bits-1) + 1 entries a group padded to a power of two); as
    // registers, the two arrays with their read muxes are priced as one table of every entry.
    // Then the two 2:1 muxes that put the banks' words in node order.
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    Seg tab;
    if (L.tables_ram) {
      tab = b.slot_table(entries + 1, tw, L.groups, true,
                         "stage 1: t^n table, even and odd banks (per datapath group)", nullptr, 2,
                         true);
    } else {
      const int half = (1 << (bits - 1)) + 1;
      const std::size_t stride = std::size_t{1} << bits;
      std::vector<std::int64_t> even, odd;
      for (const LutUnit& u : units) {
        for (int h = 0; h < half; ++h) {
          even.push_back(u.entry(2 * h));
          odd.push_back(u.entry(2 * h + 1));
        }
        even.resize(even.size() + stride - static_cast<std::size_t>(half), 0);
        odd.resize(even.size(), 0);
      }
      const Seg te = b.slot_table(half, tw, L.groups, true,
                                  "stage 1: t^n table, even bank (per datapath group)",
                                  known ? &even : nullptr);
      const Seg to =
          b.slot_table(half, tw, L.groups, true,
                       "stage 1: t^n table, odd bank (per datapath group)", known ? &odd : nullptr);
      tab = parallel(te, to);
    }
    const Seg order = b.mux(2 * tw, 2, "stage 1: t^n nodes in order (bank swap)");
    b.op("table_read", 3);
    b.op("add");
    b.op("shift");
    b.reg(2 * tw + r_max, "stage 1: nodes, remainder");
    b.stage("stage 1", {sp, sub, sh, tab, order});

    // Stage 2: interpolation (rounding folded into the adder), clamp.
    std::vector<Seg> p2;
    if (r_max > 0) {
      p2.push_back(b.adder(tw + 1, "stage 2: node difference"));
      p2.push_back(b.multiplier(tw + 1, r_max, "stage 2: interpolation", 1, true));
      p2.push_back(b.adder(tw + r_max, "stage 2: + node"));
      b.op("add", 2);
      b.op("mul");
    } else {
      p2.push_back(b.adder(wo + 1, "stage 2: rounding incrementer"));
      b.op("add");
    }
    p2.push_back(b.mux(wo, 2, "stage 2: clamp to 1"));
    b.reg(wo, "stage 2: result");
    b.stage("stage 2", p2);
  }

  static nlohmann::json describe_slot(const Datapath& u) {
    return {{"t0_raw", u.t0_raw()},
            {"span_log2", u.span_log2()},
            {"entries", u.entries()},
            {"chord_error", u.chord_error()},
            {"error_bound", u.error_bound()}};
  }
  static double error_bound(const Datapath& u) { return u.error_bound(); }
  // Both are 0 up to t0, then the chord through their nodes: the exact t^n at each node
  // (float_model) and the rounded entries (model), non-decreasing when the entries are.
  static bool models_monotone(const Datapath& u) { return u.entries_non_decreasing(); }
  static std::string rtl(const hdl::DatapathPorts& p, const Config& c,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    return lut_rtl(p, c, units, layout);
  }
};

}  // namespace

const UnitDescription& lut_unit() {
  static const DescriptionOf<Lut> description;
  return description;
}

}  // namespace glint
