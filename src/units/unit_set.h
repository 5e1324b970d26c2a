// The one implementation of SpecularUnit, for every unit kind: the datapath instances (one per
// group of slots, units/slot_plan.h), the comparator in front with a threshold per slot, the batch
// loop the compiler inlines the datapath into, the staged evaluation through the same datapath
// function, and the description with its elaboration report.
//
// A kind (src/units/<unit>/<unit>.cpp) is a struct deriving from UnitKindDefaults with:
//   using Config = ...;  using Datapath = ...;      // Datapath(config, MaterialParams)
//   static constexpr const char* kName, kSummary;
//   using Keys = ...;                              // its key table (src/units/<unit>/keys.h)
//   static constexpr CosimCase kCosimCases[];      // the specs it is co-simulated with (unit.h)
//   static std::unique_ptr<SpecularUnit> build(const KeyReader&, const CommonKeys&,
//                                              const SlotPlan&);   // a datapath per plan.groups
//   static std::vector<Stage> stages(const Config&, const std::vector<Datapath>&, UnitTiming);
//   static void cost(CostBuilder&, const LaneShape&, const Config&, const std::vector<Datapath>&);
//   static nlohmann::json describe_slot(const Datapath&);
// and, where UnitKindDefaults' do not fit, error_bound, models_monotone, carries_root, n_register
// and rtl (below).
// Its Datapath has eval(t), run(t, probe) (eval is run with NoProbe), model, float_model and
// datapath_bound_ulps() (its error budget: |eval - model| in output ulps). build() reads the keys
// (KeyReader::read), writes each resolved value back (put_key) and ends with make_unit_set<Kind>,
// which also sets every slot's comparator threshold from the unit's own output
// (unit_threshold_raw) through the datapath of the slot's group. kind_check.h checks all of it at
// compile time.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cost/builder.h"
#include "hdl/verilog.h"
#include "units/keys.h"
#include "units/kind_check.h"
#include "units/lane_cost.h"
#include "units/n_register.h"
#include "units/slot_plan.h"
#include "units/unit.h"

namespace glint {

// What a kind leaves out unless it says otherwise: its contract is against its own real-valued
// model (no stated bound against t^n), its comparator carries no root to a u scaler, and it holds
// no shininess register.
struct UnitKindDefaults {
  // Run when no --unit is given. A unit outside the default set is one --unit away, and adding it
  // changes no default output.
  static constexpr bool kDefaultSet = true;
  template <class Datapath>
  static double error_bound(const Datapath&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // model() and float_model() non-decreasing in t (unit.h): not known unless the kind proves it.
  template <class Datapath>
  static bool models_monotone(const Datapath&) {
    return false;
  }
  template <class Config>
  static bool carries_root(const Config&) {
    return false;
  }
  template <class Config, class Datapath>
  static std::optional<NRegister> n_register(const Config&, const std::vector<Datapath>&, bool) {
    return std::nullopt;
  }
  // What the lane stands for in hardware it shares, stated beside its own price (sfu: the share of
  // a GPU's special-function unit one highlight uses); null: the lane is the whole of it.
  template <class Config>
  static nlohmann::json hardware_share(const Config&) {
    return nullptr;
  }
  template <class Config, class Datapath>
  static std::string rtl(const hdl::DatapathPorts&, const Config&, const std::vector<Datapath>&,
                         const StageLayout&) {
    // not from a spec: every unit in the catalogue has its generator
    throw std::invalid_argument("no Verilog generator for this unit yet");
  }
};

template <class Kind>
class UnitSet final : public SpecularUnit {
  static_assert(check_unit_kind<Kind>());

 public:
  using Config = typename Kind::Config;
  using Datapath = typename Kind::Datapath;

  UnitSet(std::string canonical, const CommonKeys& common, Config cfg,
          std::vector<Datapath> datapaths, const SlotPlan& plan, nlohmann::json config,
          UnitTiming timing)
      : name_(Kind::kName),
        canonical_(std::move(canonical)),
        in_(common.in),
        out_(common.out),
        skip_(common.skip),
        tables_ram_(common.tables_ram),
        cfg_(std::move(cfg)),
        datapaths_(std::move(datapaths)),
        group_(plan.group),
        params_(plan.params),
        group_params_(plan.groups),
        origin_(plan.origin),
        slot_capacity_(plan.slot_capacity),
        group_capacity_(plan.group_capacity),
        config_(std::move(config)),
        timing_(timing),
        layout_(Kind::stages(cfg_, datapaths_, timing_), timing_.ii, out_) {
    thresholds_.assign(group_.size(), -1);
    if (!skip_) return;
    // Each slot's own threshold through the datapath it shares: its level eps_K / c_y is its own.
    for (std::size_t s = 0; s < group_.size(); ++s) {
      const Datapath& u = datapaths_[group_[s]];
      thresholds_[s] =
          unit_threshold_raw(params_[s], in_, out_, [&u](std::int64_t t) { return u.eval(t); });
    }
  }

