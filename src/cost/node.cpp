#include "cost/node.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "cost/node_osu018.h"

namespace glint {

double NodeDelay::at(double x, double y, double loads) const {
  return std::max(0.0, c0 + per_x * x + per_log2 * std::log2(std::max(y, 1.0)) + per_load * loads +
                           per_load2 * loads * loads);
}

std::string node_part_name(const NodeConstants& k, const NodePart& p) {
  const std::pair<const NodePart*, const char*> parts[] = {{&k.adder, "adder"},
                                                           {&k.comparator, "comparator"},
                                                           {&k.multiplier, "multiplier"},
                                                           {&k.divider, "divider"},
                                                           {&k.mux, "mux"},
                                                           {&k.shifter, "shifter"},
                                                           {&k.lzd, "lzd"},
                                                           {&k.gates, "gates"},
                                                           {&k.rom, "rom"},
                                                           {&k.ram, "ram"},
                                                           {&k.ram_computed, "ram_computed"},
                                                           {&k.dff, "dff"},
                                                           {&k.dffe, "dffe"}};
  for (const auto& [part, name] : parts)
    if (part == &p) return name;
  return "other";
}

const NodeConstants& node_osu018() {
  static const NodeConstants k = make_osu018();
  return k;
}

const NodeConstants* find_node(const std::string& name) {
  return name == node_osu018().name ? &node_osu018() : nullptr;
}

std::vector<std::string> node_names() {
  return {node_osu018().name};
}

}  // namespace glint
