// The piecewise-polynomial unit as a catalogue entry (datapath: units/pwp/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& pwp_unit();

}  // namespace glint
