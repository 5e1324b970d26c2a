#include "sweep/sweep_html.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "sweep/measures.h"
#include "sweep/plot.h"
#include "sweep/report.h"

namespace glint {
namespace {

std::string text(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) ? json_cell(j.at(key)).text : std::string("-");
}

// An array of strings (grids, budget conditions) joined by `separator`.
std::string listed(const nlohmann::json& j, const char* key, const char* separator) {
  const nlohmann::json v = j.is_object() ? j.value(key, nlohmann::json()) : nlohmann::json();
  if (!v.is_array()) return json_cell(v).text;
  std::string out;
  for (const nlohmann::json& e : v) out += (out.empty() ? "" : separator) + json_cell(e).text;
  return out;
}

// The rows (all, or those `keep` accepts) in the CSV's columns (measures.h): the same names the
// CSV, the JSON and a size budget use.
template <typename Keep>
HtmlTable configurations(const std::string& id, const nlohmann::json& report, Keep keep) {
  HtmlTable t;
  t.id = id;
  const bool scene = report.at("input").at("kind") == "scene";
  const bool node = report_has_node(report);
  std::vector<const SweepColumn*> cols;
  for (const SweepColumn& c : sweep_columns())
    if ((scene || !c.scene_only) && (node || !c.node_only)) cols.push_back(&c);
  t.headings.push_back("error");
  for (const SweepColumn* c : cols) t.headings.push_back(c->name);
  for (const nlohmann::json& row : report.at("results")) {
    if (!keep(row)) continue;
    std::vector<HtmlCell> cells{json_cell(row.value("error", nlohmann::json()))};
    for (const SweepColumn* c : cols) {
      const nlohmann::json::json_pointer ptr(c->pointer);
      cells.push_back(row.contains(ptr) ? json_cell(row.at(ptr)) : HtmlCell{});
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

std::vector<std::pair<std::string, std::string>> sweep_figures(const nlohmann::json& report) {
  const nlohmann::json& input = report.at("input");
  const nlohmann::json pm = input.value("pixel_measure", nlohmann::json::object());
  std::vector<std::pair<std::string, std::string>> kv{
      {"input",
       fmt::format("{} ({}, {} {})", text(input, "path"), text(input, "kind"), text(input, "rows"),
                   input.value("kind", "") == "scene" ? "requests" : "rows")},
      {"configurations", text(report, "configurations")},
      {"grids", listed(report, "grids", "; ")},
      {"error measure",
       fmt::format("{} at {} bits", text(report, "error_measure"), text(report, "display_bits"))},
      {"chip", text(report.value("chip", nlohmann::json()), "spec")},
      {"pixel measure", fmt::format("largest channel of light x specular, {} display; eps on {}",
                                    text(pm, "display"), text(pm, "eps_measure"))}};
  if (report.value("shard", nlohmann::json()).is_object())
    kv.emplace_back("shard", fmt::format("{}/{}", text(report["shard"], "index"),
                                         text(report["shard"], "count")));
  return kv;
}

// The plots and the fronts of one sweep report; the tables' ids start with `id_prefix`.
void fronts(HtmlPage& page, const nlohmann::json& report, const std::string& id_prefix) {
  for (const SweepPlot& plot : sweep_plots(report, false)) page.raw_svg(plot.svg, plot.name);
  for (const Objective& o : report_objectives(report)) {
    HtmlTable t = configurations(
        id_prefix + "front_" + o.name, report,
        [&](const nlohmann::json& r) { return r.at("pareto").value(o.name, false); });
    t.caption =
        fmt::format("Pareto front, error vs {} ({})", o.name,
                    o.minimise ? "both minimised" : "error minimised, throughput maximised");
    page.table(t);
  }
}

std::string objective_of(const nlohmann::json& doc) {
  return doc.contains("objective") && doc["objective"].is_string()
             ? doc["objective"].get<std::string>()
             : std::string("value");
}

// One row per unit family: its cheapest configuration meeting the budget, or how close it came.
// The measures' columns are "MEASURE on INPUT", as the budget names them.
HtmlTable families_table(const std::string& id, const nlohmann::json& doc,
                         const std::vector<std::string>& inputs) {
  HtmlTable t;
  t.id = id;
  t.headings = {"family", "meets", "spec", objective_of(doc), "index"};
  std::vector<std::string> measures;
  for (const nlohmann::json& f : doc.at("families")) {
    const nlohmann::json of = f.value("measures", nlohmann::json::object());
    for (const auto& [m, v] : of.items())
      if (std::find(measures.begin(), measures.end(), m) == measures.end()) measures.push_back(m);
  }
  for (const std::string& m : measures)
    for (const std::string& in : inputs) t.headings.push_back(m + " on " + in);
  t.headings.insert(t.headings.end(), {"closest miss", "missed"});
  for (const nlohmann::json& f : doc.at("families")) {
    const nlohmann::json closest = f.value("closest", nlohmann::json::object());
    const bool meets = f.contains("spec") && f["spec"].is_string();
    const std::string spec = meets ? f["spec"].get<std::string>() : text(closest, "spec");
    std::vector<HtmlCell> row{{spec.substr(0, spec.find(':'))},
                              {meets ? "yes" : "no"},
                              {spec},
                              json_cell(f.value("value", nlohmann::json())),
                              json_cell(f.value("index", nlohmann::json()))};
    for (const std::string& m : measures) {
      const nlohmann::json v =
          f.value("measures", nlohmann::json::object()).value(m, nlohmann::json());
      for (std::size_t k = 0; k < inputs.size(); ++k)
        row.push_back(v.is_array() && k < v.size() ? json_cell(v[k]) : HtmlCell{});
    }
    row.push_back(json_cell(closest.value("miss", nlohmann::json())));
    row.push_back({text(closest, "missed")});
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

std::string sweep_html(const nlohmann::json& report, const HtmlRunInfo& run) {
  HtmlPage page("glint sweep: " + text(report.at("input"), "path"));
  page.figures("figures", sweep_figures(report));
  page.reproduce(run);
  page.heading(2, "Pareto fronts");
  fronts(page, report, "");
  page.heading(2, "Every configuration");
  HtmlTable all =
      configurations("configurations", report, [](const nlohmann::json&) { return true; });
  all.caption = "Every configuration (the CSV's columns; error: the error measure)";
  page.table(all);
  return page.finish();
}

std::string size_html(const nlohmann::json& document, const std::vector<nlohmann::json>& reports,
                      const HtmlRunInfo& run) {
  const nlohmann::json& best = document.at("best");
  std::string inputs, measures;
  for (const nlohmann::json& in : document.at("inputs")) {
    inputs += (inputs.empty() ? "" : ", ") + text(in, "path");
    const nlohmann::json pm = in.value("pixel_measure", nlohmann::json::object());
    measures += fmt::format("{}{} display, eps on {} ({})", measures.empty() ? "" : "; ",
                            text(pm, "display"), text(pm, "eps_measure"), text(in, "path"));
  }
  HtmlPage page("glint size: " + listed(document, "budget", ","));
  std::vector<std::pair<std::string, std::string>> kv{
      {"budget", listed(document, "budget", ",")},
      {"objective", text(document, "objective")},
      {"inputs", inputs},
      {"chip", text(document, "chip")},
      {"pixel measure", "largest channel of light x specular, " + measures},
      {"configurations", text(document, "configurations")},
      {"meeting the budget", text(document, "meeting")},
      {"choice", best.is_null() ? std::string("none meets the budget") : text(best, "spec")}};
  if (document.contains("loadable"))
    kv.emplace_back("choice on chip ram", document["loadable"]["best"].is_null()
                                              ? std::string("none meets the budget")
                                              : text(document["loadable"]["best"], "spec"));
  page.figures("figures", kv);
  page.reproduce(run);
  std::vector<std::string> input_paths;
  for (const nlohmann::json& in : document.at("inputs")) input_paths.push_back(text(in, "path"));
  const auto choices = [&](const nlohmann::json& doc, const std::string& chip) {
    HtmlTable families = families_table("families" + chip, doc, input_paths);
    families.caption = "The cheapest per unit family (chip " + text(doc, "chip") + ")";
    page.table(families);
    HtmlTable top = json_table("top" + chip, doc.at("top"), 1);
    top.caption = "The cheapest meeting the budget (chip " + text(doc, "chip") + ")";
    page.table(top);
  };
  page.heading(2, "Choice");
  choices(document, "");
  if (document.contains("loadable")) choices(document["loadable"], "_ram");
  for (std::size_t k = 0; k < reports.size(); ++k) {
    page.heading(2, "Pareto fronts on " + text(reports[k].at("input"), "path"));
    fronts(page, reports[k], fmt::format("input{}_", k));
  }
  return page.finish();
}

}  // namespace glint
