// What `glint regress` says when a report moved, before its full list of differences: first what
// changed in the hardware (a lane's resolved SPEC, its colour stage, timing and elaboration, the
// chip's slot capacity and sink), then the headline figures that moved, in words ("hast: max
// error rose 0.31 LSB -> 0.52 LSB (+68 %); area 6 301 -> 6 762 GE (+7.3 %)"), largest first.
//
// Both work on the reports' JSON alone (sim_report.md, render_report.md), from tables of JSON
// pointers: a hardware field a report gains (a lane's or the run's "chip") is one more row.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/golden.h"

namespace glint {

// The lanes' labels in a report: its units' names, numbered where one repeats ("hast.1").
std::vector<std::string> lane_labels(const nlohmann::json& report);

// One line per hardware field that differs between the golden's report and the fresh one
// ("lut: spec bits=6 -> bits=7", "slot capacity 42 -> 64"); empty when none does.
std::vector<std::string> hardware_changes(GoldenKind kind, const nlohmann::json& golden,
                                          const nlohmann::json& fresh);

// One line per lane whose headline figures moved beyond `rel_tol` (as the full comparison
// counts them), the lane whose largest relative move is greatest first; at most `max_lanes`
// lines, then one saying how many more.
std::vector<std::string> largest_changes(GoldenKind kind, const nlohmann::json& golden,
                                         const nlohmann::json& fresh, double rel_tol,
                                         std::size_t max_lanes = 5);

// The render report compared field by field over the whole document: strings, booleans and
// integers (counts, pixels) exactly, other numbers (errors, area, ratios) within `rel_tol`
// relative (plus 1e-12 absolute); a field on one side only is a difference. One line per
// difference, the fresh value first, as diff_sim_reports.
std::vector<std::string> diff_render_reports(const nlohmann::json& golden,
                                             const nlohmann::json& fresh, double rel_tol = 1e-9);

}  // namespace glint
