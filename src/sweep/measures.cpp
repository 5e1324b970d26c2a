#include "sweep/measures.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace glint {
namespace {

std::vector<SweepColumn> build_columns() {
  using K = ColumnKind;
  std::vector<SweepColumn> c = {
      {"index", "/index", K::kInteger},
      {"unit", "/unit", K::kText},
      {"spec", "/spec", K::kText},
      {"canonical_spec", "/canonical_spec", K::kText},
      {"area_ge", "/area_ge", K::kNumber},
      {"critical_path", "/critical_path", K::kNumber},
      {"critical_stage", "/critical_stage", K::kText},
      {"latency", "/latency", K::kInteger},
      {"ii", "/ii", K::kInteger},
      {"buffer_depth", "/buffer_depth", K::kInteger},
      {"area_latency", "/area_latency", K::kNumber},
      {"vectors", "/vectors", K::kInteger},
      {"skipped", "/skipped", K::kInteger},
      {"computed", "/computed", K::kInteger},
      {"cycles", "/cycles", K::kInteger},
      {"throughput", "/throughput", K::kNumber},
      {"latency_min", "/latency_cycles/min", K::kInteger},
      {"latency_mean", "/latency_cycles/mean", K::kNumber},
      {"latency_max", "/latency_cycles/max", K::kInteger},
      {"stall_cycles", "/stall_cycles", K::kInteger},
      // The lane at the node (engine.cpp copies them from UnitCost::node_json).
      {"area_um2", "/node/area_um2", K::kNumber, false, true},
      {"critical_path_ns", "/node/critical_path_ns", K::kNumber, false, true},
      {"max_clock_mhz", "/node/max_clock_mhz", K::kNumber, false, true},
      {"energy_pj_per_request", "/energy_pj_per_request", K::kNumber, false, true},
  };
  for (const std::string& k : operation_kinds()) {
    c.push_back({"ops_" + k, "/operations/total/" + k, K::kNumber});
    c.push_back({"ops_" + k + "_per_computed", "/operations/per_computed/" + k, K::kNumber});
    c.push_back({"ops_" + k + "_per_request", "/operations/per_request/" + k, K::kNumber});
  }
  for (const char* e : {"max_abs", "rms", "t_at_max"})
    c.push_back({e, std::string("/errors/") + e, K::kNumber});
  c.push_back({"count", "/errors/count", K::kInteger});
  for (const char* e : {"max_datapath_ulps", "t_at_max_datapath_ulps"})
    c.push_back({e, std::string("/errors/") + e, K::kNumber});
  c.push_back({"display_bits", "/errors/display_bits", K::kInteger});
  for (const char* e : {"max_lsb", "mismatch_fraction"})
    c.push_back({e, std::string("/errors/") + e, K::kNumber});
  c.push_back({"always_skipped_vectors", "/errors/always_skipped_vectors", K::kInteger});
  for (const char* e : {"bound", "bound_lsb"})
    c.push_back({e, std::string("/errors/") + e, K::kNumber});
  for (const char* e : {"max_abs", "t_at_max", "max_lsb", "bound", "bound_lsb"})
    c.push_back({std::string("weighted.") + e, std::string("/errors/weighted/") + e, K::kNumber});
  for (const char* p : {"input", "parameter", "approximation", "datapath", "skip"})
    for (const char* e : {"max_abs", "t_at_max", "bound"})
      c.push_back(
          {fmt::format("parts.{}.{}", p, e), fmt::format("/errors/parts/{}/{}", p, e), K::kNumber});
  c.push_back({"parts.datapath.max_ulps", "/errors/parts/datapath/max_ulps", K::kNumber});
  c.push_back({"parts.datapath.bound_ulps", "/errors/parts/datapath/bound_ulps", K::kNumber});
  c.push_back({"contract", "/errors/contract", K::kText});
  c.push_back({"contract_reason", "/errors/contract_reason", K::kText});
  for (const char* e : {"max_lsb", "mean_lsb", "psnr_db", "differing_fraction"})
    c.push_back({std::string("image.") + e, std::string("/image/") + e, K::kNumber, true});
  c.push_back({"image.highlight_pixels", "/image/highlight_pixels", K::kInteger, true});
  c.push_back({"image.highlight_ratio", "/image/highlight_ratio", K::kNumber, true});
  c.push_back({"image.core_pixels", "/image/core_pixels", K::kInteger, true});
  c.push_back({"image.core_ratio", "/image/core_ratio", K::kNumber, true});
  c.push_back({"refused", "/refused", K::kText});
  c.push_back({"digest", "/digest", K::kText});
  c.push_back({"error", "/error", K::kNumber});
  c.push_back({"pareto_area", "/pareto/area", K::kFlag});
  c.push_back({"pareto_throughput", "/pareto/throughput", K::kFlag});
  c.push_back({"pareto_area_latency", "/pareto/area_latency", K::kFlag});
  c.push_back({"pareto_energy", "/pareto/energy", K::kFlag, false, true});
  return c;
}

bool numeric(const SweepColumn& c) {
  return c.kind == ColumnKind::kNumber || c.kind == ColumnKind::kInteger;
}

const SweepColumn* column(std::string_view name, bool scene) {
  for (const SweepColumn& c : sweep_columns())
    if (c.name == name && numeric(c) && (scene || !c.scene_only)) return &c;
  return nullptr;
}

// LSB measures and the absolute errors they scale: "max_lsb" is max_abs x (2^bits - 1).
struct LsbMeasure {
  const char* lsb;
  const char* abs_pointer;
};
constexpr LsbMeasure kLsbMeasures[] = {{"max_lsb", "/errors/max_abs"},
                                       {"bound_lsb", "/errors/bound"},
                                       {"weighted.max_lsb", "/errors/weighted/max_abs"},
                                       {"weighted.bound_lsb", "/errors/weighted/bound"}};

std::string measure_list(bool scene) {
  std::string out;
  for (const SweepColumn& c : sweep_columns())
    if (numeric(c) && (scene || !c.scene_only) && c.name != "index")
      out += (out.empty() ? "" : ", ") + c.name;
  out +=
      "; LSB measures at another depth with a suffix: max_lsbN, bound_lsbN, "
      "weighted.max_lsbN, weighted.bound_lsbN (N = 1..16); aliases: ";
  for (const MeasureAlias& a : measure_aliases())
    out +=
        fmt::format("{}{} = {}", &a == &measure_aliases().front() ? "" : ", ", a.alias, a.measure);
  return out;
}

// A measure by its own name: a column, or an LSB measure with a depth suffix.
std::optional<MeasureRef> find_named(std::string_view name, bool scene) {
  if (const SweepColumn* c = column(name, scene))
    return MeasureRef{std::string(name), c->pointer, 0};
  // An LSB measure with a depth: the longest digit suffix after a known LSB name.
  std::size_t digits = 0;
  while (digits < name.size() &&
         std::isdigit(static_cast<unsigned char>(name[name.size() - 1 - digits])))
    ++digits;
  if (digits == 0 || digits > 2) return std::nullopt;
  const std::string_view base = name.substr(0, name.size() - digits);
  int bits = 0;
  std::from_chars(name.data() + base.size(), name.data() + name.size(), bits);
  if (bits < 1 || bits > 16) return std::nullopt;
  for (const LsbMeasure& m : kLsbMeasures)
    if (base == m.lsb) return MeasureRef{std::string(name), m.abs_pointer, bits};
  return std::nullopt;
}

}  // namespace

