#include "sweep/golden_budgets.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <stdexcept>

#include "eval/golden_diff.h"
#include "io/input_error.h"

namespace glint {
namespace {

// Where a sweep row's value is in a lane of each report: {row pointer, lane pointer}.
struct RowField {
  const char* row;
  const char* lane;
};

constexpr RowField kSimRow[] = {{"/unit", "/unit"},
                                {"/spec", "/spec"},
                                {"/area_ge", "/area/ge"},
                                {"/critical_path", "/critical_path/delay"},
                                {"/critical_stage", "/critical_path/stage"},
                                {"/latency", "/timing/latency"},
                                {"/ii", "/timing/ii"},
                                {"/buffer_depth", "/timing/buffer_depth"},
                                {"/vectors", "/vectors"},
                                {"/skipped", "/skipped"},
                                {"/computed", "/computed"},
                                {"/cycles", "/cycles"},
                                {"/throughput", "/throughput"},
                                {"/latency_cycles", "/latency"},
                                {"/stall_cycles", "/stall_cycles"},
                                {"/stalls", "/stalls"},
                                {"/errors", "/errors"},
                                {"/digest", "/digest"}};
// A render has no timing: no cycles, latency or throughput to hold a lane to.
constexpr RowField kRenderRow[] = {{"/unit", "/unit"},        {"/spec", "/spec"},
                                   {"/area_ge", "/area_ge"},  {"/critical_path", "/critical_path"},
                                   {"/vectors", "/requests"}, {"/skipped", "/skipped"},
                                   {"/errors", "/errors"},    {"/image", "/image_error"}};
// Filled from several fields (budget_row), in both reports unless named.
constexpr const char* kDerivedRow[] = {"/operations/total", "/computed"};
constexpr const char* kDerivedSimOnly = "/area_latency";

bool under(const std::string& pointer, const std::string& prefix) {
  return pointer.compare(0, prefix.size(), prefix) == 0 &&
         (pointer.size() == prefix.size() || pointer[prefix.size()] == '/');
}

template <std::size_t N>
bool any_under(const std::string& pointer, const RowField (&fields)[N]) {
  return std::any_of(std::begin(fields), std::end(fields),
                     [&](const RowField& f) { return under(pointer, f.row); });
}

bool row_has(GoldenKind kind, const std::string& pointer) {
  const bool trace = kind == GoldenKind::kTrace;
  if (trace ? any_under(pointer, kSimRow) : any_under(pointer, kRenderRow)) return true;
  for (const char* d : kDerivedRow)
    if (under(pointer, d)) return true;
  return trace && under(pointer, kDerivedSimOnly);
}

}  // namespace

std::vector<LaneBudget> parse_golden_budgets(const Golden& g, const std::string& file) {
  const bool scene = g.kind == GoldenKind::kScene;
  std::vector<LaneBudget> out;
  for (const auto& [spec, text] : g.budgets) {
    const std::string field = "budgets." + spec;
    LaneBudget lane{spec, text, {}};
    try {
      lane.conditions = parse_budgets(text, scene, "budget");
    } catch (const std::invalid_argument& e) {
      throw InputError(file, 0, field, e.what());
    }
    for (const Budget& b : lane.conditions)
      if (!row_has(g.kind, b.measure.pointer))
        throw InputError(file, 0, field,
                         fmt::format("'{}': a {} report has no figure for '{}'", b.text,
                                     scene ? "render" : "sim", b.measure.name));
    out.push_back(std::move(lane));
  }
  return out;
}

nlohmann::json budget_row(GoldenKind kind, const nlohmann::json& lane) {
  const bool trace = kind == GoldenKind::kTrace;
  nlohmann::json row = nlohmann::json::object();
  const auto copy = [&](const RowField& f) {
    const nlohmann::json::json_pointer from(f.lane);
    if (lane.contains(from)) row[nlohmann::json::json_pointer(f.row)] = lane.at(from);
  };
  if (trace) {
    for (const RowField& f : kSimRow) copy(f);
  } else {
    for (const RowField& f : kRenderRow) copy(f);
  }
  // Every kind the sweep's rows have, 0 when the lane never executes it.
  nlohmann::json total = nlohmann::json::object();
  for (const std::string& kind_name : operation_kinds()) total[kind_name] = 0.0;
  if (lane.contains("operations") && lane["operations"].is_object())
    for (auto it = lane["operations"].begin(); it != lane["operations"].end(); ++it)
      total[it.key()] = *it;
  row["operations"] = {{"total", total}};
  if (!trace && row.contains("vectors") && row.contains("skipped"))
    row["computed"] = row["vectors"].get<std::uint64_t>() - row["skipped"].get<std::uint64_t>();
  if (trace && row.contains("area_ge") && row.contains("latency"))
    row["area_latency"] = row["area_ge"].get<double>() * row["latency"].get<double>();
  return row;
}

std::vector<std::string> broken_budgets(const Golden& g, const std::vector<LaneBudget>& budgets,
                                        const nlohmann::json& report) {
  std::vector<std::string> out;
  const auto& lanes = report.at("units");
  const auto labels = lane_labels(report);
  for (std::size_t i = 0; i < g.units.size() && i < lanes.size(); ++i) {
    for (const LaneBudget& lb : budgets) {
      if (lb.spec != g.units[i]) continue;
      const nlohmann::json row = budget_row(g.kind, lanes[i]);
      for (const Budget& b : lb.conditions) {
        if (meets(row, b)) continue;
        const auto v = measure_value(row, b.measure);
        out.push_back(fmt::format("{}: {} does not hold: {}", labels[i], b.text,
                                  v ? fmt::format("{:.6g}", *v) : std::string("no value")));
      }
    }
  }
  return out;
}

}  // namespace glint
