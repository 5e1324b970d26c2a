// The table + interpolation baseline as a catalogue entry (datapath: units/lut/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& lut_unit();

}  // namespace glint
