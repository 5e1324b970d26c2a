// HornerPipeline: a fitted polynomial by Horner's rule (Öztürk eq.12), one multiply-add per stage
// (L = degree + 1, II = 1).
//   in          comparator register of the compute path
//   scale       u scaler (u = (t - tau)/(1 - tau) on the tau domain; t itself on the full domain)
//   mac1 .. mac{p}     acc = acc * u + c_{p-k}; the last drives `result` (SpecularUnit::eval)
#pragma once

#include <string>
#include <vector>

#include "rtl_model/compute_pipeline.h"

namespace glint::rtl {

class HornerPipeline : public ComputePipeline {
 public:
  HornerPipeline(sc_core::sc_module_name name, const SpecularUnit& unit, bool tracing)
      : ComputePipeline(name, unit, layout(unit), tracing) {}

  static std::vector<StageSpec> layout(const SpecularUnit& unit) {
    const int latency = unit.timing().latency;
    if (latency < 2) return ComputePipeline::generic_stages(latency);
    std::vector<StageSpec> s{{"in", 0, 0}, {"scale", 1, 1}};
    for (int k = 1; k < latency; ++k) s.push_back({"mac" + std::to_string(k), k + 1, k + 1});
    return s;
  }
};

}  // namespace glint::rtl
