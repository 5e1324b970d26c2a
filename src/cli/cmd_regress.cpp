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
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "cli/cli.h"
#include "eval/golden.h"
#include "eval/golden_diff.h"
#include "eval/sim_report.h"
#include "io/input_error.h"
#include "io/output_set.h"
#include "sweep/golden_budgets.h"

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

// Runs `cmd` and parses the JSON report it prints; `what` names the run in messages.
nlohmann::json run_json(const std::string& cmd, const std::string& input, const char* what) {
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("cannot run " + cmd);
  std::string out;
  char buf[65536];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const bool read_error = std::ferror(p) != 0;
  const int st = pclose(p);
  if (st != 0)
    throw std::invalid_argument(fmt::format("{}: `glint {}` failed (status {})", input, what, st));
  // The child checks its standard output (exit 2 on a failed write), so a report that does not
  // parse here is lost on the way: glint's own failure.
  try {
    if (read_error) throw std::runtime_error("read error on its pipe");
    return nlohmann::json::parse(out);
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: the report of `glint {} --json` is incomplete: {}",
                                         input, what, e.what()));
  }
}

std::string self_and_units(const char* command, const std::string& input, const Golden& g) {
  std::string cmd = shell_quote(fs::read_symlink("/proc/self/exe").string()) + " " + command + " " +
                    shell_quote(input) + " --json";
  for (const auto& u : g.units) cmd += " --unit " + shell_quote(u);
  if (g.slots > 0) cmd += fmt::format(" --slots {}", g.slots);
  return cmd;
}

nlohmann::json run_sim(const std::string& trace, const Golden& setup) {
  std::string cmd = self_and_units("sim", trace, setup);
  cmd += fmt::format(" --sink-ready {:.17g}", setup.sink_ready);
  // An always-ready sink has no pattern to seed (sim refuses --seed then; the golden records 1).
  if (setup.sink_ready < 1) cmd += fmt::format(" --seed {}", setup.seed);
  return run_json(cmd, trace, "sim");
}

