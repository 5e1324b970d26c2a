#include "sweep/outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "eval/chip_report.h"
#include "eval/evaluate.h"
#include "sweep/measures.h"
#include "sweep/plot.h"
#include "sweep/report.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
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

SweepOutputs sweep_outputs(const std::string& out, const std::string& csv,
                           const std::string& plot) {
  SweepOutputs outputs;
  if (!out.empty()) add_output_by_extension(outputs, out);
  if (!csv.empty()) {
    if (!outputs.csv.empty())
      throw std::invalid_argument(
          fmt::format("--csv {}: -o {} already writes the CSV", csv, outputs.csv));
    outputs.csv = csv;
  }
  outputs.plot_dir = plot;
  return outputs;
}

SweepOutputFiles declare_sweep_outputs(OutputSet& set, const SweepOutputs& outputs) {
  SweepOutputFiles files;
  if (!outputs.json.empty()) files.json = &set.add("-o", outputs.json);
  if (!outputs.csv.empty()) files.csv = &set.add("--csv", outputs.csv);
  if (!outputs.plot_dir.empty()) {
    set.make_folder("--plot", outputs.plot_dir);
    for (const char* name : {"error_vs_area", "error_vs_throughput"})
      for (const char* ext : {".svg", ".png"}) {
        const std::string file = std::string(name) + ext;
        files.plots.emplace_back(file,
                                 &set.add("--plot", (fs::path(outputs.plot_dir) / file).string()));
      }
  }
  return files;
}

void write_sweep_outputs(const nlohmann::json& report, const SweepOutputFiles& files) {
  if (files.json) files.json->stream() << report_json_text(report);
  if (files.csv) files.csv->stream() << report_csv_text(report);
  if (files.plots.empty()) return;
  for (const SweepPlot& plot : sweep_plots(report)) {
    for (const auto& [file, out] : files.plots) {
      if (file == plot.name + ".svg") out->stream() << plot.svg;
      if (file != plot.name + ".png") continue;
      const std::vector<std::uint8_t> png = encode_png(plot.png);
      out->stream().write(reinterpret_cast<const char*>(png.data()),
                          static_cast<std::streamsize>(png.size()));
    }
  }
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
  // The pixel measure its weighted and image errors are in (reference/pixel_error.h).
  // A report that merge accepted may come from elsewhere: only a well-formed one is printed.
  const auto text = [](const nlohmann::json& o, const char* key) {
    const auto it = o.find(key);
    return it != o.end() && it->is_string() ? it->get<std::string>() : std::string("?");
  };
  if (const auto pm = input.find("pixel_measure"); pm != input.end() && pm->is_object())
    out += fmt::format("pixel error: largest channel of light x specular, {} display; eps on {}\n",
                       text(*pm, "display"), text(*pm, "eps_measure"));
  // The chip every configuration is built on (eval/chip_report.h), when well formed.
  if (const auto chip = report.find("chip"); chip != report.end() && chip->is_object()) {
    const auto count = [&](const char* key) {
      const auto it = chip->find(key);
      return it != chip->end() && it->is_number_unsigned();
    };
    if (count("materials") && count("slots") && text(*chip, "spec") != "?" &&
        text(*chip, "tables") != "?" && text(*chip, "sized_to") != "?" && chip->contains("given") &&
        chip->at("given").is_boolean())
      out += chip_line(*chip);
  }
  std::size_t refused = 0;
  for (const nlohmann::json& r : rows) refused += r.at("refused").is_string();
  if (refused > 0)
    out += fmt::format(
        "{} configurations refused by this input (no row ran through them; \"refused\" says why)\n",
        refused);
  // A bound measure's value is an estimate where a slot's bound is (row_bounds_exact): marked "~".
  const std::optional<MeasureRef> measure =
      find_measure(report.at("error_measure").get<std::string>(), input.at("kind") == "scene");
  const bool bound = measure && is_bound_measure(*measure);
  bool estimates = false;
  // With --node every front also states the lane at the node, in its CSV columns' names.
  const bool node = report_has_node(report);
  const auto node_headings = [&] {
    return node ? fmt::format(" {:>10} {:>16} {:>13}", "area_um2", "critical_path_ns",
                              "max_clock_mhz")
                : std::string();
  };
  const auto node_cells = [&](const nlohmann::json& r) {
    if (!node) return std::string();
    const auto at = [&](const char* pointer) {
      const nlohmann::json::json_pointer p(pointer);
      return r.contains(p) ? r.at(p) : nlohmann::json();
    };
    return fmt::format(" {:>10} {:>16} {:>13}", cell(at("/node/area_um2"), "{:.0f}"),
                       cell(at("/node/critical_path_ns"), "{:.3f}"),
                       cell(at("/node/max_clock_mhz"), "{:.1f}"));
  };
  for (const Objective& o : report_objectives(report)) {
    // The energy's front states the energy beside the other measures.
    const bool energy = std::string(o.key) == kEnergyObjective.key;
    out += fmt::format("Pareto front, error vs {} ({}):\n", o.name,
                       o.minimise ? "both minimised" : "error minimised, throughput maximised");
    // Headed by the measures' names (measures.h).
    out += fmt::format("  {:>5} {:>11} {:>10} {:>10} {:>12} {:>7}{}{}  {}\n", "index", "error",
                       "area_ge", "throughput", "area_latency", "latency", node_headings(),
                       energy ? fmt::format(" {:>21}", kEnergyObjective.key) : "", "spec");
    // The front from the cheapest (or fastest) configuration to the most accurate.
    std::vector<const nlohmann::json*> front;
    for (const nlohmann::json& r : rows)
      if (r.at("pareto").at(o.name).get<bool>()) front.push_back(&r);
    std::stable_sort(front.begin(), front.end(),
                     [&](const nlohmann::json* a, const nlohmann::json* b) {
                       const double x = a->at(o.key).get<double>(), y = b->at(o.key).get<double>();
                       return o.minimise ? x < y : x > y;
                     });
    // Configurations tied with the one above in both objectives (a grid over a timing-only key
    // such as buffer can tie by the thousand) are counted on one line, not listed: the report and
    // the CSV flag every one of them.
    for (std::size_t i = 0; i < front.size();) {
      const nlohmann::json& r = *front[i];
      const bool estimate = bound && !r.at("error").is_null() && !row_bounds_exact(r);
      estimates = estimates || estimate;
      out += fmt::format(
          "  {:>5} {:>11} {:>10} {:>10} {:>12} {:>7}{}{}  {}\n", r.at("index").get<std::size_t>(),
          (estimate ? "~" : "") + cell(r.at("error"), "{:.4g}"), cell(r.at("area_ge"), "{:.0f}"),
          cell(r.at("throughput"), "{:.4f}"), cell(r.at("area_latency"), "{:.0f}"),
          r.at("latency").get<int>(), node_cells(r),
          energy ? fmt::format(" {:>21}", cell(r.at(o.key), "{:.2f}")) : "",
          r.at("spec").get<std::string>());
      std::size_t j = i + 1;
      while (j < front.size() && front[j]->at("error") == r.at("error") &&
             front[j]->at(o.key) == r.at(o.key))
        ++j;
      if (j - i > 1)
        out += fmt::format("        and {} more tied with it in error and {} ({}{})\n", j - i - 1,
                           o.name, front[i + 1]->at("spec").get<std::string>(),
                           j - i > 2
                               ? fmt::format(" ... {}", front[j - 1]->at("spec").get<std::string>())
                               : std::string());
      i = j;
    }
  }
  if (estimates) out += kEstimateNote;
  return out;
}

}  // namespace glint
