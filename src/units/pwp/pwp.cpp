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
// (t = 1). That is domain=t; domain=log (build_log) builds one set of lg2 and ex2 tables for
// every group and dispatches its layout, inventory, description and Verilog to log_kind.h.
#include "units/pwp/pwp.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "units/pwp/datapath.h"
#include "units/pwp/fit_engine.h"
#include "units/pwp/log_kind.h"
#include "units/pwp/rtl.h"
#include "units/unit_set.h"

namespace glint {
namespace {

struct Pwp : UnitKindDefaults {
  using Config = PwpConfig;
  using Datapath = PwpUnit;
  static constexpr const char* kName = "pwp";
  static constexpr const char* kSummary =
      "piecewise polynomial: 2^s segments over [t0, 1], degree 1..3 by Horner, one table per "
      "material (domain=log: ex2(n lg2 t), lg2 and ex2 by segments shared by every material)";

  // One --unit away: in the default set it would change every default report and golden.
  static constexpr bool kDefaultSet = false;
  using Keys = PwpKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"ram", "tables=ram", "--vectors traces/blinn_colored.vec --sink-ready 0.6"},
      {"cubic", "segments=3,degree=3,out=uq1.12",
       "--vectors traces/multi_light.vec --sink-ready 0.5 --seed 5"},
      {"linear_skip_off", "segments=6,degree=1,in=uq1.12,skip=off",
       "--vectors traces/eight_lights.vec --sink-ready 0.8"},
      {"log", "domain=log", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      // Several materials, each n loadable; the lg2 and ex2 ROMs shared.
      {"log_ram", "domain=log,tables=ram,degree=3,segments=3",
       "--vectors traces/blinn_colored.vec --sink-ready 0.6"},
      {"log_linear_skip_off", "domain=log,degree=1,segments=6,in=uq1.12,out=uq1.10,skip=off",
       "--vectors traces/multi_light.vec --sink-ready 0.5 --seed 5"}};

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
    const std::string fit = keys.read(Keys::fit);
    c.log_domain = keys.read(Keys::domain) == "log";
    c.n_format = keys.read(Keys::n);
    if (c.log_domain) {
      if (const std::string* v = keys.find(std::string(Keys::fit.name)); v && fit != Keys::fit.def)
        // refusal: pwp.log_fit
        keys.fail(std::string(Keys::fit.name), *v,
                  "domain=log fits its lg2 and ex2 segments with glint's Remez (fit is "
                  "domain=t's)");
      return build_log(keys, common, plan, c);
    }
    // At its default the key changes nothing (a spec spelling out every default builds).
    if (const std::string* v = keys.find(std::string(Keys::n.name)); v && c.n_format != Keys::n.def)
      // refusal: pwp.n_domain
      keys.fail(std::string(Keys::n.name), *v,
                "the n register is domain=log's (domain=t holds t^n in its tables)");
    if (fit == "sollya" && c.degree < 2)
      // refusal: pwp.fit_sollya_degree
      keys.fail(std::string(Keys::fit.name), fit,
                "Sollya fits a segment's free coefficients c_2 .. c_d, and degree 1 has none (each "
                "segment is the chord between its ends); use fit=best or fit=glint");
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
    // Sollya's segments where the key says, within the registers and guard just chosen.
    choose_pwp_fit_engines(parse_pwp_fit_engine(fit), units);
    nlohmann::json config = common_config(common);
    put_key(config, Keys::segments, c.segments);
    put_key(config, Keys::degree, c.degree);
    put_key(config, Keys::coef_frac, c.coef_frac);
    put_key(config, Keys::guard, c.guard);
    put_key(config, Keys::fit, fit);
    // lookup (index, offset, c_d), d multiply-adds, the last one rounding.
    const UnitTiming timing{c.degree + 1, 1, 0};
    return make_unit_set<Pwp>(common, std::move(config), c, std::move(units), plan, timing);
  }

