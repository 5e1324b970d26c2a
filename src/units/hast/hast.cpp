// hast: keys, build, timing, stage layout, cost inventory and description of Hast's chain.
//
// Hardware (L = d, II 1): the u scaler (k table, subtractor Wi, multiplier Wi x Wk with Wk the
// widest slot's k_int_bits + k_frac_bits, clamp), then d - 1 multipliers (fh + 1) x (fh + 1),
// fh = Fo + guard; each rounds in its tree (to fh bits, the last one to the output format).
#include "units/hast/hast.h"

#include <fmt/format.h>

#include <algorithm>

#include "units/hast/datapath.h"
#include "units/u_scaler_cost.h"
#include "units/unit_set.h"

namespace glint {
namespace {

struct Hast : UnitKindDefaults {
  using Config = HastConfig;
  using Datapath = HastUnit;
  static constexpr const char* kName = "hast";
  static constexpr const char* kSummary =
      "Hast kappa (t - tau)^d as u^d, u = (t - tau)/(1 - tau): multiplier chain";

  static std::vector<UnitKey> keys() {
    return {{"d", "exponent: d - 1 multipliers", "4"},
            {"guard", "guard bits of the chain (auto: ceil(log2(2d-2)) + 1)", "auto"}};
  }

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const std::vector<MaterialParams>& slots) {
    HastConfig c{common.in, common.out, keys.integer("d", 4, 1, 16),
                 keys.integer("guard", -1, 0, 20, true), common.skip};
    if (c.guard < 0) c.guard = hast_default_guard(c.d);
    nlohmann::json config = common_config(common);
    config["d"] = c.d;
    config["guard"] = c.guard;
    // u scaler stage, then d - 1 multiplier stages.
    const UnitTiming timing{c.d, 1, 0};
    auto units = build_per_slot<HastUnit>(c, slots);
    return make_unit_set<Hast>(common, std::move(config), c, std::move(units), slots, timing);
  }

  static std::vector<Stage> stages(const Config& c, const std::vector<Datapath>&, UnitTiming) {
    const QFormat uf = uq(1, c.out.frac_bits + c.guard);
    std::vector<Stage> s{input_stage()};
    if (c.d == 1) {
      s.push_back({"scale", 1, 1, {{"result", c.out}}});
      return s;
    }
    s.push_back({"scale", 1, 1, {{"u", uf}}});
    for (int k = 2; k <= c.d; ++k) {
      Stage m{"mul" + std::to_string(k - 1), k, k, {}};
      if (k < c.d)
        m.registers = {{"u", uf}, {"power", uf}};  // u and u^k
      else
        m.registers = {{"result", c.out}};
      s.push_back(std::move(m));
    }
    return s;
  }

  static void cost(CostBuilder& b, const LaneShape& L, const Config& c,
                   const std::vector<Datapath>& units) {
    const int d = c.d;
    const int fh = L.out.frac_bits + c.guard;
    const int wo = L.out.width();
    int wk = 0;
    for (const HastUnit& u : units)
      wk = std::max(wk, u.scaler().k_int_bits() + u.scaler().k_frac());
    std::vector<Seg> path = u_scaler_cost(b, L, wk, fh);
    if (d == 1) {
      path.push_back(b.adder(wo + 1, "stage 1: rounding incrementer"));
      b.op("add");
      b.reg(wo, "stage 1: result");
    } else {
      b.reg(fh + 1, "stage 1: u");
    }
    b.stage("stage 1", path);
    for (int s = 2; s <= d; ++s) {
      // u^(s-1) * u, rounded in the tree (to fh bits, the last one to the output format).
      const Seg mul = b.multiplier(fh + 1, fh + 1, fmt::format("stage {}: chain multiplier", s));
      b.op("mul");
      if (s < d)
        b.reg(2 * (fh + 1), fmt::format("stage {}: u and u^{}", s, s));
      else
        b.reg(wo, fmt::format("stage {}: result", s));
      b.stage(fmt::format("stage {}", s), {mul});
    }
  }

  static nlohmann::json describe_slot(const Datapath& u) {
    return {{"root_raw", u.scaler().root_raw()},
            {"k", u.scaler().k_value()},
            {"k_int_bits", u.scaler().k_int_bits()},
            {"k_frac_bits", u.scaler().k_frac()}};
  }
  static bool carries_root(const Config&) { return true; }
};

}  // namespace

const UnitDescription& hast_unit() {
  static const DescriptionOf<Hast> description;
  return description;
}

}  // namespace glint
