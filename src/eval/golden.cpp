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
};

// The sim report's fixed part (src/eval/sim_report.md, version 4): its top level and each
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
                                   {"slot_capacity", Kind::kUnsigned},
                                   {"units", Kind::kArray}};
constexpr Field kUnitFields[] = {
    {"unit", Kind::kString},           {"spec", Kind::kString},
    {"config", Kind::kObject},         {"timing", Kind::kObject},
    {"elaboration", Kind::kObject},    {"colour_multiply", Kind::kBoolean},
    {"vectors", Kind::kUnsigned},      {"skipped", Kind::kUnsigned},
    {"computed", Kind::kUnsigned},     {"cycles", Kind::kUnsigned},
    {"throughput", Kind::kNumber},     {"latency", Kind::kObject},
    {"stall_cycles", Kind::kUnsigned}, {"stalls", Kind::kObject},
    {"sink_wait", Kind::kUnsigned},    {"operations", Kind::kObject},
    {"area", Kind::kObject},           {"critical_path", Kind::kObject},
    {"errors", Kind::kObject},         {"digest", Kind::kHex16}};
constexpr Field kLatencyFields[] = {
    {"min", Kind::kUnsigned}, {"mean", Kind::kNumber}, {"max", Kind::kUnsigned}};
constexpr Field kStallFields[] = {{"merge_buffer_full", Kind::kUnsigned},
                                  {"unit_busy", Kind::kUnsigned}};
constexpr Field kAreaFields[] = {{"ge", Kind::kNumber}, {"inventory", Kind::kArray}};
constexpr Field kCriticalPathFields[] = {{"delay", Kind::kNumber}, {"stage", Kind::kString}};
constexpr Field kGoldenFields[] = {{"trace", Kind::kString},
                                   {"units", Kind::kArray},
                                   {"sink_ready", Kind::kNumber},
                                   {"seed", Kind::kUnsigned},
                                   {"report", Kind::kObject}};

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
  return {{"trace", trace},
          {"units", units},
          {"sink_ready", sink_ready},
          {"seed", seed},
          {"report", report}};
}

Golden parse_golden(const std::string& text, const std::string& file, GoldenUse use) {
  const nlohmann::json doc = parse_json_text(text, file, kGoldenMaxJsonDepth);
  const Checker c(file);
  Golden g;
  if (use == GoldenUse::kUpdate && doc.is_object() && !doc.contains("report")) {
    // --update may complete a golden that records only its settings.
    nlohmann::json settings = doc;
    settings["report"] = nlohmann::json::object();
    c.object(settings, "", kGoldenFields);
  } else {
    c.object(doc, "", kGoldenFields);
  }
  g.trace = doc.at("trace").get<std::string>();
  if (g.trace.empty() || g.trace.find('/') != std::string::npos || g.trace.size() < 5 ||
      g.trace.compare(g.trace.size() - 4, 4, ".vec") != 0)
    c.fail("trace", "must be the trace's file name, NAME.vec");
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
  g.sink_ready = doc.at("sink_ready").get<double>();
  if (!(g.sink_ready >= kMinSinkReady && g.sink_ready <= 1))
    c.fail("sink_ready", fmt::format("must be in [{}, 1] (as sim's --sink-ready)", kMinSinkReady));
  g.seed = doc.at("seed").get<std::uint64_t>();
  // sim refuses --seed with an always-ready sink, so such a run reports sim's default seed.
  if (g.sink_ready >= 1 && g.seed != 1)
    c.fail("seed",
           "must be 1 (sim's default) when sink_ready is 1: an always-ready sink has no "
           "pattern to seed");
  if (use == GoldenUse::kCompare) {
    check_report(c, g, doc.at("report"));
    g.report = doc.at("report");
  }
  return g;
}

Golden read_golden(const std::string& path, GoldenUse use) {
  return parse_golden(read_text_file(path, kGoldenMaxFileBytes, "golden"), path, use);
}

void check_report_shape(const nlohmann::json& golden_report, const nlohmann::json& fresh,
                        const std::string& file) {
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
