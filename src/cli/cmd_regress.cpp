// glint regress: re-runs `glint sim` on the shipped traces and `glint render` on the scenes that
// have goldens, and compares with traces/golden/ (and traces/golden/scenes/).
//
// Each golden records its input, the unit specs and the settings it was made with (sink, slots),
// and the report, budgets (conditions per lane, in size's grammar), or both. Every run happens in
// a child process: SystemC allows one elaboration per process, and the child is exactly what a
// user runs. A failure says first what changed in the hardware, then the figures that moved most,
// then every difference (eval/golden_diff.h).
//
// Every golden is read and checked, budgets included, before the first child runs. --update keeps
// each golden's recorded specs unless --unit gives new ones; it writes the goldens only after
// every child has succeeded and every budget held, so a failing input leaves all of them as they
// were.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "cli/cli.h"
#include "cli/regress_inputs.h"
#include "eval/golden.h"
#include "eval/golden_diff.h"
#include "eval/sim_report.h"
#include "io/input_error.h"
#include "io/output_set.h"
#include "sweep/golden_budgets.h"

namespace glint::cli {
namespace {

namespace fs = std::filesystem;

// What one check found, in the order a colleague reads it.
struct Finding {
  std::vector<std::string> hardware, budgets, largest, differences;
  bool failed() const { return !budgets.empty() || !differences.empty(); }
};

Finding compare(const RegressCheck& c, const nlohmann::json& fresh, double tolerance) {
  Finding f;
  f.budgets = broken_budgets(c.golden, c.budgets, fresh);
  if (c.golden.budgets_only) return f;
  const GoldenKind kind = c.golden.kind;
  // A golden that lacks a field, has one this build does not write, or a value of another type
  // is refused (exit 2) before its values are compared: it cannot pass by saying less.
  check_report_shape(c.golden.report, fresh, c.golden_path.string());
  f.differences = kind == GoldenKind::kTrace
                      ? diff_sim_reports(c.golden.report, fresh, tolerance)
                      : diff_render_reports(c.golden.report, fresh, tolerance);
  if (f.differences.empty()) return f;
  f.hardware = hardware_changes(kind, c.golden.report, fresh);
  f.largest = largest_changes(kind, c.golden.report, fresh, tolerance);
  return f;
}

void print_finding(const RegressCheck& c, const Finding& f) {
  if (!f.failed()) {
    std::cout << fmt::format("ok    {}\n", c.name);
    return;
  }
  std::string counts;
  if (!f.differences.empty())
    counts =
        fmt::format("{} difference{}", f.differences.size(), f.differences.size() == 1 ? "" : "s");
  if (!f.budgets.empty())
    counts += fmt::format("{}{} budget condition{} not met", counts.empty() ? "" : ", ",
                          f.budgets.size(), f.budgets.size() == 1 ? "" : "s");
  std::cout << fmt::format("FAIL  {} ({})\n", c.name, counts);
  const auto section = [](const char* title, const std::vector<std::string>& lines) {
    if (lines.empty()) return;
    std::cout << "      " << title << '\n';
    for (const auto& l : lines) std::cout << "        " << l << '\n';
  };
  section("what changed in the hardware:", f.hardware);
  section("budgets not met:", f.budgets);
  section("largest differences:", f.largest);
  section("every difference:", f.differences);
}

int run_regress(const RegressOptions& o) {
  const fs::path dir(o.traces), golden_dir = fs::path(o.traces) / "golden";
  // A NaN or negative tolerance would pass every difference (every comparison with NaN is false).
  if (!(std::isfinite(o.tolerance) && o.tolerance >= 0))
    throw std::invalid_argument(
        fmt::format("--tolerance {}: expected a finite number >= 0", o.tolerance));
  // A bad spec is a usage error here, with the spec named, not a failing child per trace.
  if (!o.units.empty()) parse_unit_options(o.units);
  if (options_only()) return kExitOk;
  if (!fs::is_directory(dir))
    throw std::invalid_argument(fmt::format("--traces {}: not a directory", o.traces));
  std::vector<RegressCheck> checks = trace_checks(o, dir, golden_dir);
  const std::size_t trace_count = checks.size();
  for (RegressCheck& c : scene_checks(o, dir, golden_dir)) checks.push_back(std::move(c));
  // Nothing checked must not read as "nothing failed".
  if (checks.empty())
    throw std::invalid_argument(fmt::format(
        "--traces {}: no *.vec trace in it, and no scene golden in golden/scenes/", o.traces));
  // Every golden and its budgets are checked before the first child runs.
  for (RegressCheck& c : checks) {
    // A golden of budgets only is a contract --update leaves as it is, lanes included.
    if (o.update && !o.units.empty() && !c.golden.budgets_only) {
      c.golden.units = o.units;
      check_budget_lanes(c);
    }
    c.budgets = parse_golden_budgets(c.golden, c.golden_path.string());
  }
  int failed = 0, checked = 0, scenes_checked = 0;
  nlohmann::json traces_summary = nlohmann::json::array(), scenes_summary = traces_summary;
  std::vector<std::pair<fs::path, nlohmann::json>> updates;  // written once every run succeeded
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const RegressCheck& c = checks[i];
    const bool trace = i < trace_count;
    nlohmann::json& summary = trace ? traces_summary : scenes_summary;
    if (c.make && !o.update) {
      std::cerr << fmt::format("{}: no golden ({}); run `glint regress --update`\n",
                               c.input.string(), c.golden_path.string());
      ++failed;
      continue;
    }
    const nlohmann::json fresh =
        trace ? run_sim(c.input.string(), c.golden) : run_render(c.input.string(), c.golden);
    ++checked;
    if (!trace) ++scenes_checked;
    const nlohmann::json key = {{trace ? "trace" : "scene", c.name}};
    if (o.update) {
      // The budgets are the designer's: figures that break them are not recorded.
      const auto broken = broken_budgets(c.golden, c.budgets, fresh);
      nlohmann::json entry = key;
      entry["budgets"] = broken;
      if (!broken.empty()) {
        ++failed;
        if (!o.json) print_finding(c, Finding{{}, broken, {}, {}});
      } else if (!c.golden.budgets_only) {
        Golden g = c.golden;
        g.report = fresh;
        updates.emplace_back(c.golden_path, g.to_json());
        entry["updated"] = true;
      }
      summary.push_back(entry);
      continue;
    }
    const Finding f = compare(c, fresh, o.tolerance);
    nlohmann::json entry = key;
    entry["hardware"] = f.hardware;
    entry["budgets"] = f.budgets;
    entry["largest"] = f.largest;
    entry["differences"] = f.differences;
    summary.push_back(entry);
    if (f.failed()) ++failed;
    if (!o.json) print_finding(c, f);
  }
  // Every golden is written to its temporary file, then all are committed together (output_set.h):
  // all are updated or none, and none when a budget broke.
  OutputSet goldens;
  if (failed > 0) updates.clear();
  for (const auto& [path, golden] : updates) {
    goldens.make_folder("--update", path.parent_path().string());
    goldens.add("--update", path.string()).stream() << golden.dump(2) << '\n';
  }
  goldens.commit();
  for (const auto& update : updates)
    std::cerr << fmt::format("updated {}\n", update.first.string());
  if (o.json) {
    print_json({{"checked", checked},
                {"failed", failed},
                {"traces", traces_summary},
                {"scenes", scenes_summary}});
  } else if (checks.size() == trace_count) {
    std::cout << fmt::format("{} traces checked, {} failed\n", checked, failed);
  } else {
    const int traces_checked = checked - scenes_checked;
    std::cout << fmt::format("{} trace{} and {} scene{} checked, {} failed\n", traces_checked,
                             traces_checked == 1 ? "" : "s", scenes_checked,
                             scenes_checked == 1 ? "" : "s", failed);
  }
  if (o.update && failed > 0)
    std::cerr << "no golden updated: a budget is not met (the figures break the contract the "
                 "golden states)\n";
  return failed ? 1 : kExitOk;
}

}  // namespace

void add_regress_command(CLI::App& app, int& status) {
  auto o = std::make_shared<RegressOptions>();
  CLI::App* sub = app.add_subcommand(
      "regress",
      "Accuracy regression: re-run the shipped traces and scenes against traces/golden/");
  sub->add_option("--traces", o->traces,
                  "Folder of *.vec traces and scenes/, with their goldens in golden/ and "
                  "golden/scenes/")
      ->capture_default_str();
  CLI::Option* update =
      sub->add_flag("--update", o->update, "Rewrite the goldens from this build (deliberately)");
  sub->add_option("--unit", o->units,
                  "With --update: unit SPEC the goldens record (repeatable; default: each "
                  "golden's own specs, the default set for a new golden)")
      ->needs(update);
  sub->add_option("--tolerance", o->tolerance,
                  "Relative tolerance of float statistics (a finite number >= 0)")
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print one JSON document on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_regress(*o); }); });
}

}  // namespace glint::cli
