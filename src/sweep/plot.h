// The plots of a sweep (`glint sweep --plot DIR`): error against area and against throughput, each
// as SVG and PNG. Log axes; every configuration a point, grey when dominated; the Pareto front in
// its unit family's colour, joined by a step line (the edge of what the front dominates) and
// numbered, the numbers keyed to the specs beside the plot.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "image/image.h"

namespace glint {

struct SweepPlot {
  std::string name;  // file name without extension: "error_vs_area", "error_vs_throughput"
  std::string svg;
  Image8 png;
  std::size_t points = 0;  // configurations drawn (those with a positive x and an error value)
  std::size_t front = 0;   // of them on the front
};

// Both plots of a report whose rows carry "error" and "pareto" (report.h's mark_pareto); without
// `png`, the SVG alone (an HTML page inlines it).
std::vector<SweepPlot> sweep_plots(const nlohmann::json& report, bool png = true);

}  // namespace glint
