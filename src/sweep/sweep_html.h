// The pages of `glint sweep --html FILE` and `glint size --html FILE`: one self-contained HTML file
// each (io/html.h) from the report the run also prints with --json: the key figures, the command
// that reproduces it, the Pareto plots as inline SVG (plot.h), the fronts and every configuration
// as sortable tables in the CSV's columns, and for size the choice per family and overall.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/html.h"

namespace glint {

// A sweep report (report.h: rows with their Pareto flags).
std::string sweep_html(const nlohmann::json& report, const HtmlRunInfo& run);

// A size document (size.h's SizeRun::document) and the sweep reports of the chosen chip per input
// (SizeRun::reports), whose fronts are plotted.
std::string size_html(const nlohmann::json& document, const std::vector<nlohmann::json>& reports,
                      const HtmlRunInfo& run);

}  // namespace glint
