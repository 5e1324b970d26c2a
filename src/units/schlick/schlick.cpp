// schlick: keys, build, timing, stage layout, cost inventory and description of Schlick's
// t / (n - n t + t) with an exact, correctly rounded divider.
//
// Hardware (L = q + 2, q = Fo + 2 quotient bits: the integer bit, Fo fraction bits, the rounding
// bit): stage 1 forms D = n (1 - t) + t (n table, multiplier Wn x (Fi + 1): 1 - t as the complement
// plus a correction row, adder Wd = max(Wn, Fn + 1) + Fi); the divider is pipelined (one row and a
// register of remainder, divisor and quotient so far per stage, II 1) or iterative (one radix-2
// row reused q times with remainder/divisor/quotient/counter registers and a load mux, II = q);
// the last stage rounds (Q + 1) >> 1 with an incrementer of q bits and clamps to 1.
//
// Key match= picks what the n register holds per datapath group: the material's n (Schlick's own
// use), or the n' matching t^n by minimax or by half-width (units/match.h); the hardware is the
// same.
#include "units/schlick/schlick.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "units/schlick/datapath.h"
#include "units/schlick/rtl.h"
#include "units/unit_set.h"

namespace glint {
namespace {

// The datapath's config plus the divider kind, which changes timing and cost, not the result.
struct SchlickSetup {
  SchlickConfig datapath;
  bool iterative = false;
};

struct Schlick : UnitKindDefaults {
  using Config = SchlickSetup;
  using Datapath = SchlickUnit;
  static constexpr const char* kName = "schlick";
  static constexpr const char* kSummary =
      "Schlick t/(n - n t + t) with an exact, correctly rounded divider";

  using Keys = SchlickKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.7"},
      {"iterative", "divider=iterative,n=uq10.2", "--vectors traces/gaussian.vec"},
      {"minimax_narrow", "match=minimax,in=uq1.12,out=uq1.10",
       "--vectors traces/hard_cases.vec --sink-ready 0.4"},
      {"ram", "tables=ram", "--vectors traces/phong_basic.vec --sink-ready 0.7"},
      {"ram_iterative", "tables=ram,divider=iterative,in=uq1.12",
       "--vectors traces/multi_light.vec"}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    SchlickConfig c{common.in, common.out, keys.read(Keys::n), common.skip};
    c.match = parse_match_mode(keys.read(Keys::match));
    nlohmann::json config = common_config(common);
    put_key(config, Keys::n, c.n_format);
    put_key(config, Keys::match, to_string(c.match));
    const std::string divider = keys.read(Keys::divider);
    put_key(config, Keys::divider, divider);
    // Denominator multiply-add stage, q quotient bits, rounding stage.
    const int q = common.out.frac_bits + 2;
    const bool iterative = divider == "iterative";
    const UnitTiming timing{q + 2, iterative ? q : 1, 0};
    // n' per datapath group, solved once per distinct n (materials often share one; minimax
    // costs ~30 us).
    std::vector<SchlickUnit> units;
    units.reserve(plan.groups.size());
    std::unordered_map<double, double> n_prime;
    for (const MaterialParams& m : plan.groups) {
      for_slot(m, [&] {
        auto it = n_prime.find(m.shininess);
        if (it == n_prime.end())
          it = n_prime.emplace(m.shininess, schlick_n_prime(c.match, m.shininess)).first;
        units.emplace_back(c, m, it->second);
      });
    }
    return make_unit_set<Schlick>(common, std::move(config), SchlickSetup{c, iterative},
                                  std::move(units), plan, timing);
  }

  // D in units of 2^-(Fn + Fi): D = n (1 - t) + t < max(n, 1) needs max(Wn, Fn + 1) + Fi bits.
  static QFormat denominator_format(const QFormat& nf, const QFormat& in) {
    return uq(std::max(nf.width(), nf.frac_bits + 1) - nf.frac_bits, nf.frac_bits + in.frac_bits);
  }

