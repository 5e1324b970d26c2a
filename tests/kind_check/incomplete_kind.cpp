// A unit kind that meets the contract (src/units/unit_set.h) but for the member one of the LACK_*
// macros takes away: its build must stop at check_unit_kind's sentence naming that member
// (tests/CMakeLists.txt, kind_check.*). With none defined it compiles.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "units/unit_set.h"

namespace glint {
namespace {

struct ProbeKeys {
  static constexpr IntKey width{"width", 4, 1, 8, "a key"};
  static std::vector<UnitKey> list() { return key_list(width); }
};

struct ProbeConfig {
  int width = ProbeKeys::width.def;
};

class ProbeDatapath {
 public:
  ProbeDatapath(const ProbeConfig&, const MaterialParams&) {}
  std::int64_t eval(std::int64_t t) const { return run(t, NoProbe{}); }
  template <class Probe>
  std::int64_t run(std::int64_t t, const Probe&) const {
    return t;
  }
  double model(std::int64_t t) const { return static_cast<double>(t); }
#ifndef LACK_FLOAT_MODEL
  double float_model(double t) const {
    return t;
  }
#endif
  double datapath_bound_ulps() const {
    return 0.5;
  }
};

struct ProbeKind : UnitKindDefaults {
  using Config = ProbeConfig;
  using Datapath = ProbeDatapath;
#ifndef LACK_NAME
  static constexpr const char* kName = "probe";
#endif
  static constexpr const char* kSummary = "a unit kind for the compile-time checks";
  using Keys = ProbeKeys;
  static constexpr CosimCase kCosimCases[] = {{"default", "", ""}};

  static std::unique_ptr<SpecularUnit> build(const KeyReader& keys, const CommonKeys& common,
                                             const SlotPlan& plan) {
    ProbeConfig c{keys.read(Keys::width)};
    nlohmann::json config = common_config(common);
    put_key(config, Keys::width, c.width);
    auto datapaths = build_per_group<ProbeDatapath>(c, plan.groups);
    return make_unit_set<ProbeKind>(common, std::move(config), c, std::move(datapaths), plan,
                                    UnitTiming{1, 1, 0});
  }
  static std::vector<Stage> stages(const Config&, const std::vector<Datapath>&, UnitTiming) {
    return {input_stage()};
  }
  static void cost(CostBuilder&, const LaneShape&, const Config&, const std::vector<Datapath>&) {}
  static nlohmann::json describe_slot(const Datapath&) {
    return nlohmann::json::object();
  }
};

}  // namespace

const UnitDescription& probe_unit() {
  static const DescriptionOf<ProbeKind> description;
  return description;
}

}  // namespace glint
