#include "cost/cost_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <stdexcept>
#include <utility>

namespace glint {

const CostConstants& cost_constants() {
  static const CostConstants k;
  return k;
}

double adder_delay(int width) {
  const CostConstants& k = cost_constants();
  return std::max(1.0, k.add_depth0 + k.add_depth_log * std::log2(std::max(width, 2)));
}

double comparator_delay(int width) {
  const CostConstants& k = cost_constants();
  return std::max(1.0, k.cmp_depth0 + k.cmp_depth_log * std::log2(std::max(width, 2)));
}

double multiplier_delay(int width_a, int width_b) {
  const CostConstants& k = cost_constants();
  const int lo = std::max(1, std::min(width_a, width_b));
  return std::max(1.0, k.mul_depth0 + k.mul_depth_min * std::log2(lo) +
                           k.mul_depth_sum * std::log2(width_a + width_b));
}

double multiplier_ge(int width_a, int width_b, bool is_signed) {
  const CostConstants& k = cost_constants();
  const double ab = static_cast<double>(width_a) * width_b, sum = width_a + width_b;
  // A one-bit operand is an AND row; the fit's negative (A + B) term is for real trees.
  const double ge =
      is_signed ? k.smul_ab_ge * ab + k.smul_sum_ge * sum : k.mul_ab_ge * ab + k.mul_sum_ge * sum;
  return std::max(ge, 1.5 * ab);
}

double divider_row_delay(int divisor_bits) {
  return adder_delay(divisor_bits + 2) + 1;  // the subtractor's borrow, then the restore mux
}

double table_delay(int entries) {
  const CostConstants& k = cost_constants();
  if (entries <= 2) return entries <= 1 ? 0 : 1;
  return k.rom_depth0 + k.rom_depth_log * std::log2(entries);
}

double mux_delay(int inputs) {
  const CostConstants& k = cost_constants();
  if (inputs <= 1) return 0;
  if (inputs == 2) return 1;
  return k.mux_depth0 + k.mux_depth_log * clog2(inputs);
}

double rom_ge(const std::vector<std::int64_t>& words, int width) {
  if (words.size() <= 2) return 0;
  const int ab = clog2(static_cast<long long>(words.size()));
  const std::size_t n = std::size_t{1} << ab;
  double nodes = 0;
  std::vector<std::uint8_t> f(n);
  std::set<std::vector<std::uint8_t>> seen;
  for (int bit = 0; bit < width; ++bit) {
    for (std::size_t i = 0; i < n; ++i)
      f[i] = i < words.size() ? static_cast<std::uint8_t>((words[i] >> bit) & 1) : 0;
    seen.clear();
    // Level by level, address MSB first: a node is a distinct sub-function that depends on its
    // variable and is not a single literal (both halves constant: a wire or an inverter).
    for (std::size_t size = n; size >= 2; size /= 2) {
      for (std::size_t i = 0; i < n; i += size) {
        const auto b = f.begin() + static_cast<std::ptrdiff_t>(i);
        const auto mid = b + static_cast<std::ptrdiff_t>(size / 2);
        const auto e = b + static_cast<std::ptrdiff_t>(size);
        if (std::equal(b, mid, mid)) continue;
        const bool lo_const = std::adjacent_find(b, mid, std::not_equal_to<>()) == mid;
        const bool hi_const = std::adjacent_find(mid, e, std::not_equal_to<>()) == e;
        if (lo_const && hi_const) continue;
        seen.emplace(b, e);
      }
    }
    nodes += static_cast<double>(seen.size());
  }
  return nodes * cost_constants().rom_node_ge;
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

nlohmann::json UnitCost::node_json() const {
  nlohmann::json paths = nlohmann::json::array();
  for (const auto* list : {&stages, &lane_paths})
    for (const StageDelay& s : *list) {
      nlohmann::json chain = nlohmann::json::array();
      for (const StageDelay::Part& p : s.parts)
        chain.push_back(
            {{"part", p.label}, {"kind", p.kind}, {"ns", p.ns}, {"counted_ns", p.counted_ns}});
      paths.push_back({{"path", s.stage}, {"ns", s.ns}, {"parts", s.path}, {"chain", chain}});
    }
  nlohmann::json area = nlohmann::json::object();
  nlohmann::json unfitted = nlohmann::json::object(), factors = nlohmann::json::object();
  for (const Primitive& p : inventory) {
    area[p.kind] = area.value(p.kind, 0.0) + p.um2;
    unfitted[p.node_part] = unfitted.value(p.node_part, 0.0) + p.um2_unfitted;
    if (p.um2_unfitted > 0) factors[p.node_part] = p.um2 / p.um2_unfitted;
  }
  return {{"node", node},
          {"area_um2", area_um2},
          {"area_um2_by_kind", std::move(area)},
          {"area_um2_unfitted_by_part", std::move(unfitted)},
          {"lane_area_factors", std::move(factors)},
          {"critical_path_ns", critical_path_ns},
          {"max_clock_mhz", critical_path_ns > 0 ? 1000.0 / critical_path_ns : 0.0},
          {"critical_path", critical_path_node},
          {"paths", std::move(paths)}};
}

UnitCost UnitCost::from_json(const nlohmann::json& j) {
  UnitCost c;
  for (const auto& p : j.at("inventory")) c.inventory.push_back(Primitive::from_json(p));
  c.area_ge = j.at("area_ge").get<double>();
  c.critical_path = j.at("critical_path").get<double>();
  c.critical_stage = j.at("critical_stage").get<std::string>();
  for (const auto& s : j.at("stages"))
    c.stages.push_back({s.at("stage").get<std::string>(),
                        s.at("delay").get<double>(),
                        s.at("path").get<std::string>(),
                        0,
                        {}});
  c.ops_per_computed = j.at("ops_per_computed").get<std::map<std::string, double>>();
  c.ops_per_request = j.at("ops_per_request").get<std::map<std::string, double>>();
  return c;
}

}  // namespace glint
