// The compute module for a unit, chosen by its name (and, for schlick, its `divider` key).
#pragma once

#include <memory>

#include "rtl_model/compute_pipeline.h"
#include "units/catalogue.h"

namespace glint::rtl {

// SchlickDivider, HastChain, HornerPipeline, PowPipeline or LutInterp; a generic ComputePipeline
// (stages in, s1..sL) for any other unit.
std::unique_ptr<ComputePipeline> make_compute_unit(sc_core::sc_module_name name,
                                                   const SpecularUnit& unit, bool tracing);

}  // namespace glint::rtl
