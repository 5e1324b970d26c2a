#include "units/catalogue.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "units/hast/hast.h"
#include "units/horner/horner.h"
#include "units/keys.h"
#include "units/lut/lut.h"
#include "units/pow/pow.h"
#include "units/pwp/pwp.h"
#include "units/schlick/schlick.h"
#include "units/sfu/sfu.h"

namespace glint {

// Adding a unit: one line here (and its folder, src/units/<unit>/).
const std::vector<const UnitDescription*>& unit_descriptions() {
  static const std::vector<const UnitDescription*> all = {
      &pow_unit(), &schlick_unit(), &hast_unit(), &horner_unit(),
      &lut_unit(), &sfu_unit(),     &pwp_unit()};
  return all;
}

UnitSpec parse_unit_spec(std::string_view text) {
  UnitSpec spec;
  const auto colon = text.find(':');
  spec.name = std::string(text.substr(0, colon));
  // refusal: spec.empty
  if (spec.name.empty()) throw std::invalid_argument("empty unit spec");
  if (colon == std::string_view::npos) return spec;
  std::string_view rest = text.substr(colon + 1);
  if (rest.empty())
    // refusal: spec.no_keys
    throw std::invalid_argument(fmt::format("unit spec '{}': no keys after ':'", text));
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    const auto eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0 || eq + 1 == item.size()) {
      // refusal: spec.not_key_value
      throw std::invalid_argument(fmt::format("unit spec '{}': '{}' is not key=value", text, item));
    }
    std::string key(item.substr(0, eq));
    for (const auto& kv : spec.keys)
      if (kv.first == key)
        // refusal: spec.twice
        throw std::invalid_argument(fmt::format("unit spec '{}': key '{}' given twice", text, key));
    spec.keys.emplace_back(std::move(key), std::string(item.substr(eq + 1)));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
    if (rest.empty())
      // refusal: spec.trailing_comma
      throw std::invalid_argument(fmt::format("unit spec '{}': trailing ','", text));
  }
  return spec;
}

std::vector<std::string> unit_labels(const std::vector<std::string>& names) {
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto same = std::count(names.begin(), names.end(), names[i]);
    const auto index =
        std::count(names.begin(), names.begin() + static_cast<long>(i) + 1, names[i]);
    labels.push_back(same > 1 ? names[i] + "." + std::to_string(index) : names[i]);
  }
  return labels;
}

namespace {

std::vector<UnitInfo> build_catalog() {
  std::vector<UnitInfo> out;
  for (const UnitDescription* d : unit_descriptions()) {
    UnitInfo info = d->info();
    std::vector<UnitKey> keys = common_keys();
    keys.insert(keys.end(), info.keys.begin(), info.keys.end());
    info.keys = std::move(keys);
    out.push_back(std::move(info));
  }
  return out;
}

const UnitDescription& description(std::string_view name) {
  const auto& catalog = unit_catalog();
  for (std::size_t i = 0; i < catalog.size(); ++i)
    if (catalog[i].name == name) return *unit_descriptions()[i];
  // refusal: spec.unknown_unit
  throw std::invalid_argument(
      fmt::format("unknown unit '{}' (known: {})", name, fmt::join(unit_names(), ", ")));
}

}  // namespace

const std::vector<UnitInfo>& unit_catalog() {
  static const std::vector<UnitInfo> catalog = build_catalog();
  return catalog;
}

std::string cosim_spec(const UnitInfo& unit, const CosimCase& c) {
  return c.spec.empty() ? unit.name : unit.name + ":" + std::string(c.spec);
}

std::string cosim_name(const UnitInfo& unit, const CosimCase& c) {
  return unit.name + "." + std::string(c.name);
}

std::vector<std::string> unit_names() {
  std::vector<std::string> names;
  for (const auto& u : unit_catalog()) names.push_back(u.name);
  return names;
}

std::vector<std::string> default_unit_names() {
  std::vector<std::string> names;
  for (const auto& u : unit_catalog())
    if (u.default_set) names.push_back(u.name);
  return names;
}

const UnitInfo& unit_info(std::string_view name) {
  const UnitDescription& d = description(name);
  const auto& all = unit_descriptions();
  return unit_catalog()[static_cast<std::size_t>(std::find(all.begin(), all.end(), &d) -
                                                 all.begin())];
}

std::unique_ptr<SpecularUnit> make_unit(const UnitSpec& spec,
                                        const std::vector<MaterialParams>& slots) {
  return make_unit(spec, SlotPlan::per_slot(slots));
}

std::unique_ptr<SpecularUnit> make_unit(const UnitSpec& spec, const SlotPlan& plan) {
  check_slot_plan(plan);
  const UnitInfo& info = unit_info(spec.name);
  const UnitDescription& d = description(spec.name);
  try {
    const KeyReader keys(spec, info.keys);
    return d.build(keys, plan);
  } catch (const std::invalid_argument& e) {
    // Datapath constructors name themselves ("hast: ..."); key errors do not.
    const std::string what = e.what();
    if (what.rfind(spec.name + ":", 0) == 0) throw;
    // not from a spec: names the unit of a refusal tagged where it is thrown
    throw std::invalid_argument(fmt::format("unit '{}': {}", spec.name, what));
  }
}

}  // namespace glint
