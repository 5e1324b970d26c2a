#include "sweep/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "io/input_error.h"
#include "sweep/measures.h"
#include "sweep/pareto.h"

namespace glint {
namespace {

bool is_scene(const nlohmann::json& report) {
  return report.at("input").at("kind") == "scene";
}

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_cell(const nlohmann::json& row, const SweepColumn& c) {
  const nlohmann::json::json_pointer ptr(c.pointer);
  if (!row.contains(ptr)) return "";
  const nlohmann::json& v = row.at(ptr);
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_string()) return csv_text(v.get<std::string>());
  if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
  if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
  // The shortest text that reads back as the same double (as the JSON has it).
  if (v.is_number_float()) return fmt::format("{}", v.get<double>());
  return csv_text(v.dump());
}

}  // namespace

void mark_pareto(nlohmann::json& report) {
  nlohmann::json& rows = report.at("results");
  const MeasureRef m = measure_or_throw(report.at("error_measure").get<std::string>(),
                                        report.value("image_error", false), "error_measure");
  const std::size_t n = rows.size();
  std::vector<double> error(n, NAN);
  for (std::size_t i = 0; i < n; ++i) {
    const std::optional<double> v = measure_value(rows[i], m);
    rows[i]["error"] = v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    if (v) error[i] = *v;
  }
  for (const Objective& o : kObjectives) {
    std::vector<double> cost(n, NAN);
    for (std::size_t i = 0; i < n; ++i) {
      const auto v = rows[i].find(o.key);  // a refused configuration has none
      if (v != rows[i].end() && v->is_number())
        cost[i] = o.minimise ? v->get<double>() : -v->get<double>();
    }
    const std::vector<bool> on = pareto_front(error, cost);
    for (std::size_t i = 0; i < n; ++i) rows[i]["pareto"][o.name] = static_cast<bool>(on[i]);
  }
}

std::string report_json_text(const nlohmann::json& report) {
  return report.dump(2) + "\n";
}

std::string report_csv_text(const nlohmann::json& report) {
  const bool scene = is_scene(report);
  std::vector<const SweepColumn*> cols;
  for (const SweepColumn& c : sweep_columns())
    if (scene || !c.scene_only) cols.push_back(&c);
  std::string out;
  for (std::size_t k = 0; k < cols.size(); ++k) out += (k ? "," : "") + csv_text(cols[k]->name);
  out += "\n";
  for (const nlohmann::json& row : report.at("results")) {
    for (std::size_t k = 0; k < cols.size(); ++k) out += (k ? "," : "") + csv_cell(row, *cols[k]);
    out += "\n";
  }
  return out;
}

nlohmann::json read_sweep_report(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "file", "cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t at = std::min<std::size_t>(e.byte, text.size());
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    throw InputError(path, static_cast<std::uint64_t>(line), "json",
                     "not valid JSON (a sweep report written by glint sweep -o FILE.json)");
  }
  if (!j.is_object() || !j.contains("glint_sweep_report"))
    throw InputError(path, 0, "glint_sweep_report",
                     "missing: not a sweep report (glint sweep -o FILE.json)");
  if (j["glint_sweep_report"] != kSweepReportVersion)
    throw InputError(path, 0, "glint_sweep_report",
                     fmt::format("version {} (this glint reads version {})",
                                 j["glint_sweep_report"].dump(), kSweepReportVersion));
  for (const char* key : {"input", "results", "configurations", "shard", "error_measure"})
    if (!j.contains(key)) throw InputError(path, 0, key, "missing");
  if (!j["results"].is_array()) throw InputError(path, 0, "results", "not an array");
  if (!j["configurations"].is_number_unsigned())
    throw InputError(path, 0, "configurations", "not a count");
  for (const nlohmann::json& row : j["results"])
    if (!row.is_object() || !row.contains("index") || !row["index"].is_number_unsigned())
      throw InputError(path, 0, "results", "a row without an index");
  return j;
}

nlohmann::json merge_sweep_reports(
    const std::vector<std::pair<std::string, nlohmann::json>>& shards) {
  if (shards.empty()) throw std::invalid_argument("merge: no shard reports given");
  const auto sweep_of = [](const nlohmann::json& r) {
    nlohmann::json s = r;
    s.erase("results");
    s.erase("shard");
    return s;
  };
  const nlohmann::json sweep = sweep_of(shards.front().second);
  const nlohmann::json& first_shard = shards.front().second.at("shard");
  if (!first_shard.is_object())
    throw std::invalid_argument(
        fmt::format("merge: {} is not a shard (it was run without --shard)", shards.front().first));
  const std::size_t count = first_shard.at("count").get<std::size_t>();
  std::vector<const std::string*> seen(count, nullptr);
  const std::size_t configurations = sweep.at("configurations").get<std::size_t>();
  std::vector<nlohmann::json> rows(configurations);
  std::vector<bool> have(configurations, false);
  for (const auto& [path, r] : shards) {
    const nlohmann::json& shard = r.at("shard");
    if (!shard.is_object())
      throw std::invalid_argument(
          fmt::format("merge: {} is not a shard (it was run without --shard)", path));
    if (sweep_of(r) != sweep)
      throw std::invalid_argument(
          fmt::format("merge: {} is from another sweep than {} (input, grids or settings differ)",
                      path, shards.front().first));
    const std::size_t k = shard.at("index").get<std::size_t>();
    if (shard.at("count").get<std::size_t>() != count || k >= count)
      throw std::invalid_argument(fmt::format("merge: {} is shard {}/{}, the others are of {}",
                                              path, k, shard.at("count").dump(), count));
    if (seen[k])
      throw std::invalid_argument(
          fmt::format("merge: {} and {} are both shard {}/{}", *seen[k], path, k, count));
    seen[k] = &path;
    for (const nlohmann::json& row : r.at("results")) {
      const std::size_t i = row.at("index").get<std::size_t>();
      if (i >= configurations || i % count != k || have[i])
        throw std::invalid_argument(fmt::format(
            "merge: {}: configuration {} does not belong to shard {}/{} of {} configurations "
            "(or is there twice)",
            path, i, k, count, configurations));
      rows[i] = row;
      have[i] = true;
    }
  }
  for (std::size_t k = 0; k < count; ++k)
    if (!seen[k])
      throw std::invalid_argument(fmt::format("merge: shard {}/{} is missing", k, count));
  for (std::size_t i = 0; i < configurations; ++i)
    if (!have[i])
      throw std::invalid_argument(
          fmt::format("merge: configuration {} is in no shard (shard {}/{})", i, i % count, count));
  nlohmann::json out = sweep;
  out["shard"] = nullptr;
  out["results"] = std::move(rows);
  mark_pareto(out);
  return out;
}

}  // namespace glint
