// The fitted polynomial's Horner pipeline as a catalogue entry (datapath: units/horner/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& horner_unit();

}  // namespace glint
