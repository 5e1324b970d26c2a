// The `glint sim` report: structured data first (JSON, schema in src/eval/sim_report.md), text
// second.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "timing/timing.h"
#include "units/catalogue.h"

namespace glint {

// 2: errors decomposed; 3: the scene's elaboration (datapath_groups, slot_capacity, per unit
// "elaboration"); 4: no colour stage in any lane (units[].colour_multiply gone); 5: pixel_measure,
// and weighted errors are the pixel error of reference/pixel_error.h (4: the scalar error times
// c_y) (src/eval/sim_report.md).
inline constexpr int kSimReportVersion = 5;

// One unit's report: config, elaboration, counts, timing, operations, area and critical path,
// errors.
// node: with the lane's figures at the node (UnitCost::node_json) as "node".
nlohmann::json unit_sim_report(const SpecularUnit& unit, const TimingStats& timing,
                               const UnitStats& stats, std::uint64_t digest, bool node = false);

// One line of a lane's figures at the node (UnitCost::node_json): area, critical path, clock.
std::string node_line(const nlohmann::json& node);

// The table printed on stdout.
std::string format_sim_table(const nlohmann::json& report);

// Regression: compares a fresh report with a golden one. Bit-accurate fields (digest, counts,
// cycles, latencies, stalls, operations) must match exactly; float statistics within `rel_tol`
// relative (plus 1e-12 absolute). Returns one readable line per difference.
std::vector<std::string> diff_sim_reports(const nlohmann::json& golden, const nlohmann::json& fresh,
                                          double rel_tol = 1e-9);

}  // namespace glint
