// PowPipeline: the GPU special-function-unit baseline 2^(n log2 t) (L = 5, II = 1).
//   in          comparator register of the compute path
//   log_table   leading-one detect + log2 table read
//   log_interp  log2 interpolation
//   mul_n       y = n log2 t
//   exp_table   exp2 table read
//   exp_interp  exp2 interpolation, shift and rounding; drives `result` (SpecularUnit::eval)
#pragma once

#include <vector>

#include "rtl_model/compute_pipeline.h"

namespace glint::rtl {

class PowPipeline : public ComputePipeline {
 public:
  PowPipeline(sc_core::sc_module_name name, const SpecularUnit& unit, bool tracing)
      : ComputePipeline(name, unit, layout(unit), tracing) {}

  static std::vector<StageSpec> layout(const SpecularUnit& unit) {
    const int latency = unit.timing().latency;
    if (latency != 5) return ComputePipeline::generic_stages(latency);
    return {{"in", 0, 0},    {"log_table", 1, 1}, {"log_interp", 2, 2},
            {"mul_n", 3, 3}, {"exp_table", 4, 4}, {"exp_interp", 5, 5}};
  }
};

}  // namespace glint::rtl
