// How `glint size` widens a grid on its own (src/cli/guide/size.md, "How the grids widen"): from
// the configuration that decides the family (the cheapest meeting the budget, else the one that
// misses it by the least), of the ordered keys sitting at an end of its grid where things improve
// outward, the one that improves most takes one more value beyond that end, as far as the unit's
// key table allows, round after round until the decision sits at no such end, or a cap is
// reached.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sweep/grid.h"

namespace glint {

// The bounds of the search (--no-widen, --widen-rounds, --widen-configurations).
struct WidenLimits {
  bool widen = true;
  std::size_t rounds = 8;             // widenings per grid
  std::size_t configurations = 1000;  // configurations over all grids at the end, at most
};

// One more value of one key, beyond the end of its grid's values.
struct GridStep {
  std::size_t axis = 0;
  std::string key, value;
  bool largest = true;  // beyond the largest value (else below the smallest)
};

// Why a grid stopped widening.
enum class WidenStop {
  kFixed,             // --no-widen
  kMet,               // the budget holds and its cheapest sits at no improving end
  kNoImprovement,     // missed, and the closest sits at no end towards which the miss shrinks
  kTooSlow,           // missed, and the miss shrinks too little per step to close in the rounds
  kRangeEnd,          // the keys to widen are at the end of what the unit takes
  kRoundCap,          // --widen-rounds reached
  kConfigurationCap,  // --widen-configurations reached
  kNoValue,           // no configuration has a value for every condition
};
const char* to_string(WidenStop s);

// What to do with one grid after a round: the step to take (one), or why it stops.
struct WidenDecision {
  std::vector<GridStep> steps;
  std::optional<WidenStop> stop;
  std::string why;  // words for the report
};

// The decision for grid `grid` (index `grid_index` among the configurations' grids), given per
// configuration (in `configs`' order) its cost (smaller is cheaper; NaN: refused), whether it meets
// the budget, and its margin (sweep/size_explain.h relative_margin, the worst condition's).
// `rounds_left`: widenings this grid may still take. Pure but for the unit builds that check a
// step against the key table (probe_step).
WidenDecision decide_widening(const Grid& grid, std::size_t grid_index,
                              const std::vector<SweepConfig>& configs,
                              const std::vector<double>& cost, const std::vector<bool>& meets,
                              const std::vector<double>& margin, std::size_t rounds_left);

// The value one step beyond an end of an ordered axis: an integer key +-1, a format +-1 fraction
// bit. nullopt when the unit's key table refuses it (the reason in `why`).
std::optional<std::string> probe_step(const Grid& grid, std::size_t axis, bool largest,
                                      std::string* why = nullptr);

// The grid with the steps' values added (below the smallest value at the front, beyond the largest
// at the back) and its text rewritten (integer runs as lo..hi), ready for --grid.
Grid widen_grid(const Grid& grid, const std::vector<GridStep>& steps);

// Grids whose configurations are exactly those of `wider` that `narrower` (the same keys, fewer
// values) lacks, each configuration once.
std::vector<Grid> grid_difference(const Grid& narrower, const Grid& wider);

// A grid's text from its axes: "unit:key=v|v|...", runs of integers as lo..hi[/step].
std::string grid_text(const Grid& grid);

// One grid's search, as the report gives it.
struct GridSearch {
  Grid given, grid;
  std::size_t rounds = 0;
  nlohmann::json steps = nlohmann::json::array();  // {round, key, value}
  WidenStop stop = WidenStop::kFixed;
  std::string why;
  nlohmann::json to_json() const;
};

}  // namespace glint
