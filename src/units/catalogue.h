// The unit catalogue: parsing of unit SPECs ("NAME[:key=value,...]", in the manner of FloPoCo
// operators), the keys each unit takes with their defaults, and a runtime interface over the
// bit-accurate datapath classes so that the CLI, sweeps and SystemC modules can drive any unit.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "timing/timing.h"
#include "units/common.h"

namespace glint {

struct UnitSpec {
  std::string name;
  std::vector<std::pair<std::string, std::string>> keys;  // in the order given
};

// Parses "horner:degree=4,method=minimax". Throws std::invalid_argument naming the bad part.
UnitSpec parse_unit_spec(std::string_view text);

struct UnitKey {
  std::string key;
  std::string meaning;
  std::string default_value;
};
struct UnitInfo {
  std::string name;
  std::string summary;
  std::vector<UnitKey> keys;
};
// Every unit with every key (common keys included), for `glint units` and for validation.
const std::vector<UnitInfo>& unit_catalog();
const UnitInfo& unit_info(std::string_view name);  // throws std::invalid_argument
// Every unit's name in catalogue order: the default set of `glint eval` and `glint sim`.
std::vector<std::string> unit_names();

// One unit built for a set of slots (materials or light x material pairs).
class SpecularUnit {
 public:
  virtual ~SpecularUnit() = default;

  virtual const std::string& name() const = 0;
  // The spec with every key resolved to its value, e.g. "hast:in=uq1.15,out=uq1.15,d=4,...".
  virtual std::string canonical_spec() const = 0;
  virtual QFormat in_format() const = 0;
  virtual QFormat out_format() const = 0;
  virtual std::size_t slots() const = 0;

  // Comparator threshold of a slot in the input format (-1: never skips).
  virtual std::int64_t tau_raw(std::size_t slot) const = 0;
  // The datapath alone (no skip), the unit's real-valued model at the same quantized input, and
  // the float approximation at the exact t (no quantization anywhere).
  virtual std::int64_t eval(std::size_t slot, std::int64_t t_raw) const = 0;
  virtual double model(std::size_t slot, std::int64_t t_raw) const = 0;
  virtual double float_model(std::size_t slot, double t) const = 0;
  // Comparator then datapath over a batch: out[i] = 0 where skipped[i].
  virtual void eval_batch(std::size_t slot, const std::int64_t* t_raw, std::int64_t* out,
                          std::uint8_t* skipped, std::size_t n) const = 0;
  // Stated bound on |result - t^n| for units that approximate t^n itself (pow, lut); NaN for units
  // whose contract is against their own model.
  virtual double error_bound(std::size_t slot) const = 0;
  // Structured description: config and per-slot constants (tables sizes, coefficients, widths).
  virtual nlohmann::json describe() const = 0;
  // Latency, initiation interval and merge-buffer depth of the unit's hardware (timing keys).
  virtual UnitTiming timing() const = 0;

  bool skip(std::size_t slot, std::int64_t t_raw) const { return tau_skip(t_raw, tau_raw(slot)); }
  std::int64_t eval_with_skip(std::size_t slot, std::int64_t t_raw) const {
    return skip(slot, t_raw) ? 0 : eval(slot, t_raw);
  }
};

// Display labels of units shown side by side: the unit's name, or name.1, name.2, ... when the same
// kind appears more than once (e.g. hast and hast:d=3).
std::vector<std::string> unit_labels(const std::vector<std::string>& names);

// Builds a unit. Throws std::invalid_argument for unknown names, keys or bad values.
std::unique_ptr<SpecularUnit> make_unit(const UnitSpec& spec,
                                        const std::vector<MaterialParams>& slots);

}  // namespace glint
