// pow: keys, build, timing, stage layout, cost inventory and description of the exact-power
// baseline exp2(n log2 t).
//
// Hardware (L = 5, II 1): stage 1 a leading-one detector Wi, the normalisation shifter and the log2
// ROM (2^log_bits + 1) x (log_frac + 1), an even and an odd bank each read once at one of the
// segment's ends; stage 2 the node difference and
// interpolation multiplier, with the n table read beside; stage 3 the multiplier Wn x log2 t; stage
// 4 the exp2 ROM (2^exp_bits + 1) x (exp_frac + 2), banked the same way; stage 5 the exp2
// interpolation, the output shifter, rounding and clamp.
#include "units/pow/pow.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "units/pow/datapath.h"
#include "units/pow/rtl.h"
#include "units/unit_set.h"

namespace glint {
namespace {

// A fixed-function table read at i and i + 1 (units/pow/rtl.cpp, banked_table): a ROM of its
// even entries and one of its odd entries, each read once, then two 2:1 muxes of the word width
// that put the two words in node order.
Seg banked_rom(CostBuilder& b, const std::vector<std::int64_t>& words, int w,
               const std::string& where) {
  std::vector<std::int64_t> even, odd;
  for (std::size_t j = 0; j < words.size(); ++j) (j % 2 == 0 ? even : odd).push_back(words[j]);
  const Seg e = b.rom(even, w, where + " (ROM, even bank)");
  const Seg o = b.rom(odd, w, where + " (ROM, odd bank)");
  const Seg order = b.mux(2 * w, 2, where + ": nodes in order (bank swap)");
  return series({parallel(e, o), order});
}

struct Pow : UnitKindDefaults {
  using Config = PowConfig;
  using Datapath = PowUnit;
  static constexpr const char* kName = "pow";
  static constexpr const char* kSummary =
      "exact-power baseline: log2 table + interp, multiply by n, exp2 table + interp";

  using Keys = PowKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"small_tables", "log_bits=6,exp_bits=4,in=uq1.16,out=uq1.10",
       "--vectors traces/multi_light.vec --sink-ready 0.5"},
      {"n_wide", "n=uq14.6,y_frac=16,log_frac=20",
       "--vectors traces/contract_cases.vec --sink-ready 0.9 --seed 11"},
      {"ram", "tables=ram", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"ram_small_tables", "tables=ram,log_bits=6,exp_bits=4,in=uq1.12,out=uq1.10",
       "--vectors traces/blinn_colored.vec --sink-ready 0.5"},
      {"chip_capacity", "in=uq1.12,out=uq1.10",
       "--vectors traces/blinn_colored.vec --chip ram:materials=9,slots=7 --sink-ready 0.6"}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    PowConfig c;
    c.in = common.in;
    c.out = common.out;
    c.skip = common.skip;
    c.n_format = keys.read(Keys::n);
    c.log_bits = keys.read(Keys::log_bits);
    c.log_frac = keys.read(Keys::log_frac);
    c.y_frac = keys.read(Keys::y_frac);
    c.exp_bits = keys.read(Keys::exp_bits);
    c.exp_frac = keys.read(Keys::exp_frac);
    nlohmann::json config = common_config(common);
    put_key(config, Keys::n, c.n_format);
    put_key(config, Keys::log_bits, c.log_bits);
    put_key(config, Keys::log_frac, c.log_frac);
    put_key(config, Keys::y_frac, c.y_frac);
    put_key(config, Keys::exp_bits, c.exp_bits);
    put_key(config, Keys::exp_frac, c.exp_frac);
    // leading-one detect + log2 table read, log2 interpolation, multiply by n, exp2 table read,
    // exp2 interpolation + shift + rounding.
    const UnitTiming timing{5, 1, 0};
    auto units = build_pow_units(c, plan.groups);
    return make_unit_set<Pow>(common, std::move(config), c, std::move(units), plan, timing);
  }

  // The widths of the registers for an n register of format nf (the stage layout: the key's
  // format; the cost model: the register as the scene elaborates it, n_register()).
  struct Widths {
    int ebits, log2t_int, yint, log_r, exp_r;
  };
  static Widths widths(const Config& c, const QFormat& nf) {
    const int fi = c.in.frac_bits;
    const int ebits = clog2(fi + 1);  // exponent of t / normalisation shift
    return {ebits, ebits + 1, nf.int_bits + ebits + 1, std::max(0, fi - c.log_bits),
            std::max(0, c.y_frac - c.exp_bits)};
  }

