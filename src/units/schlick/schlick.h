// Schlick's rational approximation with a real divider as a catalogue entry (datapath:
// units/schlick/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& schlick_unit();

}  // namespace glint
