// `glint size`: the cheapest configuration of a sweep, per unit family and overall, that meets an
// error budget on every input (src/cli/guide/size.md).
#pragma once

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sweep/measures.h"
#include "sweep/size_widen.h"
#include "sweep/sweep.h"

namespace glint {

// What "cheapest" means. A configuration's value over several inputs is its worst: the largest
// area (a chip that serves every input holds every input's slots), the least throughput, the
// largest area x latency.
// kAreaUm2 and kEnergy need a sweep at a node (--node): rows without one have no value.
enum class SizeObjective { kArea, kThroughput, kAreaLatency, kEnergy, kAreaUm2 };
// "area", "throughput", "area*latency", "energy" (or the measure's name, objective_measure) or
// "area_um2"; throws std::invalid_argument naming --objective.
SizeObjective parse_size_objective(const std::string& text);
const char* to_string(SizeObjective o);
// The measure an objective minimises (maximises, for throughput): "area_ge", "throughput",
// "area_latency", "energy_pj_per_request", "area_um2" (measures.h).
const char* objective_measure(SizeObjective o);

// The grids `glint size` sweeps without --grid: a few per unit family (src/cli/guide/size.md lists
// them).
const std::vector<std::string>& default_size_grids();

struct SizePick {
  std::size_t meeting = 0;                                      // configurations meeting the budget
  std::optional<std::size_t> best;                              // overall (a configuration index)
  std::map<std::string, std::optional<std::size_t>> by_family;  // every family swept
  std::vector<double> value;  // per configuration: the objective over every input (worst)
  std::vector<bool> meets;    // per configuration: every condition on every input
};

// The choice over the sweep reports of the same configurations on each input (rows in index
// order): a configuration qualifies when it meets every condition on every input; among those the
// least area (or area x latency), or the greatest throughput, wins; ties go to the lower index.
SizePick pick_cheapest(const std::vector<nlohmann::json>& reports,
                       const std::vector<Budget>& budgets, SizeObjective objective);

// The configurations meeting the budget, cheapest first (ties to the lower index), at most `k`.
std::vector<std::size_t> cheapest_meeting(const SizePick& pick, SizeObjective objective,
                                          std::size_t k);

// The whole of `glint size`: a sweep of the grids per input, then the pick; unless `widen.widen`
// is false, rounds of widening (size_widen.h), each sweeping only the configurations the widened
// grids add, until every grid stops. The document --json prints: budgets, objective, inputs, the
// grids as given and as searched, the choice per family and overall, the `top` cheapest and, per
// family, how close it came (size_explain.h) and how its grids widened. A function of its
// arguments alone: two calls with other settings are independent.
struct SizeRun {
  std::vector<nlohmann::json> reports;  // per input
  SizePick pick;
  nlohmann::json document;
};
SizeRun run_size(const std::vector<SweepInput>& inputs, const std::vector<Grid>& grids,
                 const std::vector<Budget>& budgets, SizeObjective objective,
                 const SweepSettings& settings, bool image, const WidenLimits& widen = {},
                 std::size_t top = 1, const std::function<void(const std::string&)>& progress = {});

// The text `glint size` prints: the budget, a line per family and, last, the overall choice's
// spec alone on its line (ready to paste; `| tail -1`).
std::string format_size(const SizeRun& run);

}  // namespace glint