  // The n register holds every group's n'_q exactly in the bits those values use (units/
  // n_register.h). S = t / (n (1 - t) + t) is the same quotient when n and t are scaled alike, so
  // D and the divider shrink with it: Q = T 2^(Fn + Fo) / D does not depend on Fn.
  static std::optional<NRegister> n_register(const Config& c, const std::vector<Datapath>& units,
                                             bool fixed) {
    std::vector<std::int64_t> raw;
    std::vector<double> target;
    for (const SchlickUnit& u : units) {
      raw.push_back(u.n_raw());
      target.push_back(u.n_prime());
    }
    return elaborate_n_register(c.datapath.n_format, raw, target, fixed);
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>&, UnitTiming) {
    const SchlickConfig& d = c.datapath;
    const QFormat df = denominator_format(d.n_format, d.in);
    const QFormat rf = uq(df.int_bits + 1, df.frac_bits);  // partial remainder < 2 D
    const int q = d.out.frac_bits + 2;
    std::vector<Stage> s{input_stage(), {"mac", 1, 1, {{"D", df}}}};
    if (c.iterative) {
      // One shift register for every iteration: its k bits are an integer until the last.
      s.push_back({"div", 2, q + 1, {{"remainder", rf}, {"quotient", uq(q, 0)}}});
    } else {
      // After quotient bit k the register holds k bits of Q = S 2^(Fo + 1) (S at Fo + 1 fraction
      // bits): S to k - 1 fraction bits, so each stage shows the quotient converging to S.
      for (int k = 1; k <= q; ++k)
        s.push_back({"q" + std::to_string(k - 1),
                     1 + k,
                     1 + k,
                     {{"remainder", rf}, {"quotient", uq(1, k - 1)}}});
    }
    s.push_back({"round", q + 2, q + 2, {{"result", d.out}}});
    return s;
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config& c,
                   const std::vector<Datapath>& units) {
    const bool iterative = c.iterative;
    const QFormat nf = n_register(c, units, L.fixed)->built;
    const int wi = L.in.width(), fi = L.in.frac_bits, wo = L.out.width();
    const int wn = nf.width();
    // D's width follows n's: the scene's bits in a ROM (Yosys drops D's constant-zero top bits),
    // the key's whole format when the chip loads n (every bit of D and the divider rows live).
    const int wd = denominator_format(L.tables_ram ? c.datapath.n_format : nf, L.in).width();
    const int q = L.out.frac_bits + 2;

    // Stage 1: D = n (1 - t) + t. 1 - t is the complement of t plus one: the +n correction is one
    // more row of the multiplier's tree.
    // The RTL's n table holds the key's whole format (units/schlick/rtl.cpp): as a ROM its
    // constants fold to the scene's bits; as registers (tables=ram) every bit is stored and
    // multiplied.
    const int wn_table = L.tables_ram ? c.datapath.n_format.width() : wn;
    const Seg n =
        b.slot_table(L.groups, wn_table, 1, true, "stage 1: n table (per datapath group)");
    // n from a ROM of known contents unless the chip loads it (builder.h, table_multiplier).
    std::vector<std::int64_t> ns;
    for (const SchlickUnit& u : units) ns.push_back(u.n_raw());
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    const Seg mul = known ? b.table_multiplier(fi + 1, ns, "stage 1: n (1 - t)")
                          : b.multiplier(wn_table, fi + 1, "stage 1: n (1 - t)");
    Seg add = b.adder(wd, "stage 1: + t");
    // A full multiplier (n loaded, not a constant): Yosys sums `+ t` in the product's tree, and its
    // carries run while the product's high bits settle, about half an adder's depth after it, as
    // horner's `+ c_k` (horner.cpp; here on the calibration set's tables=ram schlick lanes, 42-43
    // gates for the stage).
    if (!known) {
      add.delay /= 2;
      add.ns /= 2;
    }
    b.reg(wd + wi, "stage 1: D and t");
    b.op("table_read");
    b.op("mul");
    b.op("add");
    b.stage("stage 1", {n, mul, add});

    // Restoring division, q quotient bits; the last decides the rounding.
    b.op("div_step", q);
    const std::string span = fmt::format("stages 2-{}", q + 1);
    if (!iterative) {
      const Seg row = b.divider(q, wd, span + ": divider (pipelined, one row per stage)");
      for (int r = 1; r <= q; ++r) {
        // Partial remainder, divisor and the quotient bits so far; the last row passes only Q.
        const int carried = r < q ? (wd + 1) + wd + r : q;
        b.reg(carried, fmt::format("stage {}: divider row {}", r + 1, r));
        b.stage(fmt::format("stage {}", r + 1), {row});
      }
    } else {
      // Two rows, as the RTL writes it: the first quotient bit's (from stage 1's registers) and
      // the one the loop reuses; the numerator's bits still to bring down are shifted beside.
      const Seg row = b.divider(2, wd, span + ": divider (iterative: first row, one row reused)");
      const int counter = clog2(q + 1);
      const Seg load = b.mux(wd + 1, 2, span + ": divider load/iterate mux");
      b.state_reg(wd + 1, span + ": divider partial remainder", q);
      b.state_reg(wd, span + ": divider divisor", 1);
      b.state_reg(q, span + ": divider quotient shift register", q);
      b.state_reg(counter, span + ": divider step counter", q);
      b.state_reg(fi + 1, span + ": divider numerator bits", q);
      b.stage(span + " (divider loop)", {row, load});
    }

    // Last stage: round (Q + 1) >> 1 and clamp to 1.0.
    const Seg rnd = b.adder(q, fmt::format("stage {}: rounding incrementer", q + 2));
    const Seg over = b.comparator(q + 1, fmt::format("stage {}: above 1.0", q + 2));
    const Seg clamp = b.mux(wo, 2, fmt::format("stage {}: clamp to 1", q + 2));
    b.reg(wo, fmt::format("stage {}: result", q + 2));
    b.op("add");
    b.stage(fmt::format("stage {}", q + 2), {rnd, over, clamp});
  }

  static std::string rtl(const hdl::DatapathPorts& p, const Config& c,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    return schlick_rtl(p, units, c.iterative, layout);
  }
  static nlohmann::json describe_slot(const Datapath& u) {
    // n: the material's shininess; n_prime: what Schlick's formula uses for it (exact), n_q: the
    // register's value of n_prime.
    return {{"n", u.material_n()},
            {"n_prime", u.n_prime()},
            {"n_raw", u.n_raw()},
            {"n_q", u.shininess_q()}};
  }
  // S = t / (n - n t + t) at n_q (model) and n' (float_model), both > 0, for t clamped to
  // [0, 1]: dS/dt = n / (n - n t + t)^2 > 0.
  static bool models_monotone(const Datapath&) { return true; }
};

}  // namespace

const UnitDescription& schlick_unit() {
  static const DescriptionOf<Schlick> description;
  return description;
}

}  // namespace glint
