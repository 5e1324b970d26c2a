// What `glint size` says about a family beyond its cheapest qualifying configuration: how close
// the family came to each condition of the budget, and, where none of its configurations meets
// the budget, which configuration came closest, what blocks it (the error part and the slot of the
// contract's decomposition) and whether its grid may be too narrow (src/cli/guide/size.md, "When
// nothing meets the budget").
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sweep/grid.h"
#include "sweep/measures.h"

namespace glint {

// A condition's value for one configuration over several inputs: the worst (the largest for an
// upper limit, the least for a lower one); nullopt when an input has none (a refused
// configuration, a missing part).
std::optional<double> worst_over_inputs(const std::vector<nlohmann::json>& reports, std::size_t i,
                                        const Budget& b);

// How far a value misses a condition, relative to its limit (|limit| when it is not 0): 0 when
// the condition holds, +inf when there is no value.
double relative_miss(const std::optional<double>& value, const Budget& b);

// The rows of one family, explained against the budget. `reports` holds the sweep of each input
// (rows in index order), `configs` the sweep's configurations (expand_grids of `grids`). `cost`
// orders configurations (smaller is cheaper) to break ties between equally close ones.
nlohmann::json explain_family(const std::string& unit, const std::vector<nlohmann::json>& reports,
                              const std::vector<Budget>& budgets, const std::vector<Grid>& grids,
                              const std::vector<SweepConfig>& configs,
                              const std::vector<double>& cost, bool meets_budget);

// The lines `glint size` prints for one family's explanation (none when the family meets the
// budget and nothing else is worth saying).
std::string format_explanation(const nlohmann::json& explanation);

}  // namespace glint
