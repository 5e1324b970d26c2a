// The sfu unit: the highlight as NVIDIA's Tesla-class GPUs compute it (units/sfu/datapath.h).
#pragma once

#include "units/unit.h"

namespace glint {

const UnitDescription& sfu_unit();

}  // namespace glint