  // The n register holds every group's n_q exactly in the bits those values use (units/
  // n_register.h): y = n log2 t is the same product with fewer zero bits around n.
  static std::optional<NRegister> n_register(const Config& c, const std::vector<Datapath>& units,
                                             bool fixed) {
    std::vector<std::int64_t> raw;
    std::vector<double> target;
    for (const PowUnit& u : units) {
      raw.push_back(u.n_raw());
      target.push_back(u.shininess());
    }
    return elaborate_n_register(c.n_format, raw, target, fixed);
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>&, UnitTiming) {
    const Widths w = widths(c, c.n_format);
    const QFormat log_node = uq(1, c.log_frac), exp_node = uq(2, c.exp_frac);
    return {input_stage(),
            {"log_table",
             1,
             1,
             {{"shift", uq(w.ebits, 0)},
              {"log2_lo", log_node},
              {"log2_hi", log_node},
              {"frac", uq(0, std::max(1, w.log_r))}}},
            {"log_interp", 2, 2, {{"log2_t", sq(w.log2t_int, c.log_frac)}, {"n", c.n_format}}},
            {"mul_n", 3, 3, {{"y", sq(w.yint, c.y_frac)}}},
            {"exp_table",
             4,
             4,
             {{"y_int", sq(w.yint, 0)},
              {"exp2_lo", exp_node},
              {"exp2_hi", exp_node},
              {"frac", uq(0, std::max(1, w.exp_r))}}},
            {"exp_interp", 5, 5, {{"exp2", exp_node}, {"result", c.out}}}};
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config& c,
                   const std::vector<Datapath>& units) {
    const QFormat nf = n_register(c, units, L.fixed)->built;
    const int lf = c.log_frac, yf = c.y_frac, xf = c.exp_frac;
    const int wi = L.in.width(), wo = L.out.width(), wn = nf.width();
    const Widths w = widths(c, nf);
    const int ebits = w.ebits;
    const int lw = lf + 1;                 // log2(1 + x) in [0, 1]: 1.0 at the last node
    const int log_r = w.log_r;             // interpolation bits of the mantissa
    const int log2t_w = lf + w.log2t_int;  // signed log2 t
    const int yint = w.yint;               // |y| <= n_max fi, signed
    const int xw = xf + 2;                 // 2^x in [1, 2]: 2.0 at the last node
    const int exp_r = w.exp_r;

    // Stage 1: normalise t, read log2 at the segment's two ends.
    const Seg z = b.lzd(wi, "stage 1: leading-one detector");
    const Seg sh = b.shifter(wi, ebits, "stage 1: normalisation shifter");
    // The log2 and exp2 tables are the same for every material; each is read at the segment's
    // two ends, one even and one odd entry: an even and an odd ROM bank, each read once, and the
    // muxes that put their words in order (banked_rom, as units/pow/rtl.cpp writes them).
    const PowTables& tabs = *units.front().tables();
    const Seg lt = banked_rom(b, tabs.log_table, lw, "stage 1: log2 table");
    b.op("lzd");
    b.op("shift");
    b.op("table_read", 2);
    b.reg(2 * lw + log_r + ebits + L.group_bits,
          "stage 1: log2 nodes, remainder, exponent, group id");
    b.stage("stage 1", {z, sh, lt});

    // Stage 2: log2 interpolation; the n register read beside it.
    std::vector<Seg> p2;
    if (log_r > 0) {
      p2.push_back(b.adder(lw + 1, "stage 2: log2 node difference"));
      p2.push_back(b.multiplier(lw + 1, log_r, "stage 2: log2 interpolation", 1, true));
      b.op("add");
      b.op("mul");
    }
    p2.push_back(b.adder(lw, "stage 2: + log2 node"));
    b.op("add");
    // The RTL's n table and register hold the key's whole format (units/pow/rtl.cpp): as a ROM
    // its constants fold to the scene's bits; as registers (tables=ram) every bit is stored,
    // carried and multiplied.
    const int wn_ram = L.tables_ram ? c.n_format.width() : wn;
    const Seg n = b.slot_table(L.groups, wn_ram, 1, true, "stage 2: n table (per datapath group)");
    b.op("table_read");
    p2.front() = parallel(p2.front(), n);
    b.reg(log2t_w + wn_ram, "stage 2: log2 t, n");
    b.stage("stage 2", p2);

    // Stage 3: y = n log2 t, rounded to y_frac in the tree.
    // n from a ROM of known contents unless the chip loads it (builder.h, table_multiplier).
    std::vector<std::int64_t> ns;
    for (const PowUnit& u : units) ns.push_back(u.n_raw());
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    const Seg my = known ? b.table_multiplier(log2t_w, ns, "stage 3: n log2 t", true)
                         : b.multiplier(wn_ram, log2t_w, "stage 3: n log2 t", 1, true);
    b.op("mul");
    b.reg(yint + yf, "stage 3: y");
    b.stage("stage 3", {my});

    // Stage 4: exp2 nodes of the fraction of y.
    const Seg et = banked_rom(b, tabs.exp_table, xw, "stage 4: exp2 table");
    b.op("table_read", 2);
    b.reg(2 * xw + exp_r + yint, "stage 4: exp2 nodes, remainder, integer part of y");
    b.stage("stage 4", {et});

    // Stage 5: exp2 interpolation, shift by the integer part, round, clamp.
    std::vector<Seg> p5;
    if (exp_r > 0) {
      p5.push_back(b.adder(xw + 1, "stage 5: exp2 node difference"));
      p5.push_back(b.multiplier(xw + 1, exp_r, "stage 5: exp2 interpolation", 1, true));
      b.op("add");
      b.op("mul");
    }
    p5.push_back(b.adder(xw, "stage 5: + exp2 node"));
    // Beside the interpolation (pow/rtl.cpp): the shift amount from y's integer part, its range
    // checks (nothing left, no shift) and the decoded rounding half of the variable shift.
    b.adder(yint, "stage 5: shift amount");
    b.comparator(yint, "stage 5: shift range check (all shifted out)");
    b.comparator(yint, "stage 5: shift range check (no shift)");
    b.gates(xw, "stage 5: rounding half decoder");
    // The RTL shifts a 64-bit word (exp2 plus the decoded rounding half, which reaches bit 62) by
    // up to 63 and compares all of it with 1.0: Yosys keeps the whole 64 x 6 shifter.
    p5.push_back(b.shifter(64, 6, "stage 5: output shifter (64 bits, round half up)"));
    // The compare with 1.0 reads the rounded value, but ABC overlaps it with the incrementer's
    // carries: on the calibration set stage 5's depth is that of the path without it.
    // Placed one statement each: as two arguments of one call their order in the inventory would
    // be the compiler's (GCC and clang evaluate arguments in opposite orders).
    const Seg above_one = b.comparator(64, "stage 5: above 1.0 (the 64-bit shifted word)");
    const Seg increment = b.adder(wo + 1, "stage 5: rounding incrementer");
    p5.push_back(parallel(increment, above_one));
    p5.push_back(b.mux(wo, 2, "stage 5: clamp to 1"));
    b.op("add", 2);
    b.op("shift");
    b.reg(wo + xw, "stage 5: result, exp2 (shown beside it)");
    b.stage("stage 5", p5);
  }

  static std::string rtl(const hdl::DatapathPorts& p, const Config&,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    return pow_rtl(p, units, layout);
  }
  static nlohmann::json describe_slot(const Datapath& u) {
    return {{"n", u.shininess_q()},
            {"table_bits", u.table_bits()},
            {"log_error", u.log_error()},
            {"exp_error", u.exp_error()},
            {"error_bound", u.error_bound()}};
  }
  static double error_bound(const Datapath& u) { return u.error_bound(); }
  // model = t_q^n_q (t clamped to [0, 1]) and float_model = t^n, with n, n_q >= 0.
  static bool models_monotone(const Datapath&) { return true; }
};

}  // namespace

const UnitDescription& pow_unit() {
  static const DescriptionOf<Pow> description;
  return description;
}

}  // namespace glint