const std::vector<std::string>& operation_kinds() {
  static const std::vector<std::string> kinds = {"add", "compare",  "div_step", "lzd",
                                                 "mul", "reg_bits", "shift",    "table_read"};
  return kinds;
}

const std::vector<SweepColumn>& sweep_columns() {
  static const std::vector<SweepColumn> columns = build_columns();
  return columns;
}

const std::vector<MeasureAlias>& measure_aliases() {
  // Short names of the text tables before they were headed by the measures' own names, issue 9's
  // "lsb8", and the --objective words.
  static const std::vector<MeasureAlias> aliases = {
      {"lsb", "max_lsb", "issue 9's lsb8 <= 1; glint eval's table before (lsb8)"},
      {"wlsb", "weighted.max_lsb", "glint eval's table before (wlsb8)"},
      {"max_err", "max_abs", "glint eval's and sim's tables before"},
      {"rms_err", "rms", "glint eval's table before"},
      {"t@max", "t_at_max", "glint eval's table before"},
      {"dp_ulps", "max_datapath_ulps", "glint eval's and sim's tables before"},
      {"res/cyc", "throughput", "glint sim's and sweep's tables before"},
      {"stalls", "stall_cycles", "glint sim's table before"},
      {"cp", "critical_path", "glint sim's table before"},
      {"area", "area_ge", "glint size --objective area"},
      {"area*latency", "area_latency", "glint size --objective area*latency"},
      {"energy", "energy_pj_per_request", "glint size --objective energy"},
      {"area*lat", "area_latency", "glint sweep's table before"},
      {"lat", "latency", "glint sweep's table before"},
  };
  return aliases;
}

