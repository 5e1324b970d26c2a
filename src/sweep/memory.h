// The memory a sweep's configurations take, bounded before any is built (src/cli/README.md,
// "Limits and guarantees"). Every configuration is a lane kept for the whole stream: about 15 KB
// per slot (threshold, contract, accumulators, elaboration), plus, for inputs of at most 16 bits,
// a memo of each slot's codes above its threshold (eval/evaluate.h, memo_bytes: 40 bytes per
// code, 2^F + 1 codes at most for an input of F fraction bits). That memo is what grows: at the
// default in=uq1.15 a configuration takes up to about 1.3 MB per slot.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sweep/grid.h"
#include "units/unit.h"

namespace glint {

inline constexpr std::uint64_t kSweepBytesPerSlot = 15 << 10;
// The bound of one sweep (of one shard): 4 GiB by the figures above, which are upper bounds (a
// slot's memo only holds the codes above its threshold; measured peaks are a third to a half).
inline constexpr std::uint64_t kMaxSweepBytes = std::uint64_t{4} << 30;

// The most memory one configuration's lane may take over `slots` slots.
std::uint64_t sweep_config_bytes(const UnitSpec& spec, std::size_t slots);

// Throws std::invalid_argument naming --grid and the limit when `configs` over `slots` slots may
// take more than kMaxSweepBytes.
void check_sweep_memory(const std::vector<SweepConfig>& configs, std::size_t slots);

}  // namespace glint
