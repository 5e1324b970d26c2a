// What a built unit offers the rest of glint, whatever its kind: the runtime interface over the
// datapaths its slots share (units/unit_set.h implements it once for every kind), and the
// description each unit registers in the catalogue (units/catalogue.h): its name, keys and how to
// build it.
//
// A unit's knowledge lives in its own folder, src/units/<unit>/: keys.h (its key table), datapath.h
// (the bit-accurate datapath, one behaviour for eval and the staged evaluation), datapath.cpp
// (construction, real models, error budget), and <unit>.cpp (co-simulation cases, build, timing,
// stage layout, cost inventory, description). Nothing outside that folder compares unit names.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "timing/timing.h"
#include "units/common.h"
#include "units/key_table.h"
#include "units/slot_plan.h"
#include "units/stages.h"

namespace glint {

class CostBuilder;
struct LaneShape;
namespace hdl {
struct DatapathPorts;
}

struct UnitSpec {
  std::string name;
  std::vector<std::pair<std::string, std::string>> keys;  // in the order given
};

// A spec the unit is tested and co-simulated with, in its own folder (the kind's kCosimCases):
// ctest `rtl.<unit>.<name>` runs `glint rtl <unit>:SPEC INPUT` and the Verilog testbench over every
// input code of every slot (tests/rtl/cosim.sh), and the unit tests build every such spec.
struct CosimCase {
  std::string_view name;
  std::string_view spec;   // the keys after "<unit>:", empty for the defaults
  std::string_view input;  // glint rtl's input options, paths from the source folder
};
struct UnitInfo {
  std::string name;
  std::string summary;
  std::vector<UnitKey> keys;  // common keys first, then the unit's own
  std::vector<CosimCase> cosim_cases;
  // In the set `eval`, `sim`, `render` run when no --unit is given (default_unit_names()).
  bool default_set = true;
};

// One unit built for a scene's slots (units/slot_plan.h): a comparator threshold per slot, in front
// of datapaths built once per group of slots (a material's, whatever its lights) and shared.
class SpecularUnit {
 public:
  virtual ~SpecularUnit() = default;

  virtual const std::string& name() const = 0;
  // The spec with every key resolved to its value, e.g. "hast:in=uq1.15,out=uq1.15,d=4,...".
  virtual std::string canonical_spec() const = 0;
  virtual QFormat in_format() const = 0;
  virtual QFormat out_format() const = 0;
  virtual std::size_t slots() const = 0;
  // A chip of given capacity (SlotPlan, units/chip.h): entries of the threshold table and of every
  // per-material table. 0: sized to the stream (slots() thresholds, datapath_groups() entries).
  virtual std::size_t slot_capacity() const = 0;
  virtual std::size_t group_capacity() const = 0;
  // The datapath instances (tables, coefficients, n register contents) and which one a slot reads.
  virtual std::size_t datapath_groups() const = 0;
  virtual std::size_t datapath_of(std::size_t slot) const = 0;

  // Comparator threshold of a slot in the input format (-1: never skips): the unit's own
  // (unit_threshold_raw in units/common.h), so every skipped output is imperceptible.
  virtual std::int64_t tau_raw(std::size_t slot) const = 0;
  // The datapath alone (no skip), the unit's real-valued model at the same quantized input, and
  // the float approximation at the exact t (no quantization anywhere).
  virtual std::int64_t eval(std::size_t slot, std::int64_t t_raw) const = 0;
  virtual double model(std::size_t slot, std::int64_t t_raw) const = 0;
  virtual double float_model(std::size_t slot, double t) const = 0;
  // Comparator then datapath over a batch: out[i] = 0 where skipped[i].
  virtual void eval_batch(std::size_t slot, const std::int64_t* t_raw, std::int64_t* out,
                          std::uint8_t* skipped, std::size_t n) const = 0;
  // The same datapath as eval(), recording every stage's registers: values[stages().size()]
  // laid out by stages() (values[stages().result_index()] == eval(slot, t_raw)).
  virtual void eval_staged(std::size_t slot, std::int64_t t_raw, std::int64_t* values) const = 0;
  virtual const StageLayout& stages() const = 0;
  // Stated bound on |result - t^n| for units that approximate t^n itself (pow, lut); NaN for units
  // whose contract is against their own model.
  virtual double error_bound(std::size_t slot) const = 0;
  // The unit's error budget against its own real-valued model(): |eval - model| <= this many
  // output ulps on every input code (½: correctly rounded; < 1: faithful).
  virtual double datapath_bound_ulps(std::size_t slot) const = 0;
  // model() is non-decreasing in the input code and float_model() in t on [0, 1], as the kind
  // proves for this slot (its models_monotone). The contract certifies inputs too wide to sweep
  // code by code from this (eval/contract.md, "Exhaustive, certified or estimated"); false: not
  // known, and such a slot's parts stay estimates.
  virtual bool models_monotone(std::size_t slot) const = 0;
  // Structured description: config, per-slot constants (tables sizes, coefficients, widths) and
  // the elaboration (what the scene made the unit build, and why).
  virtual nlohmann::json describe() const = 0;
  // Latency, initiation interval and merge-buffer depth of the unit's hardware (timing keys).
  virtual UnitTiming timing() const = 0;
  // The tau comparator is built (key skip=on).
  virtual bool comparator_enabled() const = 0;
  // Per-slot tables as registers with a write port (key tables=ram), not case ROMs of the
  // scene's materials.
  virtual bool tables_ram() const = 0;
  // The comparator register also carries the slot's root to a u scaler (hast, horner on [tau, 1]).
  virtual bool comparator_carries_root() const = 0;
  // Places the unit's own stages (after the comparator stage) in the cost builder.
  virtual void add_cost(CostBuilder& b, const LaneShape& lane) const = 0;
  // The datapath as synthesizable Verilog-2005 (`glint rtl`): one module with the ports of
  // hdl::DatapathPorts, positions 0..L of stages() as its registers, every table and constant
  // taken from the built datapaths (src/units/<unit>/rtl.cpp). Throws std::invalid_argument when
  // the unit (or this spec of it) has no generator.
  virtual std::string rtl_datapath(const hdl::DatapathPorts& ports) const = 0;

  bool skip(std::size_t slot, std::int64_t t_raw) const { return tau_skip(t_raw, tau_raw(slot)); }
  std::int64_t eval_with_skip(std::size_t slot, std::int64_t t_raw) const {
    return skip(slot, t_raw) ? 0 : eval(slot, t_raw);
  }
};

class KeyReader;

// A unit kind as the catalogue lists it.
class UnitDescription {
 public:
  virtual ~UnitDescription() = default;
  // Name, summary and the unit's own keys (without the common ones).
  virtual UnitInfo info() const = 0;
  // Builds the unit for a scene's slots from its keys: one datapath per group of `plan`, one
  // threshold per slot. Throws std::invalid_argument for bad values.
  virtual std::unique_ptr<SpecularUnit> build(const KeyReader& keys,
                                              const SlotPlan& plan) const = 0;
};

}  // namespace glint
