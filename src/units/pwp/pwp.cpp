// pwp: keys, build (one segment table per datapath group, the guard raised until the output is
// monotone), timing, stage layout, cost inventory and description of the piecewise polynomial.
//
// Hardware (L = degree + 1, II 1): stage 1 the span tables (t0 and the offset width, per datapath
// group, as lut's), the subtractor t - t0, the shifter that splits v into the segment index and
// the offset x, and the read of c_d; then d multiply-add stages, each a signed multiplier acc x x
// and an adder, with the bank of the coefficient it adds read beside the multiply (the index and
// the group are carried down the pipeline, not the coefficients). Bank j holds c_j of every
// segment of every group ((groups x 2^segments) x its own width: the higher coefficients are
// smaller and narrower). The last stage rounds once, clamps, and muxes in 0 (t <= t0) and 1.0
// (t = 1).
#include "units/pwp/pwp.h"

#include <fmt/format.h>

#include <algorithm>

#include "units/pwp/datapath.h"
#include "units/unit_set.h"

namespace glint {
namespace {

// Width of bank j: every group's c_j, two's complement when any is negative.
int bank_width(const std::vector<PwpUnit>& units, int j) {
  std::int64_t hi = 0;
  bool negative = false;
  for (const PwpUnit& u : units)
    for (std::size_t k = 0; k < u.segment_count(); ++k) {
      const std::int64_t c = u.coeff(k, j);
      negative = negative || c < 0;
      hi = std::max(hi, c < 0 ? -c : c);
    }
  int bits = 1;
  while (bits < 62 && (std::int64_t{1} << bits) <= hi) ++bits;
  return bits + (negative ? 1 : 0);
}

// Bank j's words, group-major, each group's 2^segments entries (the segments a group does not use,
// when its span holds fewer codes, read 0).
std::vector<std::int64_t> bank_words(const std::vector<PwpUnit>& units, int segments, int j) {
  std::vector<std::int64_t> w;
  const std::size_t rows = std::size_t{1} << segments;
  for (const PwpUnit& u : units) {
    for (std::size_t k = 0; k < rows; ++k) w.push_back(k < u.segment_count() ? u.coeff(k, j) : 0);
  }
  return w;
}

struct Pwp : UnitKindDefaults {
  using Config = PwpConfig;
  using Datapath = PwpUnit;
  static constexpr const char* kName = "pwp";
  static constexpr const char* kSummary =
      "piecewise polynomial: 2^s segments over [t0, 1], degree 1..3 by Horner, one table per "
      "material";

