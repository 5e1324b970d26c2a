// The cost proxies of one lane built around a unit (cost/cost_model.h has the constants and
// formulas): the comparator stage, the unit's own stages as its description places them, the merge
// buffer and, with colour_multiply, the RGB multiply stage after it.
#pragma once

#include "cost/cost_model.h"
#include "units/unit.h"

namespace glint {

UnitCost unit_cost(const SpecularUnit& unit, bool colour_multiply = false);

}  // namespace glint