  const std::string& name() const override { return name_; }
  std::string canonical_spec() const override { return canonical_; }
  QFormat in_format() const override { return in_; }
  QFormat out_format() const override { return out_; }
  std::size_t slots() const override { return group_.size(); }
  std::size_t slot_capacity() const override { return slot_capacity_; }
  std::size_t group_capacity() const override { return group_capacity_; }
  std::size_t datapath_groups() const override { return datapaths_.size(); }
  std::size_t datapath_of(std::size_t s) const override { return group_[s]; }
  std::int64_t tau_raw(std::size_t s) const override { return thresholds_[s]; }
  std::int64_t eval(std::size_t s, std::int64_t t) const override { return dp(s).eval(t); }
  double model(std::size_t s, std::int64_t t) const override { return dp(s).model(t); }
  double float_model(std::size_t s, double t) const override { return dp(s).float_model(t); }
  void eval_batch(std::size_t s, const std::int64_t* t, std::int64_t* out, std::uint8_t* skipped,
                  std::size_t n) const override {
    const Datapath& u = dp(s);
    const std::int64_t tau = thresholds_[s];
    for (std::size_t i = 0; i < n; ++i) {
      const bool sk = tau_skip(t[i], tau);
      skipped[i] = sk;
      out[i] = sk ? 0 : u.eval(t[i]);
    }
  }
  void eval_staged(std::size_t s, std::int64_t t, std::int64_t* values) const override {
    // Registers a short-cut input leaves untouched (t = 0 in pow, t <= t0 in lut) read 0.
    std::fill(values, values + layout_.size(), 0);
    dp(s).run(t, StageProbe(layout_, values));
  }
  const StageLayout& stages() const override { return layout_; }
  double error_bound(std::size_t s) const override { return Kind::error_bound(dp(s)); }
  double datapath_bound_ulps(std::size_t s) const override { return dp(s).datapath_bound_ulps(); }
  bool models_monotone(std::size_t s) const override { return Kind::models_monotone(dp(s)); }
  UnitTiming timing() const override { return timing_; }
  bool comparator_enabled() const override { return skip_; }
  bool tables_ram() const override { return tables_ram_; }
  bool comparator_carries_root() const override { return Kind::carries_root(cfg_); }
  void add_cost(CostBuilder& b, const LaneShape& lane) const override {
    Kind::cost(b, lane, cfg_, datapaths_);
  }
  std::string rtl_datapath(const hdl::DatapathPorts& ports) const override {
    if (ports.groups <= datapaths_.size()) return Kind::rtl(ports, cfg_, datapaths_, layout_);
    // A chip of given capacity: the groups the input does not use hold a copy of the last one
    // until the driver loads a material there (the tables are RAMs: group_capacity() > 0 only on
    // a ram chip).
    std::vector<Datapath> all = datapaths_;
    all.resize(ports.groups, datapaths_.back());
    return Kind::rtl(ports, cfg_, all, layout_);
  }
  nlohmann::json describe() const override {
    nlohmann::json j;
    j["name"] = name_;
    j["spec"] = canonical_;
    j["config"] = config_;
    j["timing"] = {
        {"latency", timing_.latency}, {"ii", timing_.ii}, {"buffer_depth", timing_.buffer_depth}};
    nlohmann::json slots = nlohmann::json::array();
    for (std::size_t s = 0; s < group_.size(); ++s) {
      nlohmann::json slot = Kind::describe_slot(dp(s));
      slot["threshold_raw"] = thresholds_[s];
      slots.push_back(std::move(slot));
    }
    j["slots"] = std::move(slots);
    j["elaboration"] = elaboration();
    return j;
  }

 private:
  const Datapath& dp(std::size_t s) const { return datapaths_[group_[s]]; }