std::optional<MeasureRef> find_measure(std::string_view name, bool scene) {
  if (auto m = find_named(name, scene)) return m;
  // An alias, and an LSB alias with a depth suffix ("lsb8", "wlsb10"): the measure it stands for,
  // under the name as written.
  for (const MeasureAlias& a : measure_aliases()) {
    const std::string_view alias = a.alias;
    if (name.substr(0, alias.size()) != alias) continue;
    const std::string_view rest = name.substr(alias.size());
    const bool depth =
        !rest.empty() && std::string_view(a.measure).find("lsb") != std::string::npos &&
        std::all_of(rest.begin(), rest.end(),
                    [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
    if (!rest.empty() && !depth) continue;
    if (auto m = find_named(std::string(a.measure) + std::string(rest), scene)) {
      m->name = std::string(name);
      return m;
    }
  }
  return std::nullopt;
}

MeasureRef measure_or_throw(std::string_view name, bool scene, const std::string& option) {
  if (auto m = find_measure(name, scene)) return *m;
  const bool image = name.substr(0, 6) == "image.";
  throw std::invalid_argument(fmt::format(
      "{}: unknown measure '{}'{} (measures: {})", option, name,
      image && !scene ? " (image-level measures need --scene)" : "", measure_list(scene)));
}

std::optional<double> measure_value(const nlohmann::json& row, const MeasureRef& m) {
  const nlohmann::json::json_pointer ptr(m.pointer);
  if (!row.contains(ptr)) return std::nullopt;
  const nlohmann::json& v = row.at(ptr);
  if (!v.is_number()) return std::nullopt;
  const double x = v.get<double>();
  return m.bits > 0 ? x * static_cast<double>((std::int64_t{1} << m.bits) - 1) : x;
}

bool is_error_measure(const MeasureRef& m) {
  if (m.bits > 0) return true;
  const std::string& p = m.pointer;
  const bool error = p.rfind("/errors/", 0) == 0 || p.rfind("/image/", 0) == 0 || p == "/error";
  const bool excluded = p.find("t_at_max") != std::string::npos || p == "/errors/count" ||
                        p == "/errors/display_bits" || p == "/errors/always_skipped_vectors" ||
                        p == "/image/psnr_db" || p.find("highlight") != std::string::npos ||
                        p.find("core_") != std::string::npos || p == "/error";
  return error && !excluded;
}

bool is_bound_measure(const MeasureRef& m) {
  return m.pointer.find("bound") != std::string::npos;
}

bool row_bounds_exact(const nlohmann::json& row) {
  const auto errors = row.find("errors");
  if (errors == row.end() || !errors->is_object() || !errors->contains("slots")) return true;
  for (const nlohmann::json& s : errors->at("slots"))
    if (s.is_object() && !s.value("exact", true)) return false;
  return true;
}

std::vector<Budget> parse_budgets(std::string_view text, bool scene, const std::string& option) {
  std::vector<Budget> out;
  const std::string whole(text);
  const auto bad = [&](std::string_view item, const std::string& why) {
    return std::invalid_argument(fmt::format("{} '{}': '{}': {}", option, whole, item, why));
  };
  if (text.empty()) throw bad(text, "empty (expected MEASURE<=VALUE[,...])");
  for (;;) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    const auto op_at = item.find_first_of("<>");
    if (op_at == std::string_view::npos || op_at == 0)
      throw bad(item, "expected MEASURE OP VALUE with OP one of <=, <, >=, >");
    Budget b;
    b.text = std::string(item);
    b.op = item.substr(op_at, item.size() > op_at + 1 && item[op_at + 1] == '=' ? 2 : 1);
    std::string name(item.substr(0, op_at));
    name.erase(name.find_last_not_of(' ') + 1);
    std::string value(item.substr(op_at + b.op.size()));
    value.erase(0, value.find_first_not_of(' '));
    char* end = nullptr;
    b.limit = value.empty() ? 0 : std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(b.limit))
      throw bad(item, fmt::format("'{}' is not a finite number", value));
    b.measure = measure_or_throw(name, scene, fmt::format("{} '{}'", option, whole));
    out.push_back(std::move(b));
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return out;
}

bool meets(const nlohmann::json& row, const Budget& b) {
  const std::optional<double> v = measure_value(row, b.measure);
  if (!v || std::isnan(*v)) return false;
  if (b.op == "<=") return *v <= b.limit;
  if (b.op == "<") return *v < b.limit;
  if (b.op == ">=") return *v >= b.limit;
  return *v > b.limit;
}

}  // namespace glint