// A render writes its images too: into a folder of its own, removed whatever happens.
class TempFolder {
 public:
  TempFolder() {
    std::string pattern = (fs::temp_directory_path() / "glint-regress-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
      throw std::runtime_error("cannot make a temporary folder in " +
                               fs::temp_directory_path().string());
    path_ = pattern;
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

nlohmann::json run_render(const std::string& scene, const Golden& setup) {
  const TempFolder images;
  const std::string cmd = self_and_units("render", scene, setup) + " -o " +
                          shell_quote((images.path() / "render").string());
  return run_json(cmd, scene, "render");
}

// One golden to check: where its input and it are, and how the output names it.
struct Check {
  fs::path input;
  fs::path golden_path;
  std::string name;  // "phong_basic.vec", "scenes/small.json"
  Golden golden;
  std::vector<LaneBudget> budgets;
  bool make = false;  // --update: a trace without a golden, whose golden is made
};

// --update --unit replaces the lanes; the budgets must still name lanes that exist.
void check_budget_lanes(const Check& c) {
  for (const auto& [spec, text] : c.golden.budgets)
    if (std::find(c.golden.units.begin(), c.golden.units.end(), spec) == c.golden.units.end())
      throw InputError(c.golden_path.string(), 0, "budgets." + spec,
                       "--update --unit leaves no lane with this spec: give it with --unit, or "
                       "edit the golden's budgets first");
}

std::vector<Check> trace_checks(const RegressOptions& o, const fs::path& dir,
                                const fs::path& golden_dir) {
  std::vector<fs::path> traces;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".vec") traces.push_back(e.path());
  std::sort(traces.begin(), traces.end());
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
  std::vector<Check> out;
  for (const auto& trace : traces) {
    Check c;
    c.input = trace;
    c.name = trace.filename().string();
    c.golden_path = golden_dir / (trace.stem().string() + ".json");
    if (fs::exists(c.golden_path)) {
      c.golden =
          read_golden(c.golden_path.string(), o.update ? GoldenUse::kUpdate : GoldenUse::kCompare);
      if (c.golden.kind != GoldenKind::kTrace)
        throw InputError(c.golden_path.string(), 0, "scene",
                         "a scene's golden belongs in golden/scenes/, not beside the traces");
      if (c.golden.trace != c.name)
        throw InputError(c.golden_path.string(), 0, "trace",
                         fmt::format("{}, but the golden's file is named for {}",
                                     quote_input(c.golden.trace), c.name));
    } else if (o.update) {
      c.make = true;
      c.golden.trace = c.name;
      c.golden.units = o.units.empty() ? default_specs() : o.units;
      c.golden.sink_ready = trace.stem() == "pixels" ? 0.7 : 1.0;
      c.golden.seed =
          c.golden.sink_ready < 1 ? 7 : 1;  // 1: sim's default, all an always-ready sink has
    } else {
      c.make = true;  // no golden: reported as a failure
    }
    out.push_back(std::move(c));
  }
  return out;
}

// Scenes are checked where they have a golden (golden/scenes/NAME.json names its scene in
// scenes/): the shipped scenes are also the manual's examples, some too large for every run.
std::vector<Check> scene_checks(const RegressOptions& o, const fs::path& dir,
                                const fs::path& golden_dir) {
  std::vector<Check> out;
  const fs::path scene_goldens = golden_dir / "scenes";
  if (!fs::is_directory(scene_goldens)) return out;
  std::vector<fs::path> paths;
  for (const auto& e : fs::directory_iterator(scene_goldens))
    if (e.path().extension() == ".json" && e.is_regular_file()) paths.push_back(e.path());
  std::sort(paths.begin(), paths.end());
  for (const auto& path : paths) {
    Check c;
    c.golden_path = path;
    c.name = "scenes/" + path.filename().string();
    c.golden = read_golden(path.string(), o.update ? GoldenUse::kUpdate : GoldenUse::kCompare);
    if (c.golden.kind != GoldenKind::kScene)
      throw InputError(path.string(), 0, "trace",
                       "a trace's golden belongs in golden/, named for its trace; a scene's names "
                       "its scene with \"scene\"");
    c.input = dir / "scenes" / c.golden.scene;
    if (!fs::is_regular_file(c.input))
      throw InputError(
          path.string(), 0, "scene",
          fmt::format("no scene {} in {}", quote_input(c.golden.scene), (dir / "scenes").string()));
    out.push_back(std::move(c));
  }
  return out;
}

// What one check found, in the order a colleague reads it.
struct Finding {
  std::vector<std::string> hardware, budgets, largest, differences;
  bool failed() const { return !budgets.empty() || !differences.empty(); }
};

Finding compare(const Check& c, const nlohmann::json& fresh, double tolerance) {
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

void print_finding(const Check& c, const Finding& f) {
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
  std::vector<Check> checks = trace_checks(o, dir, golden_dir);
  const std::size_t trace_count = checks.size();
  for (Check& c : scene_checks(o, dir, golden_dir)) checks.push_back(std::move(c));
  // Nothing checked must not read as "nothing failed".
  if (checks.empty())
    throw std::invalid_argument(fmt::format(
        "--traces {}: no *.vec trace in it, and no scene golden in golden/scenes/", o.traces));
  // Every golden and its budgets are checked before the first child runs.
  for (Check& c : checks) {
    if (o.update && !o.units.empty()) {
      c.golden.units = o.units;
      check_budget_lanes(c);
    }
    c.budgets = parse_golden_budgets(c.golden, c.golden_path.string());
  }
  int failed = 0, checked = 0, scenes_checked = 0;
  nlohmann::json traces_summary = nlohmann::json::array(), scenes_summary = traces_summary;
  std::vector<std::pair<fs::path, nlohmann::json>> updates;  // written once every run succeeded
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const Check& c = checks[i];
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
