// The cost proxies of one lane built around a unit (cost/cost_model.h has the constants and
// formulas): the comparator stage, the unit's own stages as its description places them, the merge
// buffer and, with colour_multiply, the RGB multiply stage after it.
#pragma once

#include "cost/cost_model.h"
#include "units/unit.h"

namespace glint {

// colour_entries: RGB entries of the colour stage (the stream's distinct light x specular colours;
// 0: one per threshold entry).
UnitCost unit_cost(const SpecularUnit& unit, bool colour_multiply = false, int colour_entries = 0);

// The timing of the same lane: the unit's own (latency, II, merge buffer), plus one stage of
// latency with the colour stage. Both SystemC modes and `glint sweep` schedule with it
// (timing/timing.h's TimingEngine), so a sweep's cycles are the cycles `glint sim` reports.
UnitTiming lane_timing(const SpecularUnit& unit, bool colour_stage);

}  // namespace glint
