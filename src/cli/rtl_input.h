// What `glint rtl` and `glint synth` share: the slots a unit is elaborated for (a vector file's
// header, a scene's materials and lights, or materials given on the command line) and the Verilog
// of one lane (hdl/lane.h around the unit's own datapath, SpecularUnit::rtl_datapath).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "hdl/lane.h"
#include "io/vectors.h"
#include "units/unit.h"

namespace glint::cli {

struct RtlInputOptions {
  std::string vectors, scene;
  std::vector<std::string> materials;  // "NAME shininess=N [lobe=...] [specular=r,g,b]"
  double eps = 1e-3;
  Chip chip;  // --chip: the lane's tables, ROMs of the input's materials or loadable, and capacity
  EpsMeasure eps_measure = EpsMeasure::kLuminance;  // --eps-measure: the slots' thresholds
};
// --vectors, --scene, --material, --eps, --eps-measure, --chip.
void add_rtl_input_options(CLI::App* sub, RtlInputOptions& o);
// Exactly one input kind; throws std::invalid_argument naming the options otherwise.
void check_rtl_input(const RtlInputOptions& o);

// The header the slots come from: the vector file's, the scene's requests', or one made of the
// --material lines (read by the vector-file reader, so its rules and messages apply).
VectorHeader rtl_header(const RtlInputOptions& o);

struct RtlDesign {
  SlotMap slots;
  std::unique_ptr<SpecularUnit> unit;
  hdl::LaneParams lane;
  std::string lane_verilog;      // glint_<unit>_lane
  std::string datapath_verilog;  // glint_<unit>_datapath
};
// Builds the unit for the input's slots on `chip` and writes its Verilog: the lane every other
// command prices for the same spec, input and chip. A chip of given capacity gets S threshold
// entries and M entries in every per-material table (the ones the input does not use are free,
// for the driver to load). `input` names the input in a refusal (the file, or --material).
RtlDesign make_rtl_design(const UnitSpec& spec, const VectorHeader& header,
                          const std::string& input, const Chip& chip);
// --clock-period NS: the lane's clock in its SDC (hdl/sdc.h), checked in (0, 1e6].
void add_clock_period_option(CLI::App* sub, double& period_ns);

// The input as an error message names it: the vector file, the scene, or --material.
std::string rtl_input_name(const RtlInputOptions& o);

}  // namespace glint::cli
