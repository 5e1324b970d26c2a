// The contract of a unit kind (unit_set.h) as compile-time checks. UnitSet<Kind>, make_unit_set and
// DescriptionOf<Kind> read their kind through check_unit_kind<Kind>(): a kind that lacks a member,
// or has one of the wrong shape, stops the build with one sentence naming the member, ahead of the
// template errors its use would go on to cause. The members are checked in order and only the
// first one missing is named, since every later check may depend on it (stages() on Config and
// Datapath, for one).
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "cost/builder.h"
#include "units/keys.h"
#include "units/lane_cost.h"
#include "units/n_register.h"
#include "units/stages.h"
#include "units/unit.h"

namespace glint {

struct UnitKindDefaults;

namespace kind_check {

// The detection idiom: has<Op, K> is whether Op<K> names a type (C++17, std::void_t).
template <class Void, template <class> class Op, class K>
struct Detect : std::false_type {};
template <template <class> class Op, class K>
struct Detect<std::void_t<Op<K>>, Op, K> : std::true_type {};
template <template <class> class Op, class K>
inline constexpr bool has = Detect<void, Op, K>::value;

// Each member as the unit layer calls it, converted to what the call site needs.
template <class K>
using ConfigOf = typename K::Config;
template <class K>
using DatapathOf = typename K::Datapath;
template <class K>
using Name = decltype(std::string_view(K::kName));
template <class K>
using Summary = decltype(std::string_view(K::kSummary));
template <class K>
using KeyTable = decltype(std::vector<UnitKey>(K::Keys::list()));
template <class K>
using CosimCases = decltype(static_cast<const CosimCase&>(K::kCosimCases[0]));
template <class K>
using Build = decltype(std::unique_ptr<SpecularUnit>(K::build(std::declval<const KeyReader&>(),
                                                              std::declval<const CommonKeys&>(),
                                                              std::declval<const SlotPlan&>())));

template <class K>
const typename K::Config& config();
template <class K>
const std::vector<typename K::Datapath>& datapaths();

template <class K>
using Stages = decltype(std::vector<Stage>(
    K::stages(config<K>(), datapaths<K>(), std::declval<UnitTiming>())));
template <class K>
using Cost = decltype(K::cost(std::declval<CostBuilder&>(), std::declval<const LaneShape&>(),
                              config<K>(), datapaths<K>()));
template <class K>
using DescribeSlot =
    decltype(nlohmann::json(K::describe_slot(std::declval<const typename K::Datapath&>())));
template <class K>
using ErrorBound = decltype(double(K::error_bound(std::declval<const typename K::Datapath&>())));
template <class K>
using CarriesRoot = decltype(bool(K::carries_root(config<K>())));
template <class K>
using NRegisterOf =
    decltype(std::optional<NRegister>(K::n_register(config<K>(), datapaths<K>(), bool{})));
template <class K>
using Rtl = decltype(std::string(K::rtl(std::declval<const hdl::DatapathPorts&>(), config<K>(),
                                        datapaths<K>(), std::declval<const StageLayout&>())));

// The datapath's members (D = K::Datapath).
template <class D>
using Eval = decltype(std::int64_t(std::declval<const D&>().eval(std::int64_t{})));
template <class D>
using Run = decltype(std::int64_t(std::declval<const D&>().run(std::int64_t{}, NoProbe{})));
template <class D>
using Model = decltype(double(std::declval<const D&>().model(std::int64_t{})));
template <class D>
using FloatModel = decltype(double(std::declval<const D&>().float_model(double{})));
template <class D>
using BoundUlps = decltype(double(std::declval<const D&>().datapath_bound_ulps()));

template <class D>
constexpr bool check_datapath() {  // as check_unit_kind, for Kind::Datapath
  if constexpr (!has<Eval, D>) {
    static_assert(has<Eval, D>,
                  "unit kind's Datapath lacks `std::int64_t eval(std::int64_t) const`");
  } else if constexpr (!has<Run, D>) {
    static_assert(has<Run, D>,
                  "unit kind's Datapath lacks `template <class Probe> std::int64_t "
                  "run(std::int64_t, const Probe&) const`");
  } else if constexpr (!has<Model, D>) {
    static_assert(has<Model, D>, "unit kind's Datapath lacks `double model(std::int64_t) const`");
  } else if constexpr (!has<FloatModel, D>) {
    static_assert(has<FloatModel, D>,
                  "unit kind's Datapath lacks `double float_model(double) const`");
  } else if constexpr (!has<BoundUlps, D>) {
    static_assert(has<BoundUlps, D>,
                  "unit kind's Datapath lacks `double datapath_bound_ulps() const`");
  }
  return true;
}

}  // namespace kind_check

// True when Kind meets the contract; otherwise it fails to compile, naming the first member Kind
// lacks. Used as static_assert(check_unit_kind<Kind>()): the sentence is the only error, since the
// function returns true either way.
template <class Kind>
constexpr bool check_unit_kind() {
  using namespace kind_check;
  if constexpr (!has<ConfigOf, Kind>) {
    static_assert(has<ConfigOf, Kind>, "unit kind lacks `using Config = ...;`");
  } else if constexpr (!has<DatapathOf, Kind>) {
    static_assert(has<DatapathOf, Kind>, "unit kind lacks `using Datapath = ...;`");
  } else if constexpr (!has<Name, Kind>) {
    static_assert(has<Name, Kind>,
                  "unit kind lacks `static constexpr const char* kName` (its name in specs)");
  } else if constexpr (!has<Summary, Kind>) {
    static_assert(has<Summary, Kind>,
                  "unit kind lacks `static constexpr const char* kSummary` (its line in `glint "
                  "units`)");
  } else if constexpr (!has<KeyTable, Kind>) {
    static_assert(has<KeyTable, Kind>,
                  "unit kind lacks `using Keys = ...;` with `static std::vector<UnitKey> list()` "
                  "(its key table, src/units/<unit>/keys.h)");
  } else if constexpr (!has<CosimCases, Kind>) {
    static_assert(has<CosimCases, Kind>,
                  "unit kind lacks `static constexpr CosimCase kCosimCases[]` (the specs it is "
                  "tested and co-simulated with)");
  } else if constexpr (!has<Build, Kind>) {
    static_assert(has<Build, Kind>,
                  "unit kind lacks `static std::unique_ptr<SpecularUnit> build(const KeyReader&, "
                  "const CommonKeys&, const SlotPlan&)`");
  } else if constexpr (!has<Stages, Kind>) {
    static_assert(has<Stages, Kind>,
                  "unit kind lacks `static std::vector<Stage> stages(const Config&, const "
                  "std::vector<Datapath>&, UnitTiming)`");
  } else if constexpr (!has<Cost, Kind>) {
    static_assert(has<Cost, Kind>,
                  "unit kind lacks `static void cost(CostBuilder&, const LaneShape&, const "
                  "Config&, const std::vector<Datapath>&)`");
  } else if constexpr (!has<DescribeSlot, Kind>) {
    static_assert(has<DescribeSlot, Kind>,
                  "unit kind lacks `static nlohmann::json describe_slot(const Datapath&)`");
  } else if constexpr (!std::is_base_of_v<UnitKindDefaults, Kind> &&
                       !(has<ErrorBound, Kind> && has<CarriesRoot, Kind> &&
                         has<NRegisterOf, Kind> && has<Rtl, Kind>)) {
    static_assert(std::is_base_of_v<UnitKindDefaults, Kind>,
                  "unit kind lacks the optional members' defaults: derive it from "
                  "UnitKindDefaults");
  } else {
    check_datapath<typename Kind::Datapath>();
  }
  return true;
}

}  // namespace glint
