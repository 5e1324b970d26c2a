#include "eval/golden.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <utility>

#include "eval/sim_report.h"
#include "io/input_error.h"
#include "io/json_text.h"
#include "timing/timing.h"
#include "units/catalogue.h"
#include "units/slot_plan.h"

namespace glint {

namespace {

// The JSON type a value's schema asks for. Numbers are one type (a golden written with 1.0 where
// this build writes 1 is the same value); kUnsigned and kHex16 narrow it.
enum class Kind { kAny, kObject, kArray, kString, kNumber, kUnsigned, kBoolean, kHex16 };

const char* kind_text(Kind k) {
  switch (k) {
    case Kind::kObject:
      return "an object";
    case Kind::kArray:
      return "an array";
    case Kind::kString:
      return "a string";
    case Kind::kNumber:
      return "a number";
    case Kind::kUnsigned:
      return "an integer >= 0";
    case Kind::kBoolean:
      return "true or false";
    case Kind::kHex16:
      return "a string of 16 hexadecimal digits";
    default:
      return "a value";
  }
}

bool has_kind(const nlohmann::json& v, Kind k) {
  switch (k) {
    case Kind::kObject:
      return v.is_object();
    case Kind::kArray:
      return v.is_array();
    case Kind::kString:
      return v.is_string();
    case Kind::kNumber:
      return v.is_number();
    case Kind::kUnsigned:
      return v.is_number_unsigned();
    case Kind::kBoolean:
      return v.is_boolean();
    case Kind::kHex16: {
      if (!v.is_string()) return false;
      const auto& s = v.get_ref<const std::string&>();
      return s.size() == 16 && std::all_of(s.begin(), s.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
             });
    }
    default:
      return true;
  }
}

struct Field {
  const char* key;
  Kind kind;
  bool optional = false;
};

// The sim report's fixed part (src/eval/sim_report.md, version 5): its top level and each
// unit's keys. tests/eval/test_golden.cpp checks that a report of this build passes.
constexpr Field kReportFields[] = {{"glint_sim_report", Kind::kUnsigned},
                                   {"vectors_file", Kind::kString},
                                   {"rows", Kind::kUnsigned},
                                   {"mode", Kind::kString},
                                   {"sink_ready", Kind::kNumber},
                                   {"seed", Kind::kUnsigned},
                                   {"pixel_measure", Kind::kObject},
                                   {"slots", Kind::kUnsigned},
                                   {"per_light_slots", Kind::kBoolean},
                                   {"datapath_groups", Kind::kUnsigned},
                                   {"chip", Kind::kObject},
                                   {"units", Kind::kArray}};
constexpr Field kUnitFields[] = {
    {"unit", Kind::kString},          {"spec", Kind::kString},
    {"config", Kind::kObject},        {"timing", Kind::kObject},
    {"elaboration", Kind::kObject},   {"vectors", Kind::kUnsigned},
    {"skipped", Kind::kUnsigned},     {"computed", Kind::kUnsigned},
    {"cycles", Kind::kUnsigned},      {"throughput", Kind::kNumber},
    {"latency", Kind::kObject},       {"stall_cycles", Kind::kUnsigned},
    {"stalls", Kind::kObject},        {"sink_wait", Kind::kUnsigned},
    {"operations", Kind::kObject},    {"area", Kind::kObject},
    {"critical_path", Kind::kObject}, {"errors", Kind::kObject},
    {"digest", Kind::kHex16}};
constexpr Field kLatencyFields[] = {
    {"min", Kind::kUnsigned}, {"mean", Kind::kNumber}, {"max", Kind::kUnsigned}};
constexpr Field kStallFields[] = {{"merge_buffer_full", Kind::kUnsigned},
                                  {"unit_busy", Kind::kUnsigned}};
constexpr Field kAreaFields[] = {{"ge", Kind::kNumber}, {"inventory", Kind::kArray}};
constexpr Field kCriticalPathFields[] = {{"delay", Kind::kNumber}, {"stage", Kind::kString}};
// The render report's fixed part (src/render/render_report.md, version 4; float_images is
// optional so version-4 reports written before it still read; it is null without --float).
constexpr Field kRenderReportFields[] = {{"glint_render_report", Kind::kUnsigned},
                                         {"scene", Kind::kString},
                                         {"resolution", Kind::kArray},
                                         {"requests", Kind::kUnsigned},
                                         {"lobes", Kind::kArray},
                                         {"t_inputs", Kind::kArray},
                                         {"lights", Kind::kArray},
                                         {"materials", Kind::kArray},
                                         {"chip", Kind::kObject},
                                         {"meshes", Kind::kArray},
                                         {"slots", Kind::kArray},
                                         {"skip", Kind::kObject},
                                         {"display", Kind::kString},
                                         {"eps_measure", Kind::kString},
                                         {"skip_only_image_error", Kind::kObject},
                                         {"skip_guarantee", Kind::kObject},
                                         {"heat_scale", Kind::kString},
                                         {"reproduces", Kind::kAny},
                                         {"units", Kind::kArray},
                                         {"files", Kind::kArray},
                                         {"float_images", Kind::kAny, true}};
constexpr Field kRenderUnitFields[] = {{"unit", Kind::kString},
                                       {"file", Kind::kString},
                                       {"spec", Kind::kString},
                                       {"image_error", Kind::kObject},
                                       {"heatmap_scale_lsb", Kind::kNumber},
                                       {"requests", Kind::kUnsigned},
                                       {"skipped", Kind::kUnsigned},
                                       {"skipped_beyond_t_le_0", Kind::kUnsigned},
                                       {"skipped_fraction", Kind::kNumber},
                                       {"operations", Kind::kObject},
                                       {"operations_saved", Kind::kObject},
                                       {"area_ge", Kind::kNumber},
                                       {"critical_path", Kind::kNumber},
                                       {"errors", Kind::kObject},
                                       {"description", Kind::kObject}};
// The report is kAny here: an object, or null for a golden of budgets only (checked below).
constexpr Field kGoldenFields[] = {{"trace", Kind::kString},      {"units", Kind::kArray},
                                   {"sink_ready", Kind::kNumber}, {"seed", Kind::kUnsigned},
                                   {"chip", Kind::kString, true}, {"budgets", Kind::kObject, true},
                                   {"report", Kind::kAny}};
constexpr Field kSceneGoldenFields[] = {{"scene", Kind::kString},
                                        {"units", Kind::kArray},
                                        {"chip", Kind::kString, true},
                                        {"budgets", Kind::kObject, true},
                                        {"report", Kind::kAny}};

class Checker {
 public:
  explicit Checker(const std::string& file) : file_(file) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw InputError(file_, 0, path, message);
  }

