#include "render/render_html.h"

#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "io/output_set.h"

namespace glint {
namespace {

// A leaf of the report by a path of keys, or null when the report lacks it (a page of an older or
// newer report still opens).
const nlohmann::json& at_path(const nlohmann::json& j, std::initializer_list<const char*> path) {
  static const nlohmann::json kNull;
  const nlohmann::json* v = &j;
  for (const char* key : path) {
    if (!v->is_object() || !v->contains(key)) return kNull;
    v = &(*v)[key];
  }
  return *v;
}

std::string text(const nlohmann::json& v) {
  return json_cell(v).text;
}

std::string percent(const nlohmann::json& v) {
  return v.is_number() ? fmt::format("{:.1f} %", 100 * v.get<double>()) : "-";
}

std::string joined(const nlohmann::json& array) {
  std::string out;
  if (!array.is_array()) return text(array);
  for (const nlohmann::json& v : array) out += (out.empty() ? "" : ", ") + text(v);
  return out;
}

std::vector<std::pair<std::string, std::string>> key_figures(const nlohmann::json& r,
                                                             const HtmlRunInfo& run) {
  const nlohmann::json& res = at_path(r, {"resolution"});
  const nlohmann::json& total = at_path(r, {"skip", "total"});
  std::vector<std::pair<std::string, std::string>> kv{
      {"scene", text(at_path(r, {"scene"}))},
      {"resolution", res.is_array() && res.size() == 2
                         ? fmt::format("{} x {}", text(res[0]), text(res[1]))
                         : text(res)},
      {"lights", fmt::format("{}: {}", at_path(r, {"lights"}).size(),
                             joined(r.value("lights", nlohmann::json())))},
      {"materials", joined(at_path(r, {"materials"}))},
      {"requests", text(at_path(r, {"requests"}))},
      {"lobes (t)", joined(at_path(r, {"lobes"})) + " (" + joined(at_path(r, {"t_inputs"})) + ")"}};
  kv.insert(kv.end(), run.figures.begin(), run.figures.end());
  kv.emplace_back("chip", text(at_path(r, {"chip", "spec"})) + " (tables " +
                              text(at_path(r, {"chip", "tables"})) + ")");
  kv.emplace_back("pixel measure",
                  fmt::format("largest channel's 8-bit code difference, {} display; eps on {}",
                              text(at_path(r, {"display"})), text(at_path(r, {"eps_measure"}))));
  kv.emplace_back(
      "skipped (of light x pixel pairs)",
      fmt::format("{} with tau, {} with t <= 0", percent(at_path(total, {"skipped_fraction_tau"})),
                  percent(at_path(total, {"skipped_fraction_t_le_0"}))));
  kv.emplace_back("skip alone", fmt::format("max {} LSB; bound from eps {} LSB, holds: {}",
                                            text(at_path(r, {"skip_only_image_error", "max_lsb"})),
                                            text(at_path(r, {"skip_guarantee", "bound_lsb"})),
                                            text(at_path(r, {"skip_guarantee", "holds"}))));
  return kv;
}

// The table `glint render` prints, a row per unit, in the report's names.
HtmlTable unit_summary(const nlohmann::json& units) {
  HtmlTable t;
  t.id = "units";
  t.caption = "Units against the reference (pixel error in 8-bit LSBs of the display)";
  struct Column {
    const char* heading;
    std::initializer_list<const char*> path;
    bool percent = false;  // a fraction shown as a percentage (the sort key stays the fraction)
  };
  static const Column kColumns[] = {
      {"unit", {"unit"}},
      {"max_lsb", {"image_error", "max_lsb"}},
      {"mean_lsb", {"image_error", "mean_lsb"}},
      {"psnr_db", {"image_error", "psnr_db"}},
      {"differing_fraction", {"image_error", "differing_fraction"}},
      {"highlight_ratio", {"image_error", "highlight_ratio"}},
      {"core_ratio", {"image_error", "core_ratio"}},
      // The one denominator of every skip figure (the text's skip%LxP, the figures above).
      {"skipped % (light x pixel pairs)", {"skipped_fraction"}, true},
      {"area_ge", {"area_ge"}},
      {"critical_path", {"critical_path"}},
      {"spec", {"spec"}},
  };
  for (const Column& c : kColumns) t.headings.push_back(c.heading);
  for (const nlohmann::json& u : units) {
    std::vector<HtmlCell> row;
    for (const Column& c : kColumns) {
      HtmlCell cell = json_cell(at_path(u, c.path));
      if (c.percent && cell.numeric) cell.text = percent(at_path(u, c.path));
      row.push_back(std::move(cell));
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

std::string render_html(const nlohmann::json& report,
                        const std::vector<std::pair<std::string, std::string>>& pngs,
                        const HtmlRunInfo& run) {
  HtmlPage page("glint render: " + text(at_path(report, {"scene"})));
  page.figures("figures", key_figures(report, run));
  page.reproduce(run);
  const nlohmann::json& units = at_path(report, {"units"});
  if (units.is_array()) page.table(unit_summary(units));
  page.heading(2, "Images");
  page.gallery(pngs);
  page.heading(2, "Tables of the report");
  HtmlTable skips = json_table("skips", at_path(report, {"skip", "per_light_material"}));
  skips.caption = "Skips per light and material (light x pixel pairs)";
  page.table(skips);
  HtmlTable slots = json_table("slots", at_path(report, {"slots"}));
  slots.caption = "Comparator slots";
  page.table(slots);
  // Every unit field but the description (elaboration and tables, in the JSON below).
  nlohmann::json unit_fields = nlohmann::json::array();
  if (units.is_array())
    for (nlohmann::json u : units) {
      u.erase("description");
      unit_fields.push_back(std::move(u));
    }
  HtmlTable all = json_table("unit_fields", unit_fields, 2);
  all.caption = "Every unit's figures (report.json units[], description left out)";
  page.table(all);
  page.open_details("report.json");
  page.pre(report.dump(2));
  page.close_details();
  return page.finish();
}

void write_render_html(const nlohmann::json& report, const RenderOutputs& files, OutputFile& page,
                       const HtmlRunInfo& run) {
  std::vector<std::pair<std::string, std::string>> pngs;
  for (const auto& [name, file] : files.files) {
    if (name.size() < 4 || name.compare(name.size() - 4, 4, ".png") != 0) continue;
    file->stream().flush();
    std::ifstream in(file->temp_path(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof())
      throw OutputError(
          fmt::format("{}: cannot read back {} for the page", file->option(), file->temp_path()));
    pngs.emplace_back(name, std::move(bytes));
  }
  page.stream() << render_html(report, pngs, run);
}

}  // namespace glint