  // domain=log (units/pwp/log_datapath.h): one set of tables for every group, n per group.
  static std::unique_ptr<SpecularUnit> build_log(const KeyReader& keys, const CommonKeys& common,
                                                 const SlotPlan& plan, PwpConfig c) {
    for (const IntKey* k : {&Keys::coef_frac, &Keys::guard}) {
      const std::string* v = keys.find(std::string(k->name));
      if (v != nullptr && *v != "auto")
        // refusal: pwp.log_widths
        keys.fail(std::string(k->name), *v,
                  "domain=log derives its widths from out, n and degree (units/pwp/"
                  "log_datapath.h); coef_frac and guard are domain=t's");
    }
    const auto tables = std::make_shared<const PwpLogTables>(pwp_log_spec(c));
    auto units = build_per_group<PwpUnit>(c, plan.groups, tables);
    nlohmann::json config = common_config(common);
    put_key(config, Keys::segments, c.segments);
    put_key(config, Keys::degree, c.degree);
    put_key(config, Keys::domain, "log");
    put_key(config, Keys::n, c.n_format);
    // lg2 lookup, d multiply-adds, the n multiplier, ex2 lookup, d multiply-adds.
    const UnitTiming timing{2 * c.degree + 3, 1, 0};
    return make_unit_set<Pwp>(common, std::move(config), c, std::move(units), plan, timing);
  }

  static std::optional<NRegister> n_register(const Config& c, const std::vector<Datapath>& units,
                                             bool fixed) {
    if (!c.log_domain) return std::nullopt;
    std::vector<std::int64_t> raw;
    std::vector<double> target;
    for (const PwpUnit& u : units) {
      raw.push_back(u.log_path()->n_raw());
      target.push_back(u.log_path()->shininess());
    }
    return elaborate_n_register(c.n_format, raw, target, fixed);
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>& units,
                                   UnitTiming) {
    if (c.log_domain) return pwp_log_stages(c, units);
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
    if (c.log_domain) return pwp_log_cost(b, L, c, units);
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
      const PwpBank k = pwp_bank(units, c.segments, j);
      return b.slot_table(rows, k.width, L.groups, true,
                          fmt::format("coefficient bank c_{} (2^segments per datapath group)", j),
                          known ? &k.words : nullptr);
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
    // acc = c_d << (fa - cf): the register holds c_d's bits (its low ones are constant zeros).
    const PwpBank top = pwp_bank(units, c.segments, d);
    b.reg(std::max(1, rb) + top.width + carried, "stage 1: x, c_d, index, group, flags");
    b.stage("stage 1", {sp, sub, sh, cd});

    // Multiply-add stages: acc x rounded to fa bits (the last: exact), + c_j from its bank.
    for (int s = 2; s <= d + 1; ++s) {
      const int j = d + 1 - s;  // the coefficient this stage adds
      const bool last = s == d + 1;
      std::vector<Seg> p;
      const Seg cj = bank(j);
      // The first product multiplies x by the register loaded with c_d: from a ROM of known,
      // non-negative contents it has one partial-product row per bit some c_d sets (as horner's
      // first multiply-add); otherwise the signed accumulator.
      const std::string what = fmt::format("stage {}: acc x", s);
      Seg mul;
      if (rb > 0 && s == 2 && known && !top.is_signed)
        mul = b.table_multiplier(rb, top.words, what);
      else if (rb > 0)
        mul = b.multiplier(s == 2 ? top.width : wacc, rb, what, 1, true);
      p.push_back(rb > 0 ? parallel(mul, cj) : cj);
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
    if (u.log_path() != nullptr) return pwp_log_describe(u);
    const PwpFitRecord& f = u.fit_record();
    nlohmann::json slot{{"t0_raw", u.t0_raw()},
                        {"segments", u.segment_count()},
                        {"offset_bits", u.offset_bits()},
                        {"blended_segments", u.blended_segments()},
                        {"chord_segments", u.chord_segments()},
                        {"fit_engine", f.sollya == 0 ? "glint" : "sollya"},
                        {"sollya_segments", f.sollya},
                        {"fitted_segments", f.fitted}};
    if (f.sollya > 0) slot["sup_norm"] = {{"lo", f.sup_lo}, {"hi", f.sup_hi}};
    return slot;
  }
  static std::string rtl(const hdl::DatapathPorts& p, const Config& c,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    if (c.log_domain) return pwp_log_rtl(p, c, units, layout);
    return pwp_rtl(p, c, units, layout);
  }
};

}  // namespace

const UnitDescription& pwp_unit() {
  static const DescriptionOf<Pwp> description;
  return description;
}

}  // namespace glint
