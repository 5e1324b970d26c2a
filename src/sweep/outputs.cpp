#include "sweep/outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "io/atomic_file.h"
#include "sweep/plot.h"
#include "sweep/report.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void write_text(const std::string& path, const std::string& text) {
  AtomicOutputFile f(path);
  f.stream() << text;
  f.commit();
}

std::string cell(const nlohmann::json& v, const char* format) {
  return v.is_number() ? fmt::format(format, v.get<double>()) : std::string("-");
}

}  // namespace

void add_output_by_extension(SweepOutputs& outputs, const std::string& path) {
  std::string* slot = ends_with(path, ".json")  ? &outputs.json
                      : ends_with(path, ".csv") ? &outputs.csv
                                                : nullptr;
  if (!slot)
    throw std::invalid_argument(
        fmt::format("-o {}: expected a .json (the report) or .csv (the table) file name", path));
  if (!slot->empty())
    throw std::invalid_argument(fmt::format("-o {}: a {} output is already given ({})", path,
                                            slot == &outputs.json ? "JSON" : "CSV", *slot));
  *slot = path;
}

void check_sweep_outputs(const SweepOutputs& outputs, const std::vector<std::string>& inputs) {
  std::vector<std::pair<std::string, std::string>> files;  // option, path
  if (!outputs.json.empty()) files.emplace_back("-o", outputs.json);
  if (!outputs.csv.empty()) files.emplace_back("--csv", outputs.csv);
  if (!outputs.plot_dir.empty()) {
    std::error_code ec;
    if (fs::exists(outputs.plot_dir, ec) && !fs::is_directory(outputs.plot_dir, ec))
      throw OutputError(fmt::format("--plot {}: exists and is not a folder", outputs.plot_dir));
    for (const char* name : {"error_vs_area", "error_vs_throughput"})
      for (const char* ext : {".svg", ".png"})
        files.emplace_back("--plot",
                           (fs::path(outputs.plot_dir) / (std::string(name) + ext)).string());
  }
  std::vector<fs::path> canonical;
  for (const auto& [option, path] : files) {
    check_output_path(path);
    // The folder must be there (the plots' is made): a sweep must not run for minutes only to
    // find it cannot write its result.
    const fs::path parent = fs::path(path).parent_path();
    std::error_code dir_ec;
    if (option != "--plot" && !parent.empty() && !fs::is_directory(parent, dir_ec))
      throw OutputError(fmt::format("{} {}: no folder {}", option, path, parent.string()));
    std::error_code ec;
    for (const std::string& in : inputs)
      if (fs::equivalent(in, path, ec))
        throw std::invalid_argument(fmt::format("{} {}: is the input {}", option, path, in));
    canonical.push_back(fs::weakly_canonical(fs::absolute(path)));
  }
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = i + 1; j < files.size(); ++j)
      if (canonical[i] == canonical[j])
        throw std::invalid_argument(fmt::format("{} and {} name the same file {}", files[i].first,
                                                files[j].first, files[i].second));
}

void write_sweep_outputs(const nlohmann::json& report, const SweepOutputs& outputs) {
  if (!outputs.json.empty()) write_text(outputs.json, report_json_text(report));
  if (!outputs.csv.empty()) write_text(outputs.csv, report_csv_text(report));
  if (!outputs.plot_dir.empty()) write_sweep_plots(sweep_plots(report), outputs.plot_dir);
}

std::string format_sweep_summary(const nlohmann::json& report) {
  const nlohmann::json& input = report.at("input");
  const nlohmann::json& rows = report.at("results");
  std::string out = fmt::format(
      "{}: {} {}, {} configurations{}; error = {} at {} bits\n",
      input.at("path").get<std::string>(), input.at("rows").get<std::uint64_t>(),
      input.at("kind") == "scene" ? "requests" : "rows", rows.size(),
      report.at("shard").is_object()
          ? fmt::format(" (shard {}/{} of {})", report["shard"]["index"].get<std::size_t>(),
                        report["shard"]["count"].get<std::size_t>(),
                        report.at("configurations").get<std::size_t>())
          : std::string(),
      report.at("error_measure").get<std::string>(), report.at("display_bits").get<int>());
  std::size_t refused = 0;
  for (const nlohmann::json& r : rows) refused += r.at("refused").is_string();
  if (refused > 0)
    out += fmt::format(
        "{} configurations refused by this input (no row ran through them; \"refused\" says why)\n",
        refused);
  for (const Objective& o : kObjectives) {
    out += fmt::format("Pareto front, error vs {} ({}):\n", o.name,
                       o.minimise ? "both minimised" : "error minimised, throughput maximised");
    out += fmt::format("  {:>5} {:>11} {:>10} {:>8} {:>12} {:>4}  {}\n", "index", "error",
                       "area_ge", "res/cyc", "area*lat", "lat", "spec");
    // The front from the cheapest (or fastest) configuration to the most accurate.
    std::vector<const nlohmann::json*> front;
    for (const nlohmann::json& r : rows)
      if (r.at("pareto").at(o.name).get<bool>()) front.push_back(&r);
    std::stable_sort(front.begin(), front.end(),
                     [&](const nlohmann::json* a, const nlohmann::json* b) {
                       const double x = a->at(o.key).get<double>(), y = b->at(o.key).get<double>();
                       return o.minimise ? x < y : x > y;
                     });
    for (const nlohmann::json* r : front) {
      out += fmt::format("  {:>5} {:>11} {:>10} {:>8} {:>12} {:>4}  {}\n",
                         r->at("index").get<std::size_t>(), cell(r->at("error"), "{:.4g}"),
                         cell(r->at("area_ge"), "{:.0f}"), cell(r->at("throughput"), "{:.4f}"),
                         cell(r->at("area_latency"), "{:.0f}"), r->at("latency").get<int>(),
                         r->at("spec").get<std::string>());
    }
  }
  return out;
}

}  // namespace glint