  // What the scene made the unit build, and why (src/eval/README.md, "Only the hardware a scene
  // needs").
  nlohmann::json elaboration() const {
    const bool fixed = slot_capacity_ > 0 || group_capacity_ > 0;
    nlohmann::json e{{"storage", tables_ram_ || fixed ? "ram" : "rom"},
                     {"slots", group_.size()},
                     {"capacity", slot_capacity_ > 0 ? slot_capacity_ : group_.size()},
                     {"sized_to", fixed ? "capacity" : "stream"},
                     {"datapath_groups", datapaths_.size()},
                     {"group_capacity", group_capacity_ > 0 ? group_capacity_ : datapaths_.size()}};
    std::vector<nlohmann::json> served(datapaths_.size(), nlohmann::json::array());
    nlohmann::json slot_list = nlohmann::json::array();
    for (std::size_t s = 0; s < group_.size(); ++s) {
      served[group_[s]].push_back(s);
      const MaterialParams& m = params_[s];
      nlohmann::json slot{{"slot", s},
                          {"name", m.name},
                          {"group", group_[s]},
                          {"tau", m.tau},
                          {"level", m.level},
                          {"always_skip", m.always_skip},
                          {"threshold_raw", thresholds_[s]}};
      if (s < origin_.size()) {
        const SlotOrigin& o = origin_[s];
        slot["material"] = o.material;
        slot["lights"] = o.lights;
        slot["c_y"] = o.c_y;
        slot["why"] = o.own_tau ? "these lights change the material's c_y: a tau of its own"
                                : "the material's threshold (every light gives it this c_y)";
      } else {
        slot["why"] = "a slot of its own";
      }
      slot_list.push_back(std::move(slot));
    }
    nlohmann::json groups = nlohmann::json::array();
    for (std::size_t g = 0; g < datapaths_.size(); ++g) {
      const MaterialParams& m = group_params_[g];
      groups.push_back({{"group", g},
                        {"name", m.name},
                        {"slots", served[g]},
                        {"built_for", {{"n", m.shininess}, {"tau", m.tau}, {"level", m.level}}},
                        {"why", served[g].size() > 1
                                    ? "one datapath for its slots, built for the smallest tau and "
                                      "level among them (the largest c_y)"
                                    : "the datapath of its slot"}});
    }
    e["groups"] = std::move(groups);
    e["slot_list"] = std::move(slot_list);
    if (const auto n = Kind::n_register(cfg_, datapaths_, fixed))
      e["n_register"] = n_register_json(*n, group_params_);
    // Every table the cost model places (units/lane_cost.h), as entries x width x banks.
    nlohmann::json tables = nlohmann::json::array();
    long long words = 0;
    for (const Primitive& p : unit_cost(*this).inventory) {
      if (p.kind != "table") continue;
      tables.push_back(
          {{"where", p.where}, {"entries", p.width_a}, {"width", p.width_b}, {"banks", p.count}});
      words += static_cast<long long>(p.width_a) * p.count;
    }
    e["tables"] = std::move(tables);
    e["table_entries"] = words;
    // Beside the lane's price in every report that has the elaboration (eval, sim, render).
    if (nlohmann::json share = Kind::hardware_share(cfg_); !share.is_null())
      e["hardware_share"] = std::move(share);
    return e;
  }

