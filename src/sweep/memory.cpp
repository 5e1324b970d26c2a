#include "sweep/memory.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "eval/evaluate.h"
#include "fixed/fixed_point.h"
#include "units/catalogue.h"

namespace glint {

namespace {

// The input format of a spec: its "in", else the unit's default.
QFormat input_format(const UnitSpec& spec) {
  for (const auto& [key, value] : spec.keys)
    if (key == "in") return parse_q_format(value);
  for (const UnitKey& key : unit_info(spec.name).keys)
    if (key.key == "in") return parse_q_format(key.default_value);
  throw std::invalid_argument("unit '" + spec.name + "' has no key 'in'");
}

std::string mib(std::uint64_t bytes) {
  return fmt::format("{:.0f} MiB", static_cast<double>(bytes) / (1 << 20));
}

}  // namespace

std::uint64_t sweep_config_bytes(const UnitSpec& spec, std::size_t slots) {
  return kSweepBytesPerSlot * slots + memo_bytes(input_format(spec), slots);
}

void check_sweep_memory(const std::vector<SweepConfig>& configs, std::size_t slots) {
  std::uint64_t total = 0;
  for (const SweepConfig& c : configs) {
    total += sweep_config_bytes(c.unit_spec, slots);
    if (total > kMaxSweepBytes) {
      throw std::invalid_argument(fmt::format(
          "--grid: {} configurations over the input's {} slots may take more than the limit of "
          "{} per sweep (configuration {}, '{}', crosses it; it keeps up to {} KB per slot): "
          "narrow the grid or its 'in' formats, or run it as --shard K/N",
          configs.size(), slots, mib(kMaxSweepBytes), c.index, c.spec,
          sweep_config_bytes(c.unit_spec, slots) / std::max<std::size_t>(slots, 1) / 1000));
    }
  }
}

}  // namespace glint
