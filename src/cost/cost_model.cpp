#include "cost/cost_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace glint {

const CostConstants& cost_constants() {
  static const CostConstants k;
  return k;
}

double adder_delay(int width) {
  return 2.0 * clog2(std::max(width, 1)) + 2.0;
}

int multiplier_tree_levels(int rows) {
  int levels = 0;
  for (int d = 2; d < rows; d = d * 3 / 2) ++levels;  // Dadda: 2, 3, 4, 6, 9, 13, 19, 28, ...
  return levels;
}

double multiplier_delay(int width_a, int width_b) {
  const CostConstants& k = cost_constants();
  return k.and_delay + k.fa_level_delay * multiplier_tree_levels(std::min(width_a, width_b)) +
         adder_delay(width_a + width_b);
}

double divider_row_delay(int divisor_bits) {
  return adder_delay(divisor_bits + 1) + cost_constants().mux_delay;
}

double table_delay(int entries) {
  return clog2(std::max(entries, 1)) + 2.0;
}

// ---- JSON
// ----------------------------------------------------------------------------------------

nlohmann::json Primitive::to_json() const {
  return {{"kind", kind},   {"width_a", width_a}, {"width_b", width_b},
          {"count", count}, {"ge", ge},           {"where", where}};
}

Primitive Primitive::from_json(const nlohmann::json& j) {
  Primitive p;
  p.kind = j.at("kind").get<std::string>();
  p.width_a = j.at("width_a").get<int>();
  p.width_b = j.at("width_b").get<int>();
  p.count = j.at("count").get<int>();
  p.ge = j.at("ge").get<double>();
  p.where = j.at("where").get<std::string>();
  return p;
}

nlohmann::json UnitCost::to_json() const {
  nlohmann::json inv = nlohmann::json::array();
  for (const Primitive& p : inventory) inv.push_back(p.to_json());
  nlohmann::json st = nlohmann::json::array();
  for (const StageDelay& s : stages)
    st.push_back({{"stage", s.stage}, {"delay", s.delay}, {"path", s.path}});
  return {{"area_ge", area_ge},
          {"critical_path", critical_path},
          {"critical_stage", critical_stage},
          {"stages", std::move(st)},
          {"ops_per_computed", ops_per_computed},
          {"ops_per_request", ops_per_request},
          {"inventory", std::move(inv)}};
}

UnitCost UnitCost::from_json(const nlohmann::json& j) {
  UnitCost c;
  for (const auto& p : j.at("inventory")) c.inventory.push_back(Primitive::from_json(p));
  c.area_ge = j.at("area_ge").get<double>();
  c.critical_path = j.at("critical_path").get<double>();
  c.critical_stage = j.at("critical_stage").get<std::string>();
  for (const auto& s : j.at("stages"))
    c.stages.push_back({s.at("stage").get<std::string>(), s.at("delay").get<double>(),
                        s.at("path").get<std::string>()});
  c.ops_per_computed = j.at("ops_per_computed").get<std::map<std::string, double>>();
  c.ops_per_request = j.at("ops_per_request").get<std::map<std::string, double>>();
  return c;
}

}  // namespace glint
