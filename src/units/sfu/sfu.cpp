// sfu: keys, build, timing, stage layout, cost inventory and description of the highlight as a
// Tesla-class GPU computes it: MUFU.LG2, FMUL by n, RRO.EX2, MUFU.EX2 (units/sfu/tesla_sfu.h), then
// the conversion to the output format.
//
// Hardware (L = 5, II 1), one stage per operation. The lane holds the parts one highlight uses, as
// if it had an SFU of its own: stage 1 the int-to-float conversion of t and the lg2 interpolator
// (64 x 52-bit table, 17-bit truncated squarer, B r and C r^2 multipliers, the sum, the exponent
// added in, the one's complement and the normalisation); stage 2 the n register and the fp32
// multiplier; stage 3 RRO's shifter; stage 4 the ex2 interpolator; stage 5 the shift to the
// output format, rounding and clamp. A GPU shares one SFU among four SPs and one interpolator
// among five functions: what a highlight occupies of that hardware is stated beside the lane's
// price (hardware_share below), not folded into it.
#include "units/sfu/sfu.h"

#include <fmt/format.h>

#include <optional>

#include "units/sfu/datapath.h"
#include "units/sfu/rtl.h"
#include "units/unit_set.h"

namespace glint {
namespace {

constexpr int kCoefA = 26, kCoefB = 16, kCoefC = 10;  // Oberman & Siu's widths
constexpr int kWord = kCoefA + kCoefB + kCoefC;
constexpr QFormat kFp32 = uq(32, 0);  // an fp32 register, shown as its bit pattern

// A table's words as the ROM stores them: A, B and C side by side.
std::vector<std::int64_t> table_words(const tesla_sfu::Table& t) {
  std::vector<std::int64_t> words;
  for (const auto& k : t) {
    const auto field = [](std::int64_t v, int w) { return v & ((std::int64_t{1} << w) - 1); };
    // lg2's C is negative: stored as its magnitude and subtracted (units/sfu/rtl.cpp).
    words.push_back(field(k.a, kCoefA) << (kCoefB + kCoefC) | field(k.b, kCoefB) << kCoefC |
                    field(k.c < 0 ? -k.c : k.c, kCoefC));
  }
  return words;
}

// One quadratic interpolator A + B r + C r^2 (Oberman & Siu's, one per function in the lane).
// `sum_w`: the width of the sum as the function forms it.
std::vector<Seg> interpolator(CostBuilder& b, const tesla_sfu::Table& table, int sum_w,
                              const std::string& where) {
  const Seg rom = b.rom(table_words(table), kWord, where + ": 64 x 52-bit table (A, B, C)");
  // 17 rows of r, each truncated to its bits of weight 2^18 and up: about half a 17 x 17 array.
  const Seg sq =
      b.multiplier(tesla_sfu::kOffsetBits, 9, where + ": 17-bit truncated squarer (r^2)");
  const Seg br = b.multiplier(kCoefB, tesla_sfu::kOffsetBits, where + ": B r", 1, true);
  const Seg cr = b.multiplier(kCoefC, tesla_sfu::kOffsetBits, where + ": C r^2", 1, true);
  const Seg sum = b.adder(sum_w, where + ": A + B r + C r^2 + rounding constant (3:2 and CPA)");
  b.adder(sum_w, where + ": A + B r + C r^2 (carry-save row)");
  b.op("table_read");
  b.op("mul", 3);
  b.op("add", 2);
  return {parallel(series({rom, br}), series({sq, cr})), sum};
}

struct Sfu : UnitKindDefaults {
  using Config = SfuConfig;
  using Datapath = SfuUnit;
  static constexpr const char* kName = "sfu";
  static constexpr const char* kSummary =
      "NVIDIA Tesla-class GPU: MUFU.LG2, FMUL by n, RRO.EX2, MUFU.EX2 (bit-exact), to fixed";