  // One --unit away: in the default set it would change every default report and golden.
  static constexpr bool kDefaultSet = false;
  using Keys = PwpKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"ram", "tables=ram", "--vectors traces/blinn_colored.vec --sink-ready 0.6"},
      {"cubic", "segments=3,degree=3,out=uq1.12",
       "--vectors traces/multi_light.vec --sink-ready 0.5 --seed 5"},
      {"linear_skip_off", "segments=6,degree=1,in=uq1.12,skip=off",
       "--vectors traces/eight_lights.vec --sink-ready 0.8"}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    PwpConfig c;
    c.in = common.in;
    c.out = common.out;
    c.skip = common.skip;
    c.segments = keys.read(Keys::segments);
    c.degree = keys.read(Keys::degree);
    c.coef_frac = keys.read(Keys::coef_frac);
    c.guard = keys.read(Keys::guard);
    c.coef_frac_auto = c.coef_frac < 0;
    c.guard_auto = c.guard < 0;
    c.coef_frac = pwp_coef_frac(c);
    if (c.guard < 0) c.guard = pwp_min_guard(c);
    auto units = build_per_group_bounded<PwpUnit>(
        "pwp",
        key_values(
            {{"segments", std::to_string(c.segments)}, {"degree", std::to_string(c.degree)}}),
        c, plan.groups, [](const PwpUnit& u) { return u.table_bytes(); });
    // The datapath is shared: one guard for every group, raised (when automatic) until each
    // group's output is monotone.
    for (;;) {
      const auto bad = std::find_if(units.begin(), units.end(),
                                    [](const PwpUnit& u) { return !u.output_monotone(); });
      if (bad == units.end()) break;
      if (!c.guard_auto || c.guard >= Keys::guard.hi) {
        for_slot(plan.groups[static_cast<std::size_t>(bad - units.begin())], [&]() -> void {
          // refusal: pwp.monotone
          throw std::invalid_argument(fmt::format(
              "pwp: {}: the output steps back between neighbouring input codes (the inner "
              "roundings); raise guard",
              key_values({{"guard", auto_value(!c.guard_auto, c.guard)},
                          {"degree", std::to_string(c.degree)}})));
        });
      }
      ++c.guard;
      for (PwpUnit& u : units) u.set_guard(c.guard);
    }
    nlohmann::json config = common_config(common);
    put_key(config, Keys::segments, c.segments);
    put_key(config, Keys::degree, c.degree);
    put_key(config, Keys::coef_frac, c.coef_frac);
    put_key(config, Keys::guard, c.guard);
    // lookup (index, offset, c_d), d multiply-adds, the last one rounding.
    const UnitTiming timing{c.degree + 1, 1, 0};
    return make_unit_set<Pwp>(common, std::move(config), c, std::move(units), plan, timing);
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>& units,
                                   UnitTiming) {
    int rb = 0, acc_int = 1;
    for (const PwpUnit& u : units) {
      rb = std::max(rb, u.offset_bits());
      acc_int = std::max(acc_int, u.acc_int_bits());
    }
    const QFormat x = uq(std::max(1, rb), 0);
    const QFormat acc = sq(acc_int, c.out.frac_bits + c.guard);
    std::vector<Stage> s{
        input_stage(),
        {"lookup", 1, 1, {{"index", uq(std::max(1, c.segments), 0)}, {"x", x}, {"acc", acc}}}};
    for (int j = 1; j <= c.degree; ++j) {
      Stage m{"mac" + std::to_string(j), j + 1, j + 1, {{"x", x}, {"acc", acc}}};
      if (j == c.degree) m.registers = {{"result", c.out}};
      s.push_back(std::move(m));
    }
    return s;
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config& c,
                   const std::vector<Datapath>& units) {
    const int d = c.degree, fa = L.out.frac_bits + c.guard;
    const int wi = L.in.width(), fi = L.in.frac_bits, wo = L.out.width();
    const int sbits = clog2(fi + 1);
    const int rows = 1 << c.segments;
    int rb = 0, acc_int = 1;
    for (const PwpUnit& u : units) {
      rb = std::max(rb, u.offset_bits());
      acc_int = std::max(acc_int, u.acc_int_bits());
    }
    const int wacc = acc_int + fa;
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    // Bank j: c_j of every segment of every group, read in the stage that adds it.
    const auto bank = [&](int j) {
      const std::vector<std::int64_t> words = bank_words(units, c.segments, j);
      return b.slot_table(rows, bank_width(units, j), L.groups, true,
                          fmt::format("coefficient bank c_{} (2^segments per datapath group)", j),
                          known ? &words : nullptr);
    };

    // Stage 1: t - t0 and the split of v at the group's offset width (span tables as lut's), c_d.
    const Seg sp =
        L.tables_ram
            ? b.slot_table(L.groups, wi + sbits, 1, true,
                           "stage 1: t0 and offset-width tables (per datapath group)")
            : b.slot_table(L.groups, sbits, 1, true, "stage 1: span table (per datapath group)");
    const Seg sub = b.adder(wi, "stage 1: t - t0");
    const Seg sh = b.shifter(wi, sbits, "stage 1: index / offset shifter");
    const Seg cd = bank(d);
    b.comparator(wi, "stage 1: t <= t0");
    b.op("table_read", 2);
    b.op("add");
    b.op("shift");
    const int carried = std::max(1, c.segments) + L.group_bits + 2;  // index, group, t<=t0, t=1
    b.reg(std::max(1, rb) + wacc + carried, "stage 1: x, c_d, index, group, flags");
    b.stage("stage 1", {sp, sub, sh, cd});

    // Multiply-add stages: acc x rounded to fa bits (the last: exact), + c_j from its bank.
    for (int s = 2; s <= d + 1; ++s) {
      const int j = d + 1 - s;  // the coefficient this stage adds
      const bool last = s == d + 1;
      std::vector<Seg> p;
      const Seg cj = bank(j);
      p.push_back(
          rb > 0 ? parallel(b.multiplier(wacc, rb, fmt::format("stage {}: acc x", s), 1, true), cj)
                 : cj);
      b.op("table_read");
      if (rb > 0) b.op("mul");
      p.push_back(b.adder(wacc + (last ? rb : 0), fmt::format("stage {}: + c_{}", s, j)));
      b.op("add");
      if (last) {
        p.push_back(b.mux(wo, 4, fmt::format("stage {}: clamp to [0, 1], t <= t0, t = 1", s)));
        b.reg(wo, fmt::format("stage {}: result", s));
      } else {
        b.reg(std::max(1, rb) + wacc + carried, fmt::format("stage {}: x, acc, index, flags", s));
      }
      b.stage(fmt::format("stage {}", s), p);
    }
  }

  static nlohmann::json describe_slot(const Datapath& u) {
    return {{"t0_raw", u.t0_raw()},
            {"segments", u.segment_count()},
            {"offset_bits", u.offset_bits()},
            {"blended_segments", u.blended_segments()},
            {"chord_segments", u.chord_segments()}};
  }
};

}  // namespace

const UnitDescription& pwp_unit() {
  static const DescriptionOf<Pwp> description;
  return description;
}

}  // namespace glint
