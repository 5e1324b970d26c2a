// hast: keys, build, timing, stage layout, cost inventory and description of Hast's chain.
//
// Hardware (L = d, II 1): the u scaler (k table, subtractor Wi, multiplier Wi x Wk with Wk the
// widest datapath group's k_int_bits + k_frac_bits, clamp), then d - 1 multipliers (fh + 1) x
// (fh + 1), fh = Fo + guard; each rounds in its tree (to fh bits, the last one to the output
// format). Keys match= and root= change only the per-group root in the k/root tables (units/
// match.h); d=auto adds a per-group d table and a 2:1 operand mux (u or 1.0) in front of every
// chain multiplier, the chain as long as the largest d chosen. A datapath group (units/
// slot_plan.h) is a material's: its slots share k, root and d.
#include "units/hast/hast.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "units/hast/datapath.h"
#include "units/hast/rtl.h"
#include "units/match.h"
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

  using Keys = HastKeys;
  static constexpr CosimCase kCosimCases[] = {
      {"default", "", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"d3_materials", "d=3", "--vectors traces/blinn_colored.vec"},
      {"auto_d", "d=auto,match=minimax", "--vectors traces/multi_light.vec --sink-ready 0.5"},
      {"d1_narrow", "d=1,in=uq1.9,out=uq1.8,guard=0",
       "--vectors traces/gaussian.vec --sink-ready 0.4"},
      {"ram", "tables=ram", "--vectors traces/phong_basic.vec --sink-ready 0.6"},
      {"ram_auto_d", "tables=ram,d=auto,match=minimax,in=uq1.12",
       "--vectors traces/blinn_colored.vec --sink-ready 0.5"}};

  // Each slot's root and order from the keys (root >= 0: explicit); solved once per distinct n.
  static std::vector<HastSlot> slot_roots(const KeyReader& keys, MatchMode match, bool auto_d,
                                          int d, double root,
                                          const std::vector<MaterialParams>& slots) {
    std::vector<HastSlot> out;
    out.reserve(slots.size());
    std::unordered_map<double, HastSlot> solved;
    for (const MaterialParams& m : slots) {
      for_slot(m, [&] {
        if (root >= 0) {
          out.push_back(HastSlot{d, root, false});
          return;
        }
        if (match == MatchMode::kNone) {
          out.push_back(HastSlot{d, 0.0, true});
          return;
        }
        const double n = m.shininess;
        if (!(n > 0) || !std::isfinite(n))
          // refusal: hast.match_shininess
          keys.fail("match", to_string(match),
                    fmt::format("needs the material's shininess n > 0, got {}", n));
        auto it = solved.find(n);
        if (it == solved.end()) {
          HastSlot s{d, 0.0, false};
          if (match == MatchMode::kWidth) {
            s.root = hast_width_root(n, d);
          } else if (auto_d) {
            const HastMatch j = hast_minimax_joint(n, 16);
            s.d = j.d;
            s.root = j.tau;
          } else {
            s.root = hast_minimax_root(n, d);
          }
          it = solved.emplace(n, s).first;
        }
        out.push_back(it->second);
      });
    }
    return out;
  }

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    const std::vector<MaterialParams>& groups = plan.groups;
    const std::string* d_key = keys.find("d");
    const bool auto_d = d_key && *d_key == "auto";
    HastConfig c{common.in, common.out, auto_d ? 16 : keys.read(Keys::d), keys.read(Keys::guard),
                 common.skip};
    const MatchMode match = parse_match_mode(keys.read(Keys::match));
    const std::string* root_key = keys.find("root");
    const std::optional<double> root_given = keys.read(Keys::root);
    const double root = root_given.value_or(-1.0);  // < 0: no explicit root
    if (root >= 0 && match != MatchMode::kNone)
      // refusal: hast.root_match
      keys.fail("root", *keys.find("root"),
                fmt::format("an explicit root cannot be combined with match={}, which chooses "
                            "the root (drop one of them)",
                            to_string(match)));
    if (auto_d && match != MatchMode::kMinimax)
      // refusal: hast.d_auto
      keys.fail("d", "auto",
                fmt::format("d=auto chooses d by minimax: it needs match=minimax (given "
                            "match={}{})",
                            to_string(match), root >= 0 ? ", root=" + *root_key : ""));
    // Roots per datapath group: match=none takes the group's Källberg threshold, the smallest tau
    // of its slots, so the chain's f is > 0 wherever any of their comparators lets t through.
    const std::vector<HastSlot> roots = slot_roots(keys, match, auto_d, c.d, root, groups);
    if (auto_d) {
      // The chain is as long as the largest order any slot chose.
      c.per_slot_d = true;
      c.d = 1;
      for (const HastSlot& s : roots) c.d = std::max(c.d, s.d);
    }
    c.guard_auto = c.guard < 0;
    if (c.guard < 0) c.guard = hast_default_guard(c.d);
    const KeyValue root_from =
        root >= 0 ? KeyValue{"root", *root_key} : KeyValue{"match", std::string(to_string(match))};
    c.root_source = key_values({root_from});
    nlohmann::json config = common_config(common);
    if (auto_d) {
      // The key as given (each slot has its own d); the chain's length is described beside it,
      // outside the spec.
      config[std::string(Keys::d.name)] = "auto";
      config["chain"] = c.d;
    } else {
      put_key(config, Keys::d, c.d);
    }
    put_key(config, Keys::guard, c.guard);
    put_key(config, Keys::match, to_string(match));
    put_key(config, Keys::root, root_given);
    // u scaler stage, then d - 1 multiplier stages.
    const UnitTiming timing{c.d, 1, 0};
    std::vector<HastUnit> units;
    units.reserve(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g)
      for_slot(groups[g], [&] { units.emplace_back(c, groups[g], roots[g]); });
    return make_unit_set<Hast>(common, std::move(config), c, std::move(units), plan, timing);
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
    // The k of every group: the ROM's contents unless the chip loads them.
    std::vector<std::int64_t> ks;
    for (const HastUnit& u : units) ks.push_back(u.scaler().k_raw());
    const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
    std::vector<Seg> path = u_scaler_cost(b, L, wk, fh, known ? &ks : nullptr);
    // d=auto: each slot's order, read with its k and carried down the chain, where stage s
    // multiplies by u while s <= d_s and by 1.0 after (a 2:1 operand mux per stage).
    const int db = c.per_slot_d ? clog2(d + 1) : 0;
    if (c.per_slot_d) {
      // Read beside the k table: off the stage's path.
      b.slot_table(L.groups, db, 1, true, "stage 1: d table (per datapath group)");
      b.op("table_read");
    }
    if (d == 1) {
      path.push_back(b.adder(wo + 1, "stage 1: rounding incrementer"));
      b.op("add");
      b.reg(wo, "stage 1: result");
    } else {
      b.reg(fh + 1 + db, "stage 1: u");
    }
    b.stage("stage 1", path);
    for (int s = 2; s <= d; ++s) {
      // u^(s-1) * u, rounded in the tree (to fh bits, the last one to the output format).
      std::vector<Seg> seg;
      if (c.per_slot_d) {
        seg.push_back(b.mux(fh + 1, 2, fmt::format("stage {}: operand u or 1.0 (d per slot)", s)));
        if (s < d) b.reg(db, fmt::format("stage {}: d", s));
      }
      seg.push_back(b.multiplier(fh + 1, fh + 1, fmt::format("stage {}: chain multiplier", s)));
      b.op("mul");
      if (s < d)
        b.reg(2 * (fh + 1), fmt::format("stage {}: u and u^{}", s, s));
      else
        b.reg(wo, fmt::format("stage {}: result", s));
      b.stage(fmt::format("stage {}", s), seg);
    }
  }

  static nlohmann::json describe_slot(const Datapath& u) {
    // n: the material's shininess (what match= matched); root: the root exact (the material's
    // Källberg threshold for match=none), root_raw: as the u scaler holds it.
    return {{"n", u.shininess()},
            {"d", u.order()},
            {"root", u.root()},
            {"root_raw", u.scaler().root_raw()},
            {"k", u.scaler().k_value()},
            {"k_int_bits", u.scaler().k_int_bits()},
            {"k_frac_bits", u.scaler().k_frac()}};
  }
  static bool carries_root(const Config&) { return true; }
  // model = u^d with u the scaler's exact value, non-decreasing and in [0, 1]; float_model =
  // ((t - tau) / (1 - tau))^d above tau, 0 below.
  static bool models_monotone(const Datapath&) { return true; }
  static std::string rtl(const hdl::DatapathPorts& p, const Config& c,
                         const std::vector<Datapath>& units, const StageLayout& layout) {
    return hast_rtl(p, c, units, layout);
  }
};

}  // namespace

const UnitDescription& hast_unit() {
  static const DescriptionOf<Hast> description;
  return description;
}

}  // namespace glint