  // One --unit away: in the default set it would change every default report and golden.
  static constexpr bool kDefaultSet = false;
  using Keys = SfuKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"narrow", "in=uq1.12,out=uq1.10,n=uq10.2",
       "--vectors traces/multi_light.vec --sink-ready 0.5"},
      {"ram", "tables=ram", "--vectors traces/blinn_colored.vec --sink-ready 0.6"},
      // Every code from t = 0 through the datapath, and outputs finer than fp32's significand
      // (to_fixed's left shift).
      {"skip_off_wide_out", "skip=off,in=uq1.17,out=uq1.30",
       "--vectors traces/contract_cases.vec --sink-ready 0.9 --seed 11"}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    SfuConfig c;
    c.in = common.in;
    c.out = common.out;
    c.skip = common.skip;
    c.n_format = keys.read(Keys::n);
    nlohmann::json config = common_config(common);
    put_key(config, Keys::n, c.n_format);
    // lg2, fmul, pre (RRO.EX2), ex2, to_fixed: one operation a stage, as the shader issues them.
    const UnitTiming timing{5, 1, 0};
    auto units = build_per_group<SfuUnit>(c, plan.groups);
    return make_unit_set<Sfu>(common, std::move(config), c, std::move(units), plan, timing);
  }

  static std::optional<NRegister> n_register(const Config& c, const std::vector<Datapath>& units,
                                             bool fixed) {
    std::vector<std::int64_t> raw;
    std::vector<double> target;
    for (const SfuUnit& u : units) {
      raw.push_back(u.n_raw());
      target.push_back(u.shininess());
    }
    return elaborate_n_register(c.n_format, raw, target, fixed);
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>&, UnitTiming) {
    return {input_stage(),
            {"lg2", 1, 1, {{"lg2", kFp32}}},
            {"fmul", 2, 2, {{"n", kFp32}, {"product", kFp32}}},
            {"pre", 3, 3, {{"pre", kFp32}}},
            {"ex2", 4, 4, {{"ex2", kFp32}}},
            {"to_fixed", 5, 5, {{"result", c.out}}}};
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config&,
                   const std::vector<Datapath>& units) {
    const int wi = L.in.width(), wo = L.out.width();

    // Stage 1: t to fp32 (leading-one detector, normalisation shift), lg2 of it.
    std::vector<Seg> p1;
    p1.push_back(b.lzd(wi, "stage 1: t to fp32: leading-one detector"));
    p1.push_back(b.shifter(wi, clog2(wi), "stage 1: t to fp32: normalisation shifter"));
    b.op("lzd");
    b.op("shift");
    // lg2 forms its sum in 36 fraction bits plus the exponent's 7 integer bits (tesla_sfu.cpp).
    for (const Seg& s : interpolator(b, tesla_sfu::kLg2Table, 43, "stage 1: lg2")) p1.push_back(s);
    p1.push_back(b.gates(43, "stage 1: lg2: one's complement of a negative sum"));
    p1.push_back(b.lzd(43, "stage 1: lg2: leading-one detector"));
    p1.push_back(b.shifter(43, 6, "stage 1: lg2: normalisation shifter"));
    b.adder(8, "stage 1: lg2: exponent");
    b.op("lzd");
    b.op("shift");
    b.reg(32, "stage 1: lg2 t (fp32)");
    b.stage("stage 1", p1);

    // Stage 2: FMUL by n, read from a table of n's fp32 patterns, one per datapath group (its
    // sign bit is always 0: 31 bits stored).
    std::vector<std::int64_t> ns;
    for (const SfuUnit& u : units) ns.push_back(u.n_fp32());
    const Seg n = b.slot_table(L.groups, 31, 1, true, "stage 2: n table, fp32 (per datapath group)",
                               L.tables_ram ? nullptr : &ns);
    b.op("table_read");
    // n's significand from a ROM of known contents unless the chip loads it: one material's is a
    // constant, and Yosys builds rows for its one bits only (builder.h, table_multiplier).
    std::vector<std::int64_t> sig;
    for (std::int64_t v : ns) sig.push_back(0x800000 | (v & 0x7fffff));
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    const Seg mul =
        known ? b.table_multiplier(24, sig, "stage 2: fp32 significand multiplier 24 x n's")
              : b.multiplier(24, 24, "stage 2: fp32 significand multiplier 24 x 24");
    const Seg rnd = b.adder(25, "stage 2: round to nearest even");
    b.adder(9, "stage 2: exponent sum");
    b.mux(24, 2, "stage 2: normalise by one bit");
    b.op("mul");
    b.op("add", 2);
    b.reg(32, "stage 2: product (fp32)");
    b.stage("stage 2", {n, mul, rnd});

    // Stage 3: RRO.EX2: the significand shifted to 7.23 fixed point, range checks.
    const Seg rro = b.shifter(30, 5, "stage 3: RRO: significand to 7.23 fixed point");
    b.comparator(8, "stage 3: RRO: |x| >= 128 and underflow checks");
    b.op("shift");
    b.reg(32, "stage 3: pre (sign, 7.23)");
    b.stage("stage 3", {rro});

    // Stage 4: ex2: complement of a negative fraction, interpolation, the integer part as the
    // exponent.
    std::vector<Seg> p4;
    p4.push_back(b.gates(23, "stage 4: ex2: complement of a negative fraction"));
    for (const Seg& s : interpolator(b, tesla_sfu::kEx2Table, 40, "stage 4: ex2")) p4.push_back(s);
    b.adder(8, "stage 4: ex2: exponent");
    b.reg(32, "stage 4: ex2 (fp32)");
    b.stage("stage 4", p4);

    // Stage 5: fp32 to the output format: shift by the exponent, round to nearest even, clamp.
    std::vector<Seg> p5;
    p5.push_back(b.adder(8, "stage 5: shift amount"));
    p5.push_back(b.shifter(std::max(wo, 24) + 2, 5, "stage 5: significand to the output's ulp"));
    p5.push_back(b.adder(wo + 1, "stage 5: rounding incrementer (ties to even)"));
    p5.push_back(b.mux(wo, 2, "stage 5: clamp to 1"));
    b.op("shift");
    b.op("add");
    b.reg(wo, "stage 5: result");
    b.stage("stage 5", p5);
  }

