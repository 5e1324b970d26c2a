// glint regress's inputs: the goldens found beside the traces and in golden/scenes/, each read and
// checked, and the child `glint sim` or `glint render` that re-runs one (cmd_regress.cpp compares).
#include "cli/regress_inputs.h"

#include <fmt/format.h>
#include <stdlib.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "io/input_error.h"

namespace glint::cli {
namespace {

namespace fs = std::filesystem;

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
  if (!g.chip.empty()) cmd += " --chip " + shell_quote(g.chip);
  return cmd;
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

}  // namespace

nlohmann::json run_sim(const std::string& trace, const Golden& setup) {
  std::string cmd = self_and_units("sim", trace, setup);
  cmd += fmt::format(" --sink-ready {:.17g}", setup.sink_ready);
  // An always-ready sink has no pattern to seed (sim refuses --seed then; the golden records 1).
  if (setup.sink_ready < 1) cmd += fmt::format(" --seed {}", setup.seed);
  return run_json(cmd, trace, "sim");
}

nlohmann::json run_render(const std::string& scene, const Golden& setup) {
  const TempFolder images;
  const std::string cmd = self_and_units("render", scene, setup) + " -o " +
                          shell_quote((images.path() / "render").string());
  return run_json(cmd, scene, "render");
}

// --update --unit replaces the lanes; the budgets must still name lanes that exist.
void check_budget_lanes(const RegressCheck& c) {
  for (const auto& [spec, text] : c.golden.budgets)
    if (std::find(c.golden.units.begin(), c.golden.units.end(), spec) == c.golden.units.end())
      throw InputError(c.golden_path.string(), 0, "budgets." + spec,
                       "--update --unit leaves no lane with this spec: give it with --unit, or "
                       "edit the golden's budgets first");
}

std::vector<RegressCheck> trace_checks(const RegressOptions& o, const fs::path& dir,
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
  std::vector<RegressCheck> out;
  for (const auto& trace : traces) {
    RegressCheck c;
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
std::vector<RegressCheck> scene_checks(const RegressOptions& o, const fs::path& dir,
                                       const fs::path& golden_dir) {
  std::vector<RegressCheck> out;
  const fs::path scene_goldens = golden_dir / "scenes";
  if (!fs::is_directory(scene_goldens)) return out;
  std::vector<fs::path> paths;
  for (const auto& e : fs::directory_iterator(scene_goldens))
    if (e.path().extension() == ".json" && e.is_regular_file()) paths.push_back(e.path());
  std::sort(paths.begin(), paths.end());
  for (const auto& path : paths) {
    RegressCheck c;
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

}  // namespace glint::cli
