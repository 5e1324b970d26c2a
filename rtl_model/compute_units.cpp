#include "rtl_model/compute_units.h"

#include "rtl_model/hast_chain.h"
#include "rtl_model/horner_pipeline.h"
#include "rtl_model/lut_interp.h"
#include "rtl_model/pow_pipeline.h"
#include "rtl_model/schlick_divider.h"

namespace glint::rtl {

std::unique_ptr<ComputePipeline> make_compute_unit(sc_core::sc_module_name name,
                                                   const SpecularUnit& unit, bool tracing) {
  const std::string& kind = unit.name();
  if (kind == "schlick") {
    const nlohmann::json d = unit.describe();
    const auto config = d.find("config");
    const bool iterative =
        config != d.end() && config->contains("divider") && (*config)["divider"] == "iterative";
    return std::make_unique<SchlickDivider>(
        name, unit, iterative ? DividerKind::kIterative : DividerKind::kPipelined, tracing);
  }
  if (kind == "hast") return std::make_unique<HastChain>(name, unit, tracing);
  if (kind == "horner") return std::make_unique<HornerPipeline>(name, unit, tracing);
  if (kind == "pow") return std::make_unique<PowPipeline>(name, unit, tracing);
  if (kind == "lut") return std::make_unique<LutInterp>(name, unit, tracing);
  return std::make_unique<ComputePipeline>(
      name, unit, ComputePipeline::generic_stages(unit.timing().latency), tracing);
}

}  // namespace glint::rtl