  std::string name_, canonical_;
  QFormat in_, out_;
  bool skip_;
  bool tables_ram_;
  Config cfg_;
  std::vector<Datapath> datapaths_;           // one per datapath group
  std::vector<std::uint32_t> group_;          // per slot: its group
  std::vector<MaterialParams> params_;        // per slot: its comparator's parameters
  std::vector<MaterialParams> group_params_;  // per group: what its datapath was built from
  std::vector<SlotOrigin> origin_;
  std::size_t slot_capacity_ = 0, group_capacity_ = 0;  // a chip's capacity (0: the stream's)
  nlohmann::json config_;
  UnitTiming timing_;
  StageLayout layout_;
  std::vector<std::int64_t> thresholds_;  // comparator threshold per slot (-1: never skips)
};

// The description JSON's config of the common keys; a kind's build adds its own keys.
inline nlohmann::json common_config(const CommonKeys& c) {
  using K = CommonKeyTable;
  nlohmann::json j;
  put_key(j, K::in, c.in);
  put_key(j, K::out, c.out);
  put_key(j, K::skip, c.skip);
  // Always, at its default too: the chip sets it (units/chip.h), and a report's shape must not
  // change with the chip (regress holds a golden's shape to this build's).
  j[std::string(K::tables.name)] = c.tables_ram ? "ram" : "rom";
  return j;
}

// Runs one slot's part of a build; a refusal names the slot's material (and light), so that one
// faint or extreme material in a file says which it is.
template <class F>
decltype(auto) for_slot(const MaterialParams& m, F&& f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    if (m.name.empty()) throw;
    // not from a spec: names the material of a refusal tagged where it is thrown
    throw std::invalid_argument(fmt::format("{}: {}", m.name, e.what()));
  }
}

// One datapath instance per group (plan.groups), each built from the group's params.
template <class Datapath, class Config, class... Extra>
std::vector<Datapath> build_per_group(const Config& cfg, const std::vector<MaterialParams>& groups,
                                      const Extra&... extra) {
  std::vector<Datapath> units;
  units.reserve(groups.size());
  for (const auto& m : groups) for_slot(m, [&] { units.emplace_back(cfg, m, extra...); });
  return units;
}

// What the per-group tables of one unit (every datapath group's together) may take in memory: lut's
// t^n tables are the only ones that grow with the key's table size (bits=16: up to 256 KiB per
// group); pow's tables are shared by the groups, the others keep a few coefficients per group.
inline constexpr std::size_t kMaxUnitTableBytes = std::size_t{256} << 20;

// build_per_group for a kind with per-group tables: `bytes(datapath)` is what one datapath keeps,
// and the build stops (std::invalid_argument naming the limit) as soon as the groups built so far
// exceed kMaxUnitTableBytes, so no more than the limit and one group's table is ever allocated.
template <class Datapath, class Config, class Bytes>
std::vector<Datapath> build_per_group_bounded(const char* unit, const std::string& keys,
                                              const Config& cfg,
                                              const std::vector<MaterialParams>& groups,
                                              const Bytes& bytes) {
  std::vector<Datapath> units;
  units.reserve(groups.size());
  std::size_t total = 0;
  for (const auto& m : groups) {
    for_slot(m, [&] { units.emplace_back(cfg, m); });
    total += bytes(units.back());
    if (total > kMaxUnitTableBytes)
      // refusal: unit_set.tables
      throw std::invalid_argument(fmt::format(
          "{}: {}: the tables of the first {} of {} datapath groups (one per distinct material) "
          "already take {:.2f} MiB, over the limit of {} MiB of tables per unit: use smaller "
          "tables or fewer distinct materials",
          unit, keys, units.size(), groups.size(), static_cast<double>(total) / (1 << 20),
          kMaxUnitTableBytes >> 20));
  }
  return units;
}

// Finishes a kind's build: the merge-buffer depth (auto: enough credits that a result never waits
// for one when the sink keeps up), the canonical spec (every key the build wrote back, in the key
// table's order, so it reads like the `glint units` listing) and the unit. Config and Datapath are
// deduced rather than named through Kind, so that a kind lacking them is reported by
// check_unit_kind and not as a call that matches nothing.
template <class Kind, class Config, class Datapath>
std::unique_ptr<SpecularUnit> make_unit_set(const CommonKeys& common, nlohmann::json config,
                                            Config cfg, std::vector<Datapath> datapaths,
                                            const SlotPlan& plan, UnitTiming timing) {
  timing.buffer_depth = common.buffer > 0 ? common.buffer : timing.latency + 3;
  put_key(config, CommonKeyTable::buffer, timing.buffer_depth);
  std::string canonical = Kind::kName;
  char sep = ':';
  std::vector<UnitKey> keys = common_keys();
  for (UnitKey& k : Kind::Keys::list()) keys.push_back(std::move(k));
  for (const UnitKey& key : keys) {
    const auto it = config.find(key.key);
    if (it == config.end()) continue;
    // The config states the chip's tables always (common_config); the spec leaves its default out,
    // as it always has.
    if (key.key == CommonKeyTable::tables.name && *it == CommonKeyTable::tables.def) continue;
    canonical +=
        sep + key.key + "=" + (it->is_string() ? it->template get<std::string>() : it->dump());
    sep = ',';
  }
  return std::make_unique<UnitSet<Kind>>(std::move(canonical), common, std::move(cfg),
                                         std::move(datapaths), plan, std::move(config), timing);
}

// The catalogue entry of a kind.
template <class Kind>
class DescriptionOf final : public UnitDescription {
  static_assert(check_unit_kind<Kind>());

 public:
  UnitInfo info() const override {
    return {Kind::kName,
            Kind::kSummary,
            Kind::Keys::list(),
            {std::begin(Kind::kCosimCases), std::end(Kind::kCosimCases)},
            Kind::kDefaultSet};
  }
  std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const SlotPlan& plan) const override {
    return Kind::build(keys, read_common_keys(keys), plan);
  }
};

}  // namespace glint
