// The exact-power baseline exp2(n log2 t) as a catalogue entry (datapath: units/pow/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& pow_unit();

}  // namespace glint