  // The lane's price is its own (two interpolators, fully pipelined, one highlight a cycle); a GPU
  // has neither of them to itself. What one highlight occupies of the shared SFU, stated as such:
  // its operations and the part of the SFU's table they read (Oberman & Siu: one interpolator and
  // one 448 x 52-bit table serve five functions; Lindholm et al.: two SFUs beside eight SPs).
  static nlohmann::json hardware_share(const Config&) {
    constexpr int kUsed = 2 * tesla_sfu::kSegments, kSfuWords = 448;
    return {{"statement",
             fmt::format("share of a GPU SFU, not this lane's price: a highlight issues 2 SFU "
                         "operations (MUFU.LG2, MUFU.EX2) plus RRO.EX2 and an FMUL, and reads {} "
                         "of the SFU's {} x {}-bit table words ({:.0f} %); a Tesla SM has 2 SFUs "
                         "beside 8 SPs (Oberman & Siu 2005; Lindholm et al. 2008)",
                         kUsed, kSfuWords, kWord, 100.0 * kUsed / kSfuWords)},
            {"sfu_operations", {"MUFU.LG2", "MUFU.EX2"}},
            {"other_operations", {"RRO.EX2", "FMUL"}},
            {"table_words_used", kUsed},
            {"table_words", kSfuWords},
            {"table_word_bits", kWord},
            {"table_share", static_cast<double>(kUsed) / kSfuWords},
            {"sfus_per_sm", 2},
            {"sps_per_sm", 8},
            {"sources",
             {"S. F. Oberman, M. Y. Siu, \"A high-performance area-efficient multifunction "
              "interpolator\", ARITH-17, 2005: one quadratic interpolator and a 448 x 52-bit "
              "table shared by five functions",
              "E. Lindholm, J. Nickolls, S. Oberman, J. Montrym, \"NVIDIA Tesla: a unified "
              "graphics and computing architecture\", IEEE Micro 28(2), 2008: 2 SFUs per SM of 8 "
              "SPs"}}};
  }

  static std::string rtl(const hdl::DatapathPorts& p, const Config&,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    return sfu_rtl(p, units, layout);
  }
  static nlohmann::json describe_slot(const Datapath& u) {
    return {{"n", u.shininess_q()},
            {"n_fp32", fmt::format("0x{:08x}", u.n_fp32())},
            {"error_bound", u.error_bound()}};
  }
  static double error_bound(const Datapath& u) { return u.error_bound(); }
  // model = t_q^n_q (0 at t <= 0) and float_model = t^n: the fp32 datapath itself is not the
  // model, so its own order does not enter.
  static bool models_monotone(const Datapath&) { return true; }
};

}  // namespace

const UnitDescription& sfu_unit() {
  static const DescriptionOf<Sfu> description;
  return description;
}

}  // namespace glint
