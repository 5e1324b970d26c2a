// LutInterp: table of t^n per material + linear interpolation (L = 2, II = 1).
//   in       comparator register of the compute path
//   lookup   segment index + table read (two neighbouring entries)
//   interp   interpolation + rounding; drives `result` (SpecularUnit::eval)
#pragma once

#include <vector>

#include "rtl_model/compute_pipeline.h"

namespace glint::rtl {

class LutInterp : public ComputePipeline {
 public:
  LutInterp(sc_core::sc_module_name name, const SpecularUnit& unit, bool tracing)
      : ComputePipeline(name, unit, layout(unit), tracing) {}

  static std::vector<StageSpec> layout(const SpecularUnit& unit) {
    const int latency = unit.timing().latency;
    if (latency != 2) return ComputePipeline::generic_stages(latency);
    return {{"in", 0, 0}, {"lookup", 1, 1}, {"interp", 2, 2}};
  }
};

}  // namespace glint::rtl