  // `v` is an object with exactly `fields` (each of its kind); extra keys are errors too.
  template <std::size_t N>
  void object(const nlohmann::json& v, const std::string& path, const Field (&fields)[N]) const {
    if (!v.is_object()) fail(path.empty() ? "json" : path, "must be an object");
    for (const Field& f : fields) {
      const std::string at = join(path, f.key);
      const auto it = v.find(f.key);
      if (it == v.end() && f.optional) continue;
      if (it == v.end()) fail(at, "missing");
      if (!has_kind(*it, f.kind))
        fail(at, fmt::format("must be {}, not {}", kind_text(f.kind), describe(*it)));
    }
    for (auto it = v.begin(); it != v.end(); ++it) {
      const bool known =
          std::any_of(fields, fields + N, [&](const Field& f) { return it.key() == f.key; });
      if (!known)
        fail(join(path, it.key()), fmt::format("unknown field (expected {})", names(fields)));
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  static std::string describe(const nlohmann::json& v) {
    if (v.is_string()) return "the string " + quote_input(v.get_ref<const std::string&>());
    if (v.is_number()) return "the number " + v.dump();
    return v.type_name();
  }
  template <std::size_t N>
  static std::string names(const Field (&fields)[N]) {
    std::string out;
    for (const Field& f : fields) out += (out.empty() ? "" : ", ") + std::string(f.key);
    return out;
  }

  const std::string& file_;
};

void check_report(const Checker& c, const Golden& g, const nlohmann::json& r) {
  c.object(r, "report", kReportFields);
  const auto version = r.at("glint_sim_report").get<std::uint64_t>();
  if (version != static_cast<std::uint64_t>(kSimReportVersion))
    c.fail("report.glint_sim_report",
           fmt::format("schema version {}, this build writes version {}: regenerate the golden "
                       "(glint regress --update)",
                       version, kSimReportVersion));
  if (r.at("vectors_file") != g.trace)
    c.fail("report.vectors_file", fmt::format("{}, but the golden is the trace {}",
                                              r.at("vectors_file").dump(), quote_input(g.trace)));
  const auto& mode = r.at("mode").get_ref<const std::string&>();
  if (mode != "fast" && mode != "clocked") c.fail("report.mode", "must be \"fast\" or \"clocked\"");
  // The report must be the one of the settings recorded: the child runs with these.
  if (r.at("sink_ready").get<double>() != g.sink_ready)
    c.fail("report.sink_ready", "differs from the golden's sink_ready");
  if (r.at("seed").get<std::uint64_t>() != g.seed)
    c.fail("report.seed", "differs from the golden's seed");
  const auto& units = r.at("units");
  if (units.size() != g.units.size())
    c.fail("report.units", fmt::format("{} entries, but the golden records {} unit specs",
                                       units.size(), g.units.size()));
  for (std::size_t i = 0; i < units.size(); ++i) {
    const std::string path = fmt::format("report.units[{}]", i);
    const auto& u = units[i];
    c.object(u, path, kUnitFields);
    c.object(u.at("latency"), path + ".latency", kLatencyFields);
    c.object(u.at("stalls"), path + ".stalls", kStallFields);
    c.object(u.at("area"), path + ".area", kAreaFields);
    c.object(u.at("critical_path"), path + ".critical_path", kCriticalPathFields);
    const auto& ops = u.at("operations");
    for (auto it = ops.begin(); it != ops.end(); ++it)
      if (!it->is_number()) c.fail(path + ".operations." + it.key(), "must be a number");
  }
}

void check_render_report(const Checker& c, const Golden& g, const nlohmann::json& r) {
  c.object(r, "report", kRenderReportFields);
  const auto& units = r.at("units");
  if (units.size() != g.units.size())
    c.fail("report.units", fmt::format("{} entries, but the golden records {} unit specs",
                                       units.size(), g.units.size()));
  for (std::size_t i = 0; i < units.size(); ++i)
    c.object(units[i], fmt::format("report.units[{}]", i), kRenderUnitFields);
}

// Walks golden and fresh side by side, collecting the paths where their shapes differ.
void shape_differences(const nlohmann::json& g, const nlohmann::json& f, const std::string& path,
                       std::vector<std::pair<std::string, std::string>>& out) {
  const auto type_of = [](const nlohmann::json& v) -> std::string {
    return v.is_number() ? "number" : v.type_name();
  };
  // nlohmann writes a NaN as null: a null golden value stands for a number.
  if (g.is_null() && f.is_number()) return;
  if (type_of(g) != type_of(f)) {
    out.emplace_back(
        path, fmt::format("is {}, this build's report has {} there", type_of(g), type_of(f)));
    return;
  }
  if (g.is_object()) {
    for (auto it = f.begin(); it != f.end(); ++it)
      if (!g.contains(it.key()))
        out.emplace_back(Checker::join(path, it.key()), "missing (this build's report has it)");
    for (auto it = g.begin(); it != g.end(); ++it) {
      const std::string at = Checker::join(path, it.key());
      const auto fit = f.find(it.key());
      if (fit == f.end()) {
        out.emplace_back(at, "unknown field (not in this build's report)");
      } else {
        shape_differences(*it, *fit, at, out);
      }
    }
  } else if (g.is_array()) {
    for (std::size_t i = 0; i < std::min(g.size(), f.size()); ++i)
      shape_differences(g[i], f[i], fmt::format("{}[{}]", path, i), out);
  }
}

}  // namespace

nlohmann::json Golden::to_json() const {
  nlohmann::json j = {{"units", units}, {"report", report}};
  if (kind == GoldenKind::kTrace) {
    j["trace"] = trace;
    j["sink_ready"] = sink_ready;
    j["seed"] = seed;
  } else {
    j["scene"] = scene;
  }
  // Absent on the default chip, so that goldens made before the key read the same.
  if (!chip.empty()) j["chip"] = chip;
  if (!budgets.empty()) {
    nlohmann::json b = nlohmann::json::object();
    for (const auto& [spec, conditions] : budgets) b[spec] = conditions;
    j["budgets"] = b;
  }
  return j;
}

namespace {

// The input's file name: NAME.vec for a trace, NAME.json for a scene, without a folder.
std::string checked_input_name(const Checker& c, const nlohmann::json& doc, const char* key,
                               const char* suffix) {
  const std::string name = doc.at(key).get<std::string>();
  const std::string want(suffix);
  if (name.empty() || name.find('/') != std::string::npos || name.size() <= want.size() ||
      name.compare(name.size() - want.size(), want.size(), want) != 0)
    c.fail(key, fmt::format("must be the {}'s file name, NAME{}", key, suffix));
  return name;
}

void parse_budgets_shape(const Checker& c, const nlohmann::json& budgets, Golden& g) {
  if (budgets.empty()) c.fail("budgets", "empty (leave it out, or give a lane its conditions)");
  for (auto it = budgets.begin(); it != budgets.end(); ++it) {
    const std::string at = "budgets." + it.key();
    if (std::find(g.units.begin(), g.units.end(), it.key()) == g.units.end())
      c.fail(at, "no lane has this spec: a key must be one of `units`, as written there");
    if (!it->is_string())
      c.fail(at,
             "must be a string of conditions, as glint size's --budget takes them "
             "('image.max_lsb<=1,area_ge<=12000')");
    g.budgets.emplace_back(it.key(), it->get<std::string>());
  }
}

}  // namespace

Golden parse_golden(const std::string& text, const std::string& file, GoldenUse use) {
  nlohmann::json doc = parse_json_text(text, file, kGoldenMaxJsonDepth);
  const Checker c(file);
  Golden g;
  g.kind = doc.is_object() && doc.contains("scene") && !doc.contains("trace") ? GoldenKind::kScene
                                                                              : GoldenKind::kTrace;
  // --update may complete a golden that records only its settings.
  const bool completing = use == GoldenUse::kUpdate && doc.is_object() && !doc.contains("report");
  if (completing) doc["report"] = nlohmann::json::object();
  if (use == GoldenUse::kCompare && doc.is_object() && !doc.contains("report"))
    c.fail("report",
           "missing: `glint regress --update` records it (or write null for a golden of budgets "
           "only)");
  if (g.kind == GoldenKind::kTrace) {
    c.object(doc, "", kGoldenFields);
    g.trace = checked_input_name(c, doc, "trace", ".vec");
  } else {
    c.object(doc, "", kSceneGoldenFields);
    g.scene = checked_input_name(c, doc, "scene", ".json");
  }
  const auto& units = doc.at("units");
  if (units.empty() || units.size() > kGoldenMaxUnits)
    c.fail("units", fmt::format("must list 1..{} unit specs", kGoldenMaxUnits));
  for (std::size_t i = 0; i < units.size(); ++i) {
    const std::string at = fmt::format("units[{}]", i);
    if (!units[i].is_string()) c.fail(at, "must be a unit spec string");
    try {
      parse_unit_spec(units[i].get<std::string>());
    } catch (const std::invalid_argument& e) {
      c.fail(at, e.what());
    }
    g.units.push_back(units[i].get<std::string>());
  }
  if (g.kind == GoldenKind::kTrace) {
    g.sink_ready = doc.at("sink_ready").get<double>();
    if (!(g.sink_ready >= kMinSinkReady && g.sink_ready <= 1))
      c.fail("sink_ready",
             fmt::format("must be in [{}, 1] (as sim's --sink-ready)", kMinSinkReady));
    g.seed = doc.at("seed").get<std::uint64_t>();
    // sim refuses --seed with an always-ready sink, so such a run reports sim's default seed.
    if (g.sink_ready >= 1 && g.seed != 1)
      c.fail("seed",
             "must be 1 (sim's default) when sink_ready is 1: an always-ready sink has no "
             "pattern to seed");
  }
  if (doc.contains("chip")) {
    g.chip = doc.at("chip").get<std::string>();
    try {
      parse_chip(g.chip);
    } catch (const std::invalid_argument& e) {
      c.fail("chip", fmt::format("'{}' is not a --chip value: {}", g.chip, e.what()));
    }
  }
  if (doc.contains("budgets")) parse_budgets_shape(c, doc.at("budgets"), g);
  const auto& report = doc.at("report");
  if (report.is_null()) {
    // Nothing to compare but the budgets: a golden of neither would pass anything.
    if (g.budgets.empty())
      c.fail("report", "null, but the golden holds no budgets: it would check nothing");
    g.budgets_only = true;
    return g;
  }
  if (!report.is_object()) c.fail("report", "must be an object, or null for budgets only");
  if (use == GoldenUse::kCompare) {
    if (g.kind == GoldenKind::kTrace) {
      check_report(c, g, report);
    } else {
      check_render_report(c, g, report);
    }
    g.report = report;
  }
  return g;
}

Golden read_golden(const std::string& path, GoldenUse use) {
  return parse_golden(read_text_file(path, kGoldenMaxFileBytes, "golden"), path, use);
}

void check_report_shape(const nlohmann::json& golden_report, const nlohmann::json& fresh,
                        const std::string& file) {
  // The render report's version is known above this layer: compared with this build's here.
  for (const char* key : {"glint_sim_report", "glint_render_report"}) {
    if (golden_report.contains(key) && fresh.contains(key) && golden_report[key] != fresh[key])
      throw InputError(file, 0, std::string("report.") + key,
                       fmt::format("schema version {}, this build writes version {}: regenerate "
                                   "the golden (glint regress --update)",
                                   golden_report[key].dump(), fresh[key].dump()));
  }
  std::vector<std::pair<std::string, std::string>> diffs;
  shape_differences(golden_report, fresh, "report", diffs);
  if (diffs.empty()) return;
  std::string message = diffs.front().second;
  if (diffs.size() > 1)
    message += fmt::format(" (and {} more schema differences)", diffs.size() - 1);
  throw InputError(file, 0, diffs.front().first,
                   message +
                       ": the golden does not match this build's report schema "
                       "(regenerate it deliberately: glint regress --update)");
}

}  // namespace glint
