// HastChain: Hast's kappa (t - tau)^d as u^d, u = (t - tau)/(1 - tau): the u scaler, then a chain
// of d - 1 multipliers, one per stage (L = d, II = 1).
//   in          comparator register of the compute path
//   scale       u scaler
//   mul1 .. mul{d-1}   u^2 .. u^d; the last stage drives `result` (SpecularUnit::eval)
// With d = 1 the scaler stage is the output.
#pragma once

#include <string>
#include <vector>

#include "rtl_model/compute_pipeline.h"

namespace glint::rtl {

class HastChain : public ComputePipeline {
 public:
  HastChain(sc_core::sc_module_name name, const SpecularUnit& unit, bool tracing)
      : ComputePipeline(name, unit, layout(unit), tracing) {}

  static std::vector<StageSpec> layout(const SpecularUnit& unit) {
    const int latency = unit.timing().latency;
    if (latency < 1) return ComputePipeline::generic_stages(latency);
    std::vector<StageSpec> s{{"in", 0, 0}, {"scale", 1, 1}};
    for (int k = 1; k < latency; ++k) s.push_back({"mul" + std::to_string(k), k + 1, k + 1});
    return s;
  }
};

}  // namespace glint::rtl
