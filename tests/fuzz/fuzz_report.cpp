// The shard reports `glint merge` reads (sweep/report.h): parse_sweep_report and its checks, then
// what merge does with an accepted report: merge_sweep_reports on it alone (a shard of one; a
// lone shard of several, or an unsharded report, is refused), and of the merged report the JSON
// and CSV texts, the summary and both plots. InputError and std::invalid_argument are refusals
// (exit 2); anything else thrown is a finding, and so is a merge of one shard whose JSON differs
// from the report with its shard cleared, its rows in order and its fronts recomputed.
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzz.h"
#include "io/input_error.h"
#include "sweep/outputs.h"
#include "sweep/plot.h"
#include "sweep/report.h"

namespace glint::fuzz {

int report(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json j;
  try {
    j = parse_sweep_report(text, "fuzz.json");
  } catch (const InputError&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("parse_sweep_report threw something other than InputError: ") + e.what());
  }
  nlohmann::json whole;
  try {
    whole = merge_sweep_reports({{"fuzz.json", j}});
  } catch (const std::invalid_argument&) {
    return 0;  // not a shard, a lone shard of several, rows outside it, an unknown error measure
  } catch (const std::exception& e) {
    fail(std::string("merging an accepted report threw: ") + e.what());
  }
  try {
    nlohmann::json expected = j;
    expected["shard"] = nullptr;
    std::stable_sort(expected["results"].begin(), expected["results"].end(),
                     [](const nlohmann::json& a, const nlohmann::json& b) {
                       return a["index"].get<std::uint64_t>() < b["index"].get<std::uint64_t>();
                     });
    mark_pareto(expected);
    if (report_json_text(whole) != report_json_text(expected))
      fail("a merged shard of one differs from its own report");
    (void)report_csv_text(whole);
    (void)format_sweep_summary(whole);
    (void)sweep_plots(whole);
  } catch (const std::exception& e) {
    fail(std::string("writing a merged report threw: ") + e.what());
  }
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(report)
