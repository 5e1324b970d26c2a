#include "sweep/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "io/input_error.h"
#include "io/json_text.h"
#include "sweep/grid.h"
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

std::vector<Objective> report_objectives(const nlohmann::json& report) {
  std::vector<Objective> out(std::begin(kObjectives), std::end(kObjectives));
  const nlohmann::json& rows = report.at("results");
  if (std::any_of(rows.begin(), rows.end(),
                  [](const nlohmann::json& r) { return r.contains(kEnergyObjective.key); }))
    out.push_back(kEnergyObjective);
  return out;
}

bool report_has_node(const nlohmann::json& report) {
  const nlohmann::json& rows = report.at("results");
  return std::any_of(rows.begin(), rows.end(), [](const nlohmann::json& r) {
    return r.contains("node") || r.contains(kEnergyObjective.key);
  });
}

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
  for (const Objective& o : report_objectives(report)) {
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
  const bool node = report_has_node(report);
  std::vector<const SweepColumn*> cols;
  for (const SweepColumn& c : sweep_columns())
    if ((scene || !c.scene_only) && (node || !c.node_only)) cols.push_back(&c);
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
  return parse_sweep_report(read_text_file(path, kSweepReportMaxFileBytes, "sweep report"), path);
}

nlohmann::json parse_sweep_report(const std::string& text, const std::string& path) {
  // Read defensively (io/json_text.h), as goldens are: a shard report is a file a user hands
  // glint, and the merged report is dump()ed, which recurses once per level of nesting.
  const nlohmann::json j = parse_json_text(text, path, kSweepReportMaxJsonDepth);
  if (!j.is_object() || !j.contains("glint_sweep_report"))
    throw InputError(path, 0, "glint_sweep_report",
                     "missing: not a sweep report (glint sweep -o FILE.json)");
  if (j["glint_sweep_report"] != kSweepReportVersion)
    throw InputError(path, 0, "glint_sweep_report",
                     fmt::format("version {} (this glint reads version {})",
                                 j["glint_sweep_report"].dump(), kSweepReportVersion));
  for (const char* key :
       {"input", "results", "configurations", "shard", "error_measure", "display_bits"})
    if (!j.contains(key)) throw InputError(path, 0, key, "missing");
  // What merge, the CSV and the plots read is checked here, so that no read there can throw
  // nlohmann's type errors or size vectors from a file's numbers.
  const nlohmann::json& input = j["input"];
  if (!input.is_object() || !input.contains("kind") || !input["kind"].is_string() ||
      !input.contains("path") || !input["path"].is_string() || !input.contains("rows") ||
      !input["rows"].is_number_unsigned())
    throw InputError(path, 0, "input", "not an object with a kind, a path and a row count");
  if (!j["error_measure"].is_string()) throw InputError(path, 0, "error_measure", "not a name");
  if (!j["display_bits"].is_number_unsigned() || j["display_bits"].get<std::uint64_t>() < 1 ||
      j["display_bits"].get<std::uint64_t>() > 16)
    throw InputError(path, 0, "display_bits", "not in 1..16");
  if (j.contains("image_error") && !j["image_error"].is_boolean())
    throw InputError(path, 0, "image_error", "not true or false");
  if (!j["configurations"].is_number_unsigned() ||
      j["configurations"].get<std::uint64_t>() > kMaxSweepConfigurations)
    throw InputError(path, 0, "configurations",
                     fmt::format("not a count in 0..{}", kMaxSweepConfigurations));
  const nlohmann::json& shard = j["shard"];
  if (!shard.is_null()) {
    const auto count_in = [&](const char* key, std::uint64_t lo, std::uint64_t hi) {
      return shard.is_object() && shard.contains(key) && shard[key].is_number_unsigned() &&
             shard[key].get<std::uint64_t>() >= lo && shard[key].get<std::uint64_t>() <= hi;
    };
    if (!count_in("count", 1, kMaxSweepConfigurations) ||
        !count_in("index", 0, shard["count"].get<std::uint64_t>() - 1))
      throw InputError(path, 0, "shard",
                       fmt::format("not null or {{index: K, count: N}} with 0 <= K < N <= {}",
                                   kMaxSweepConfigurations));
  }
  if (!j["results"].is_array()) throw InputError(path, 0, "results", "not an array");
  const auto kind_fits = [](const nlohmann::json& v, ColumnKind kind) {
    switch (kind) {
      case ColumnKind::kInteger:
        return v.is_number_integer();
      case ColumnKind::kNumber:
        return v.is_number();
      case ColumnKind::kText:
        return v.is_string();
      case ColumnKind::kFlag:
        return v.is_boolean();
    }
    return false;
  };
  std::size_t at = 0;
  for (const nlohmann::json& row : j["results"]) {
    const std::string where = fmt::format("results[{}]", at++);
    if (!row.is_object() || !row.contains("index") || !row["index"].is_number_unsigned())
      throw InputError(path, 0, where, "a row without an index");
    const auto field = [&](const char* key, bool (nlohmann::json::*is)() const noexcept,
                           const char* what) {
      if (!row.contains(key) || !(row[key].*is)())
        throw InputError(path, 0, where + "/" + key, what);
    };
    field("unit", &nlohmann::json::is_string, "not a unit name");
    field("spec", &nlohmann::json::is_string, "not a spec");
    if (!row.contains("refused") || !(row["refused"].is_null() || row["refused"].is_string()))
      throw InputError(path, 0, where + "/refused", "not null or the reason");
    // A refused configuration has no measures. Any other row has every column glint writes but
    // the image-level ones (absent with --no-image), the node's and the energy's (only with
    // --node) and those merge recomputes (error, pareto), each of its column's type or null (a
    // measure with no value), and an integer latency (the summary prints it).
    const bool refused = row["refused"].is_string();
    if (!refused) field("latency", &nlohmann::json::is_number_integer, "not a cycle count");
    for (const SweepColumn& c : sweep_columns()) {
      const nlohmann::json::json_pointer pointer(c.pointer);
      const bool recomputed = c.name == "error" || c.name.rfind("pareto_", 0) == 0;
      if (!row.contains(pointer)) {
        if (refused || c.scene_only || c.node_only || recomputed) continue;
        throw InputError(path, 0, where + c.pointer, "missing");
      }
      const nlohmann::json& v = row.at(pointer);
      if (!v.is_null() && !kind_fits(v, c.kind))
        throw InputError(path, 0, where + c.pointer, "wrong type: " + std::string(v.type_name()));
    }
  }
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
