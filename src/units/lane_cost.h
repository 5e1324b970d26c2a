// The cost proxies of one lane built around a unit (cost/cost_model.h has the constants and
// formulas): the comparator stage, the unit's own stages as its description places them and the
// merge buffer: the hardware `glint rtl` writes. The lane returns the scalar highlight; the
// per-channel colour multiply is outside it (in the shader's ALU), in every command's figures.
#pragma once

#include "cost/cost_model.h"
#include "units/unit.h"

namespace glint {

UnitCost unit_cost(const SpecularUnit& unit);

}  // namespace glint
