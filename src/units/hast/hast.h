// Hast's multiplier chain as a catalogue entry (datapath: units/hast/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& hast_unit();

}  // namespace glint
