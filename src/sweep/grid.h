// Grids of unit specs for `glint sweep` and `glint size`: "horner:degree=2..8,in=uq1.11|uq1.15"
// is the cross product of each key's values (src/cli/guide/sweep.md, "Grid syntax"):
//   a|b|c         alternatives
//   lo..hi        every integer from lo to hi (inclusive)
//   lo..hi/step   every step-th integer from lo, up to hi
// Alternatives may be ranges ("degree=2..4|8"). A key with one value passes through unchanged.
// Every key must be one of the unit's (units/catalogue.h) and every value one the unit accepts:
// parse_grid checks both before anything runs, naming the grid and the key.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "units/unit.h"

namespace glint {

// At most this many configurations over all grids of one run: a sweep keeps every configuration's
// unit and accumulators in memory (src/cli/guide/sweep.md: the memory per configuration).
inline constexpr std::size_t kMaxSweepConfigurations = 100000;

struct GridAxis {
  std::string key;
  std::vector<std::string> values;  // in the order written, ranges expanded
};

struct Grid {
  std::string text;  // as given, for messages and the report
  std::string unit;
  std::vector<GridAxis> axes;  // in the order written

  std::size_t size() const;  // the product of the value counts (saturates at SIZE_MAX)
};

// One configuration of a sweep: its place in the sweep and its spec as the grid wrote it (keys in
// the grid's order, e.g. "horner:degree=3,in=uq1.11": ready to paste into --unit).
struct SweepConfig {
  std::size_t index = 0;  // 0-based, over all grids in order
  std::size_t grid = 0;   // which grid it came from
  std::string spec;
  UnitSpec unit_spec;
};

// Parses and validates one grid. Throws std::invalid_argument naming the grid ("--grid 'TEXT'")
// and, where it applies, the key and value.
Grid parse_grid(std::string_view text);

// The configurations of the grids, in order: grid by grid, and within a grid the first key varying
// slowest (nested loops in the order the keys are written). Throws std::invalid_argument when
// there are more than `cap` in all.
std::vector<SweepConfig> expand_grids(const std::vector<Grid>& grids,
                                      std::size_t cap = kMaxSweepConfigurations);

// The configurations a shard K of N runs: index i goes to shard i mod N (round robin, so every
// shard gets a share of every grid; src/cli/guide/sweep.md, "Threads, memory and shards").
std::vector<SweepConfig> shard_configs(const std::vector<SweepConfig>& all, std::size_t k,
                                       std::size_t n);

// "K/N" with 0 <= K < N (N >= 1). Throws std::invalid_argument naming --shard.
std::pair<std::size_t, std::size_t> parse_shard(std::string_view text);

}  // namespace glint
