#include "eval/sim_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "eval/json_diff.h"
#include "units/lane_cost.h"

namespace glint {

nlohmann::json unit_sim_report(const SpecularUnit& unit, const TimingStats& t, const UnitStats& s,
                               std::uint64_t digest, bool node) {
  const UnitCost cost = unit_cost(unit);
  nlohmann::json ops = nlohmann::json::object();
  for (const auto& [kind, n] : cost.ops_per_computed)
    ops[kind] = ops.value(kind, 0.0) + n * static_cast<double>(t.computed);
  for (const auto& [kind, n] : cost.ops_per_request)
    ops[kind] = ops.value(kind, 0.0) + n * static_cast<double>(t.results);
  const nlohmann::json description = unit.describe();
  nlohmann::json r = {
      {"unit", s.name},
      {"spec", unit.canonical_spec()},
      {"config", description["config"]},
      {"timing", description["timing"]},
      {"elaboration", description["elaboration"]},
      {"vectors", s.vectors},
      {"skipped", s.skipped},
      {"computed", t.computed},
      {"cycles", t.cycles},
      {"throughput", t.throughput()},
      {"latency", {{"min", t.latency_min}, {"mean", t.latency_mean()}, {"max", t.latency_max}}},
      {"stall_cycles", t.stall_cycles()},
      {"stalls", {{"merge_buffer_full", t.stall_credit}, {"unit_busy", t.stall_unit}}},
      {"sink_wait", t.sink_wait},
      {"operations", ops},
      {"area", {{"ge", cost.area_ge}, {"inventory", cost.to_json()["inventory"]}}},
      {"critical_path", {{"delay", cost.critical_path}, {"stage", cost.critical_stage}}},
      {"errors", s.errors_json()},
      {"digest", fmt::format("{:016x}", digest)},
  };
  if (node) r["node"] = cost.node_json();
  return r;
}

std::string node_line(const nlohmann::json& n) {
  return fmt::format("at {}: {:.0f} um2, critical path {:.2f} ns ({}), {:.0f} MHz",
                     n.at("node").get<std::string>(), n.at("area_um2").get<double>(),
                     n.at("critical_path_ns").get<double>(),
                     n.at("critical_path").get<std::string>(), n.at("max_clock_mhz").get<double>());
}

std::string format_sim_table(const nlohmann::json& report) {
  // Columns named as their measures are (src/sweep/measures.h), as `glint eval`'s table names its.
  std::string out = fmt::format(
      "{:<9} {:>9} {:>7} {:>10} {:>10} {:>20} {:>12} {:>9} {:>13} {:>10} {:>17} {:>17}\n", "unit",
      "vectors", "skip%", "cycles", "throughput", "latency_min/mean/max", "stall_cycles", "area_ge",
      "critical_path", "max_abs", "max_datapath_ulps", "mismatch_fraction");
  for (const auto& u : report.at("units")) {
    const auto vectors = u.at("vectors").get<std::uint64_t>();
    const double skip = vectors ? 100.0 * u.at("skipped").get<double>() / vectors : 0.0;
    const auto& lat = u.at("latency");
    out += fmt::format(
        "{:<9} {:>9} {:>6.1f}% {:>10} {:>10.3f} {:>20} {:>12} {:>9.0f} {:>13.1f} {:>10.3e} "
        "{:>17.3f} {:>17.4f}\n",
        u.at("unit").get<std::string>(), vectors, skip, u.at("cycles").get<std::uint64_t>(),
        u.at("throughput").get<double>(),
        fmt::format("{}/{:.1f}/{}", lat.at("min").get<std::uint64_t>(),
                    lat.at("mean").get<double>(), lat.at("max").get<std::uint64_t>()),
        u.at("stall_cycles").get<std::uint64_t>(), u.at("area").at("ge").get<double>(),
        u.at("critical_path").at("delay").get<double>(), u.at("errors").at("max_abs").get<double>(),
        u.at("errors").at("max_datapath_ulps").get<double>(),
        u.at("errors").at("mismatch_fraction").get<double>());
  }
  return out;
}

namespace {

void diff_value(const std::string& path, const nlohmann::json& g, const nlohmann::json& f,
                bool exact, double rel_tol, std::vector<std::string>& out) {
  // Exact fields (digest, counts, cycles, ...) must be equal; the others are floating-point sums
  // that may move within rel_tol.
  const Tolerant tolerant = [exact](const nlohmann::json& a, const nlohmann::json& b) {
    return !exact && a.is_number() && b.is_number();
  };
  diff_json(path, g, f, tolerant, rel_tol, out);
}

}  // namespace

std::vector<std::string> diff_sim_reports(const nlohmann::json& golden, const nlohmann::json& fresh,
                                          double rel_tol) {
  std::vector<std::string> out;
  // The run's settings and counts (rows, slots, mode, ...) must match exactly; a field on one side
  // only is a difference too (regress checks the golden's schema first, check_report_shape).
  for (auto it = golden.begin(); it != golden.end(); ++it) {
    if (it.key() == "units") continue;
    if (!fresh.contains(it.key())) {
      out.push_back(it.key() + ": missing in the new report");
      continue;
    }
    diff_value(it.key(), it.value(), fresh.at(it.key()), true, rel_tol, out);
  }
  for (auto it = fresh.begin(); it != fresh.end(); ++it)
    if (!golden.contains(it.key())) out.push_back(it.key() + ": new field (not in the golden)");
  const auto& gu = golden.at("units");
  const auto& fu = fresh.at("units");
  if (gu.size() != fu.size()) {
    out.push_back(
        fmt::format("units: {} in the new report, {} in the golden", fu.size(), gu.size()));
    return out;
  }
  // Float statistics (errors, area, critical path, throughput/latency means, the elaboration's tau
  // and c_y) get the tolerance;
  // everything else is bit-accurate or an integer count and must match exactly.
  static const char* kTolerant[] = {"errors",     "area",    "critical_path",
                                    "throughput", "latency", "elaboration"};
  for (std::size_t i = 0; i < gu.size(); ++i) {
    const std::string name =
        gu[i].is_object() && gu[i].contains("unit") && gu[i]["unit"].is_string()
            ? gu[i]["unit"].get<std::string>()
            : std::to_string(i);
    for (auto it = gu[i].begin(); it != gu[i].end(); ++it) {
      const std::string path = name + "." + it.key();
      if (!fu[i].contains(it.key())) {
        out.push_back(path + ": missing in the new report");
        continue;
      }
      bool exact = true;
      for (const char* k : kTolerant) exact = exact && it.key() != k;
      diff_value(path, it.value(), fu[i].at(it.key()), exact, rel_tol, out);
    }
    for (auto it = fu[i].begin(); it != fu[i].end(); ++it)
      if (!gu[i].contains(it.key()))
        out.push_back(name + "." + it.key() + ": new field (not in the golden)");
  }
  return out;
}

}  // namespace glint
