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

// An axis whose values have an order a wider grid could extend: all integers (d, bits, degree) or
// all fixed-point formats (in, out: ordered by fraction bits, then integer bits). The value's key
// in that order, per value of the axis; nullopt for an unordered axis (match, method, ...).
std::optional<std::vector<double>> axis_order(const GridAxis& axis);

// The value a configuration gives `key` (nullptr: none).
const std::string* config_value(const SweepConfig& c, const std::string& key);

// The configuration of the same grid as `c` with `key` = `value` and every other key as in `c`.
std::optional<std::size_t> grid_neighbour(const std::vector<SweepConfig>& configs,
                                          const SweepConfig& c, const std::string& key,
                                          const std::string& value);

// The value of `b`'s measure relative to its limit, signed: how far it misses (> 0) or holds with
// room to spare (< 0), per |limit| when the limit is not 0; +inf when there is no value. Orders
// configurations by how near they come, met or not.
double relative_margin(const std::optional<double>& value, const Budget& b);

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
// budget and nothing else is worth saying). A family with a `search` (size_widen.h) that widened
// is said to have stopped at its edges, not to need a wider --grid.
std::string format_explanation(const nlohmann::json& explanation);

}  // namespace glint
