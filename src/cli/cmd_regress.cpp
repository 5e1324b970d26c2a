// glint regress: re-runs `glint sim` on the shipped traces and compares with traces/golden/.
//
// Each golden (traces/golden/NAME.json) records the trace, the unit specs and the sink settings it
// was made with, and the report. Every run happens in a child `glint sim` process: SystemC allows
// one elaboration per process, and the child is exactly what a user runs.
//
// --update keeps each golden's recorded specs unless --unit gives new ones; it writes the goldens
// only after every child has succeeded, so a failing trace leaves all of them as they were.
#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "cli/cli.h"
#include "eval/golden.h"
#include "eval/sim_report.h"
#include "io/input_error.h"
#include "io/output_set.h"

namespace glint::cli {
namespace {

namespace fs = std::filesystem;

struct RegressOptions {
  std::string traces = "traces";
  std::vector<std::string> units;  // with --update: the specs every updated golden records
  bool update = false;
  double tolerance = 1e-9;
  bool json = false;
};

// The goldens made by --update for a trace that has none: every unit, the iterative divider,
// a full-domain Öztürk fit, and a starved merge buffer under sink backpressure.
const std::vector<std::string>& default_specs() {
  static const std::vector<std::string> specs = {
      "pow",
      "schlick",
      "schlick:divider=iterative",
      "hast",
      "horner",
      "horner:degree=6,method=ls,domain=full,constrain=off",
      "lut",
      "lut:bits=4,buffer=2"};
  return specs;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

nlohmann::json run_child(const std::string& trace, const Golden& setup) {
  std::string cmd = shell_quote(fs::read_symlink("/proc/self/exe").string()) + " sim " +
                    shell_quote(trace) + " --json";
  for (const auto& u : setup.units) cmd += " --unit " + shell_quote(u);
  cmd += fmt::format(" --sink-ready {:.17g}", setup.sink_ready);
  // An always-ready sink has no pattern to seed (sim refuses --seed then; the golden records 1).
  if (setup.sink_ready < 1) cmd += fmt::format(" --seed {}", setup.seed);
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("cannot run " + cmd);
  std::string out;
  char buf[65536];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const bool read_error = std::ferror(p) != 0;
  const int st = pclose(p);
  if (st != 0)
    throw std::invalid_argument(fmt::format("{}: `glint sim` failed (status {})", trace, st));
  // The child checks its standard output (exit 2 on a failed write), so a report that does not
  // parse here is lost on the way: glint's own failure.
  try {
    if (read_error) throw std::runtime_error("read error on its pipe");
    return nlohmann::json::parse(out);
  } catch (const std::exception& e) {
    throw std::runtime_error(
        fmt::format("{}: the report of `glint sim --json` is incomplete: {}", trace, e.what()));
  }
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
  std::vector<fs::path> traces;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".vec") traces.push_back(e.path());
  std::sort(traces.begin(), traces.end());
  // Nothing checked must not read as "nothing failed".
  if (traces.empty())
    throw std::invalid_argument(fmt::format("--traces {}: no *.vec trace in it", o.traces));
  // Nor may a golden go unchecked because its trace is gone.
  if (fs::is_directory(golden_dir)) {
    for (const auto& e : fs::directory_iterator(golden_dir)) {
      if (e.path().extension() != ".json" || !e.is_regular_file()) continue;
      if (!fs::exists(dir / (e.path().stem().string() + ".vec")))
        throw InputError(e.path().string(), 0, "trace",
                         fmt::format("no trace {}.vec in {} for this golden",
                                     e.path().stem().string(), o.traces));
    }
  }
  int failed = 0, checked = 0;
  nlohmann::json summary = nlohmann::json::array();
  std::vector<std::pair<fs::path, nlohmann::json>> updates;  // written once every run succeeded
  for (const auto& trace : traces) {
    const fs::path golden_path = golden_dir / (trace.stem().string() + ".json");
    Golden golden;
    if (fs::exists(golden_path)) {
      golden =
          read_golden(golden_path.string(), o.update ? GoldenUse::kUpdate : GoldenUse::kCompare);
      if (golden.trace != trace.filename().string())
        throw InputError(golden_path.string(), 0, "trace",
                         fmt::format("{}, but the golden's file is named for {}",
                                     quote_input(golden.trace), trace.filename().string()));
    } else if (o.update) {
      golden.trace = trace.filename().string();
      golden.units = o.units.empty() ? default_specs() : o.units;
      golden.sink_ready = trace.stem() == "pixels" ? 0.7 : 1.0;
      golden.seed =
          golden.sink_ready < 1 ? 7 : 1;  // 1: sim's default, all an always-ready sink has
    } else {
      std::cerr << fmt::format("{}: no golden ({}); run `glint regress --update`\n", trace.string(),
                               golden_path.string());
      ++failed;
      continue;
    }
    if (o.update && !o.units.empty()) golden.units = o.units;
    const nlohmann::json fresh = run_child(trace.string(), golden);
    ++checked;
    if (o.update) {
      golden.report = fresh;
      updates.emplace_back(golden_path, golden.to_json());
      summary.push_back({{"trace", trace.filename().string()}, {"updated", true}});
      continue;
    }
    // A golden that lacks a field, has one this build does not write, or a value of another type
    // is refused (exit 2) before its values are compared: it cannot pass by saying less.
    check_report_shape(golden.report, fresh, golden_path.string());
    const auto diffs = diff_sim_reports(golden.report, fresh, o.tolerance);
    summary.push_back({{"trace", trace.filename().string()}, {"differences", diffs}});
    if (diffs.empty()) {
      if (!o.json) std::cout << fmt::format("ok    {}\n", trace.filename().string());
    } else {
      ++failed;
      if (!o.json) {
        std::cout << fmt::format("FAIL  {} ({} differences)\n", trace.filename().string(),
                                 diffs.size());
        for (const auto& d : diffs) std::cout << "      " << d << '\n';
      }
    }
  }
  // Every golden is written to its temporary file, then all are committed together (output_set.h):
  // all are updated or none.
  OutputSet goldens;
  if (!updates.empty()) goldens.make_folder("--update", golden_dir.string());
  for (const auto& [path, golden] : updates)
    goldens.add("--update", path.string()).stream() << golden.dump(2) << '\n';
  goldens.commit();
  for (const auto& update : updates)
    std::cerr << fmt::format("updated {}\n", update.first.string());
  if (o.json) {
    print_json({{"checked", checked}, {"failed", failed}, {"traces", summary}});
  } else {
    std::cout << fmt::format("{} traces checked, {} failed\n", checked, failed);
  }
  return failed ? 1 : kExitOk;
}

}  // namespace

void add_regress_command(CLI::App& app, int& status) {
  auto o = std::make_shared<RegressOptions>();
  CLI::App* sub = app.add_subcommand(
      "regress", "Accuracy regression: re-run the shipped traces against traces/golden/");
  sub->add_option("--traces", o->traces, "Folder of *.vec traces with golden/ inside")
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
