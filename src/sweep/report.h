// The sweep report (key "glint_sweep_report", schema in src/sweep/sweep_report.md): what
// was swept over which input, and one row per configuration with its Pareto flags. The JSON and
// the CSV are both functions of the document alone, so a merge of shards that rebuilds the
// document writes the same bytes as the unsharded run.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace glint {

inline constexpr int kSweepReportVersion = 2;

// The Pareto objectives each row is flagged for, against the error measure: name, the row's key,
// and whether it is minimised (else maximised).
struct Objective {
  const char* name;
  const char* key;
  bool minimise;
};
inline constexpr Objective kObjectives[] = {{"area", "area_ge", true},
                                            {"throughput", "throughput", false},
                                            {"area_latency", "area_latency", true}};
// With --node, the rows' energy per request at the node (eval/energy.h) is an objective too.
inline constexpr Objective kEnergyObjective = {"energy", "energy_pj_per_request", true};
// The objectives of a report: kObjectives, and the energy when its rows state it.
std::vector<Objective> report_objectives(const nlohmann::json& report);

// Whether a report's rows state the lane at a node (a sweep with --node; "node" in a row): its
// CSV, tables and pages then have the node_only columns (measures.h).
bool report_has_node(const nlohmann::json& report);

// Sets each row's "error" (the report's error_measure; null when the row has none) and its
// "pareto" flags, over all of the report's rows.
void mark_pareto(nlohmann::json& report);

// The document as written by -o FILE.json and merged by `glint merge`.
std::string report_json_text(const nlohmann::json& report);
// The CSV: one header line (sweep_columns(); image-level columns only for a scene), one line per
// row. Numbers in the shortest form that reads back exactly, text quoted when it must be (RFC
// 4180).
std::string report_csv_text(const nlohmann::json& report);

// What read_sweep_report accepts: glint's reports nest 7 levels deep and take ~3-5 KB per
// configuration, ~0.5 GB for the largest sweep (kMaxSweepConfigurations).
inline constexpr std::size_t kSweepReportMaxFileBytes = std::size_t{1} << 30;
inline constexpr int kSweepReportMaxJsonDepth = 32;

// Reads a report written by -o FILE.json. Throws InputError naming the file for anything that is
// not a version-1 sweep report, larger than kSweepReportMaxFileBytes or nested deeper than
// kSweepReportMaxJsonDepth.
nlohmann::json read_sweep_report(const std::string& path);
// The same from the file's text; `path` names it in messages.
nlohmann::json parse_sweep_report(const std::string& text, const std::string& path);

// Joins shard reports (path, document) into the unsharded run's document: every shard of the same
// sweep (the same version, input, grids, settings and shard count), each shard once, every
// configuration once; rows by index; Pareto flags over the union. Throws std::invalid_argument
// naming the file that does not fit.
nlohmann::json merge_sweep_reports(
    const std::vector<std::pair<std::string, nlohmann::json>>& shards);

}  // namespace glint
