// The unit catalogue: parsing of unit SPECs ("NAME[:key=value,...]", in the manner of FloPoCo
// operators), the list of unit descriptions (each in its own folder, src/units/<unit>/) and the
// one place that builds a unit from its spec.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "units/unit.h"

namespace glint {

// Parses "horner:degree=4,method=minimax". Throws std::invalid_argument naming the bad part.
UnitSpec parse_unit_spec(std::string_view text);

// Every unit kind, in catalogue order (the order `glint units` lists and `eval`/`sim` run them).
const std::vector<const UnitDescription*>& unit_descriptions();
// Every unit with every key (common keys first), for `glint units` and for validation.
const std::vector<UnitInfo>& unit_catalog();
const UnitInfo& unit_info(std::string_view name);  // throws std::invalid_argument
// Every unit's name in catalogue order.
std::vector<std::string> unit_names();
// The units `glint eval`, `sim` and `render` run when no --unit is given, in catalogue order: every
// unit but those whose kind opts out (UnitInfo::default_set).
std::vector<std::string> default_unit_names();

// A co-simulation case's whole spec ("lut" or "lut:bits=4,table_frac=20") and its name as the
// tests know it ("lut.bits4": ctest rtl.lut.bits4).
std::string cosim_spec(const UnitInfo& unit, const CosimCase& c);
std::string cosim_name(const UnitInfo& unit, const CosimCase& c);

// Display labels of units shown side by side: the unit's name, or name.1, name.2, ... when the same
// kind appears more than once (e.g. hast and hast:d=3).
std::vector<std::string> unit_labels(const std::vector<std::string>& names);

// Builds a unit for a scene's slots (units/slot_plan.h: a threshold per slot, a datapath per
// group). Throws std::invalid_argument for unknown names, keys, bad values or an inconsistent plan.
std::unique_ptr<SpecularUnit> make_unit(const UnitSpec& spec, const SlotPlan& plan);
// The same with one datapath group per slot (SlotPlan::per_slot): nothing shared.
std::unique_ptr<SpecularUnit> make_unit(const UnitSpec& spec,
                                        const std::vector<MaterialParams>& slots);

}  // namespace glint
