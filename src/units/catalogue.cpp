#include "units/catalogue.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fit/fit.h"
#include "units/hast/datapath.h"
#include "units/horner/datapath.h"
#include "units/lut/datapath.h"
#include "units/pow/datapath.h"
#include "units/schlick/datapath.h"

namespace glint {
namespace {

std::vector<UnitKey> common_keys() {
  return {{"in", "input format of t (clamped to [0, 1], rounded to nearest)", kDefaultIn.name()},
          {"out", "output format of the highlight", kDefaultOut.name()},
          {"skip", "tau comparator on|off (skip t <= tau, Källberg eq.5)", "on"},
          {"buffer", "merge-buffer entries (timing; auto: latency + 3, full throughput)", "auto"}};
}

std::vector<UnitInfo> build_catalog() {
  auto with_common = [](std::vector<UnitKey> keys) {
    auto all = common_keys();
    all.insert(all.end(), keys.begin(), keys.end());
    return all;
  };
  const PowConfig pw;
  return {
      {"pow", "exact-power baseline: log2 table + interp, multiply by n, exp2 table + interp",
       with_common(
           {{"n", "shininess register format", pw.n_format.name()},
            {"log_bits", "log2 table address bits (2^b + 1 entries)", std::to_string(pw.log_bits)},
            {"log_frac", "log2 table entry fraction bits", std::to_string(pw.log_frac)},
            {"y_frac", "fraction bits of y = n log2 t", std::to_string(pw.y_frac)},
            {"exp_bits", "exp2 table address bits", std::to_string(pw.exp_bits)},
            {"exp_frac", "exp2 table entry fraction bits", std::to_string(pw.exp_frac)}})},
      {"schlick", "Schlick t/(n - n t + t) with an exact, correctly rounded divider",
       with_common({{"n", "shininess register format", SchlickConfig{}.n_format.name()},
                    {"divider",
                     "divider kind (timing): pipelined (one quotient bit per stage, II 1) | "
                     "iterative (radix-2, one quotient bit per cycle, II = quotient bits)",
                     "pipelined"}})},
      {"hast", "Hast kappa (t - tau)^d as u^d, u = (t - tau)/(1 - tau): multiplier chain",
       with_common({{"d", "exponent: d - 1 multipliers", "4"},
                    {"guard", "guard bits of the chain (auto: ceil(log2(2d-2)) + 1)", "auto"}})},
      {"horner", "fitted polynomial, Horner pipeline (Öztürk eq.12), one multiply-add per stage",
       with_common(
           {{"degree", "polynomial degree p (1..10)", "4"},
            {"method", "fit: ls | robust (Öztürk, bisquare) | minimax (Remez)", "minimax"},
            {"domain", "fit domain: tau ([tau, 1], u = (t-tau)/(1-tau)) | full ((0, 1])", "tau"},
            {"constrain", "on: P(1) = 1 and, on the tau domain, P(tau) = 0", "on"},
            {"guard", "guard bits (auto: faithful bound from the coefficients)", "auto"}})},
      {"lut", "table of t^n over [t0, 1] + linear interpolation, one table per material",
       with_common({{"bits", "table address bits (2^b + 1 entries)", "6"},
                    {"table_frac", "table entry fraction bits (auto: out + 2)", "auto"}})},
  };
}

// Reads the keys of one spec, each once, and reports leftovers as errors.
class KeyReader {
 public:
  KeyReader(const UnitSpec& spec, const UnitInfo& info) : spec_(spec), info_(info) {
    for (const auto& [k, v] : spec.keys) {
      const bool known = std::any_of(info.keys.begin(), info.keys.end(),
                                     [&](const UnitKey& uk) { return uk.key == k; });
      if (!known) fail(k, v, "unknown key (see `glint units`)");
    }
  }
  const std::string* find(const std::string& key) const {
    for (const auto& [k, v] : spec_.keys)
      if (k == key) return &v;
    return nullptr;
  }
  QFormat format(const std::string& key, QFormat def) const {
    const std::string* v = find(key);
    if (!v) return def;
    try {
      return parse_q_format(*v);
    } catch (const std::invalid_argument& e) {
      fail(key, *v, e.what());
    }
  }
  int integer(const std::string& key, int def, int lo, int hi, bool allow_auto = false) const {
    const std::string* v = find(key);
    if (!v || (allow_auto && *v == "auto")) return def;
    int out = 0;
    auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), out);
    if (ec != std::errc() || p != v->data() + v->size() || out < lo || out > hi)
      fail(key, *v, fmt::format("expected an integer in {}..{}", lo, hi));
    return out;
  }
  bool flag(const std::string& key, bool def) const {
    const std::string* v = find(key);
    if (!v) return def;
    if (*v == "on" || *v == "1" || *v == "true" || *v == "yes") return true;
    if (*v == "off" || *v == "0" || *v == "false" || *v == "no") return false;
    fail(key, *v, "expected on or off");
  }
  std::string choice(const std::string& key, const std::string& def,
                     const std::vector<std::string>& allowed) const {
    const std::string* v = find(key);
    if (!v) return def;
    if (std::find(allowed.begin(), allowed.end(), *v) == allowed.end())
      fail(key, *v, "expected one of " + fmt::format("{}", fmt::join(allowed, "|")));
    return *v;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& value,
                         const std::string& why) const {
    throw std::invalid_argument(fmt::format("key '{}' = '{}': {}", key, value, why));
  }

 private:
  const UnitSpec& spec_;
  const UnitInfo& info_;
};

const char* on_off(bool b) {
  return b ? "on" : "off";
}

nlohmann::json describe_slot(const SchlickUnit& u) {
  return {{"tau_raw", u.tau_raw()}, {"n_raw", u.n_raw()}, {"n", u.shininess_q()}};
}
nlohmann::json describe_slot(const HastUnit& u) {
  return {{"tau_raw", u.tau_raw()},
          {"root_raw", u.scaler().root_raw()},
          {"k", u.scaler().k_value()},
          {"k_int_bits", u.scaler().k_int_bits()},
          {"k_frac_bits", u.scaler().k_frac()}};
}
nlohmann::json describe_slot(const HornerUnit& u) {
  return {{"tau_raw", u.tau_raw()},
          {"root_raw", u.scaler().root_raw()},
          {"k", u.scaler().k_value()},
          {"k_int_bits", u.scaler().k_int_bits()},
          {"k_frac_bits", u.scaler().k_frac()},
          {"coefficients", u.coefficients().c},
          {"coefficients_raw", u.coeff_raw()},
          {"coefficient_format", u.coeff_format().name()},
          {"acc_int_bits", u.acc_int_bits()}};
}
nlohmann::json describe_slot(const PowUnit& u) {
  return {{"tau_raw", u.tau_raw()},       {"n", u.shininess_q()},
          {"table_bits", u.table_bits()}, {"log_error", u.log_error()},
          {"exp_error", u.exp_error()},   {"error_bound", u.error_bound()}};
}
nlohmann::json describe_slot(const LutUnit& u) {
  return {{"tau_raw", u.tau_raw()},         {"t0_raw", u.t0_raw()},
          {"span_log2", u.span_log2()},     {"entries", u.table().size() - 1},
          {"chord_error", u.chord_error()}, {"error_bound", u.error_bound()}};
}

// The one adapter from a datapath class to the runtime interface: per-slot instances, comparator
// in front, and a batch loop the compiler can inline the datapath into.
template <class Unit>
class UnitSet final : public SpecularUnit {
 public:
  UnitSet(std::string name, std::string canonical, QFormat in, QFormat out, std::vector<Unit> units,
          nlohmann::json config, UnitTiming timing)
      : name_(std::move(name)),
        canonical_(std::move(canonical)),
        in_(in),
        out_(out),
        units_(std::move(units)),
        config_(std::move(config)),
        timing_(timing) {}

  const std::string& name() const override { return name_; }
  std::string canonical_spec() const override { return canonical_; }
  QFormat in_format() const override { return in_; }
  QFormat out_format() const override { return out_; }
  std::size_t slots() const override { return units_.size(); }
  std::int64_t tau_raw(std::size_t s) const override { return units_[s].tau_raw(); }
  std::int64_t eval(std::size_t s, std::int64_t t) const override { return units_[s].eval(t); }
  double model(std::size_t s, std::int64_t t) const override { return units_[s].model(t); }
  double float_model(std::size_t s, double t) const override { return units_[s].float_model(t); }
  void eval_batch(std::size_t s, const std::int64_t* t, std::int64_t* out, std::uint8_t* skipped,
                  std::size_t n) const override {
    const Unit& u = units_[s];
    const std::int64_t tau = u.tau_raw();
    for (std::size_t i = 0; i < n; ++i) {
      const bool sk = tau_skip(t[i], tau);
      skipped[i] = sk;
      out[i] = sk ? 0 : u.eval(t[i]);
    }
  }
  double error_bound(std::size_t s) const override {
    if constexpr (std::is_same_v<Unit, PowUnit> || std::is_same_v<Unit, LutUnit>) {
      return units_[s].error_bound();
    } else {
      (void)s;
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  UnitTiming timing() const override { return timing_; }
  nlohmann::json describe() const override {
    nlohmann::json j;
    j["name"] = name_;
    j["spec"] = canonical_;
    j["config"] = config_;
    j["timing"] = {
        {"latency", timing_.latency}, {"ii", timing_.ii}, {"buffer_depth", timing_.buffer_depth}};
    nlohmann::json slots = nlohmann::json::array();
    for (const Unit& u : units_) slots.push_back(describe_slot(u));
    j["slots"] = std::move(slots);
    return j;
  }

 private:
  std::string name_, canonical_;
  QFormat in_, out_;
  std::vector<Unit> units_;
  nlohmann::json config_;
  UnitTiming timing_;
};

template <class Unit, class Config, class... Extra>
std::vector<Unit> build_all(const Config& cfg, const std::vector<MaterialParams>& slots,
                            const Extra&... extra) {
  std::vector<Unit> units;
  units.reserve(slots.size());
  for (const auto& m : slots) units.emplace_back(cfg, m, extra...);
  return units;
}

template <class Unit>
std::unique_ptr<SpecularUnit> wrap(const std::string& name, nlohmann::json config, QFormat in,
                                   QFormat out, std::vector<Unit> units, UnitTiming timing,
                                   int buffer) {
  // buffer = auto: enough credits that a result never waits for one when the sink keeps up.
  timing.buffer_depth = buffer > 0 ? buffer : timing.latency + 3;
  config["buffer"] = timing.buffer_depth;
  // Keys in catalogue order, so the spec reads like the `glint units` listing.
  std::string canonical = name;
  char sep = ':';
  for (const UnitKey& key : unit_info(name).keys) {
    const auto it = config.find(key.key);
    if (it == config.end()) continue;
    canonical += sep + key.key + "=" + (it->is_string() ? it->get<std::string>() : it->dump());
    sep = ',';
  }
  return std::make_unique<UnitSet<Unit>>(name, canonical, in, out, std::move(units), config,
                                         timing);
}

}  // namespace

UnitSpec parse_unit_spec(std::string_view text) {
  UnitSpec spec;
  const auto colon = text.find(':');
  spec.name = std::string(text.substr(0, colon));
  if (spec.name.empty()) throw std::invalid_argument("empty unit spec");
  if (colon == std::string_view::npos) return spec;
  std::string_view rest = text.substr(colon + 1);
  if (rest.empty())
    throw std::invalid_argument(fmt::format("unit spec '{}': no keys after ':'", text));
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    const auto eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0 || eq + 1 == item.size()) {
      throw std::invalid_argument(fmt::format("unit spec '{}': '{}' is not key=value", text, item));
    }
    std::string key(item.substr(0, eq));
    for (const auto& kv : spec.keys)
      if (kv.first == key)
        throw std::invalid_argument(fmt::format("unit spec '{}': key '{}' given twice", text, key));
    spec.keys.emplace_back(std::move(key), std::string(item.substr(eq + 1)));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
    if (rest.empty())
      throw std::invalid_argument(fmt::format("unit spec '{}': trailing ','", text));
  }
  return spec;
}

std::vector<std::string> unit_labels(const std::vector<std::string>& names) {
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto same = std::count(names.begin(), names.end(), names[i]);
    const auto index =
        std::count(names.begin(), names.begin() + static_cast<long>(i) + 1, names[i]);
    labels.push_back(same > 1 ? names[i] + "." + std::to_string(index) : names[i]);
  }
  return labels;
}

const std::vector<UnitInfo>& unit_catalog() {
  static const std::vector<UnitInfo> catalog = build_catalog();
  return catalog;
}

std::vector<std::string> unit_names() {
  std::vector<std::string> names;
  for (const auto& u : unit_catalog()) names.push_back(u.name);
  return names;
}

const UnitInfo& unit_info(std::string_view name) {
  for (const auto& u : unit_catalog())
    if (u.name == name) return u;
  throw std::invalid_argument(
      fmt::format("unknown unit '{}' (known: pow, schlick, hast, horner, lut)", name));
}

namespace {
std::unique_ptr<SpecularUnit> build_unit(const UnitSpec& spec, const UnitInfo& info,
                                         const std::vector<MaterialParams>& slots) {
  const KeyReader keys(spec, info);
  const QFormat in = keys.format("in", kDefaultIn);
  const QFormat out = keys.format("out", kDefaultOut);
  const bool skip = keys.flag("skip", true);
  const int buffer = keys.integer("buffer", -1, 1, 1 << 16, true);
  nlohmann::json config = {{"in", in.name()}, {"out", out.name()}, {"skip", on_off(skip)}};
  {
    if (spec.name == "schlick") {
      SchlickConfig c{in, out, keys.format("n", SchlickConfig{}.n_format), skip};
      config["n"] = c.n_format.name();
      const std::string divider = keys.choice("divider", "pipelined", {"pipelined", "iterative"});
      config["divider"] = divider;
      // Denominator multiply-add stage, Fo + 2 quotient bits (integer bit, Fo fraction bits, the
      // rounding bit), rounding stage.
      const int q = out.frac_bits + 2;
      const UnitTiming t{q + 2, divider == "iterative" ? q : 1, 0};
      return wrap("schlick", config, in, out, build_all<SchlickUnit>(c, slots), t, buffer);
    }
    if (spec.name == "hast") {
      HastConfig c{in, out, keys.integer("d", 4, 1, 16), keys.integer("guard", -1, 0, 20, true),
                   skip};
      if (c.guard < 0) c.guard = hast_default_guard(c.d);
      config["d"] = c.d;
      config["guard"] = c.guard;
      // u scaler stage, then d - 1 multiplier stages.
      return wrap("hast", config, in, out, build_all<HastUnit>(c, slots), UnitTiming{c.d, 1, 0},
                  buffer);
    }
    if (spec.name == "horner") {
      const int degree = keys.integer("degree", 4, 1, 10);
      const std::string method = keys.choice("method", "minimax", {"ls", "robust", "minimax"});
      const std::string domain = keys.choice("domain", "tau", {"tau", "full"});
      const bool constrain = keys.flag("constrain", true);
      HornerConfig c{in, out, keys.integer("guard", -1, 0, 20, true), skip};
      // Fit every slot first: the datapath width is shared, so the guard is the largest any
      // slot needs.
      std::vector<HornerCoefficients> fits;
      int guard = 0, required = 0, max_guard = 64;
      for (const auto& m : slots) {
        FitOptions o;
        o.shininess = m.shininess;
        o.degree = degree;
        o.method = parse_fit_method(method);
        o.domain = domain == "tau" ? FitDomain::kTau : FitDomain::kFull;
        o.tau = std::clamp(m.always_skip ? 0.0 : m.tau, 0.0, 0.999);
        o.constrain_one = constrain;
        o.constrain_zero = constrain && domain == "tau";
        const FitResult r = fit_power(o);
        HornerCoefficients hc{r.coeffs, domain == "tau", o.constrain_one, o.constrain_zero};
        guard = std::max(guard, horner_preferred_guard(hc));
        required = std::max(required, horner_required_guard(hc));
        max_guard = std::min(max_guard, horner_max_guard(hc, out));
        fits.push_back(std::move(hc));
      }
      if (c.guard < 0) c.guard = std::max(required, std::min(guard, max_guard));
      config["degree"] = degree;
      config["method"] = method;
      config["domain"] = domain;
      config["constrain"] = on_off(constrain);
      config["guard"] = c.guard;
      std::vector<HornerUnit> units;
      for (std::size_t i = 0; i < slots.size(); ++i) units.emplace_back(c, slots[i], fits[i]);
      // u scaler stage, then one multiply-add stage per degree.
      return wrap("horner", config, in, out, std::move(units), UnitTiming{degree + 1, 1, 0},
                  buffer);
    }
    if (spec.name == "pow") {
      PowConfig c;
      c.in = in;
      c.out = out;
      c.skip = skip;
      c.n_format = keys.format("n", c.n_format);
      c.log_bits = keys.integer("log_bits", c.log_bits, 1, 16);
      c.log_frac = keys.integer("log_frac", c.log_frac, 4, 30);
      c.y_frac = keys.integer("y_frac", c.y_frac, 4, 30);
      c.exp_bits = keys.integer("exp_bits", c.exp_bits, 1, 16);
      c.exp_frac = keys.integer("exp_frac", c.exp_frac, 4, 30);
      config.update({{"n", c.n_format.name()},
                     {"log_bits", c.log_bits},
                     {"log_frac", c.log_frac},
                     {"y_frac", c.y_frac},
                     {"exp_bits", c.exp_bits},
                     {"exp_frac", c.exp_frac}});
      // leading-one detect + log2 table read, log2 interpolation, multiply by n, exp2 table read,
      // exp2 interpolation + shift + rounding.
      return wrap("pow", config, in, out, build_all<PowUnit>(c, slots), UnitTiming{5, 1, 0},
                  buffer);
    }
    // lut
    LutConfig c{in, out, keys.integer("bits", 6, 1, 16),
                keys.integer("table_frac", -1, 0, 40, true), skip};
    if (c.table_frac < 0) c.table_frac = out.frac_bits + 2;
    config["bits"] = c.bits;
    config["table_frac"] = c.table_frac;
    // index + table read, interpolation + rounding.
    return wrap("lut", config, in, out, build_all<LutUnit>(c, slots), UnitTiming{2, 1, 0}, buffer);
  }
}
}  // namespace

std::unique_ptr<SpecularUnit> make_unit(const UnitSpec& spec,
                                        const std::vector<MaterialParams>& slots) {
  const UnitInfo& info = unit_info(spec.name);
  try {
    return build_unit(spec, info, slots);
  } catch (const std::invalid_argument& e) {
    // Datapath constructors name themselves ("hast: ..."); key errors do not.
    const std::string what = e.what();
    if (what.rfind(spec.name + ":", 0) == 0) throw;
    throw std::invalid_argument(fmt::format("unit '{}': {}", spec.name, what));
  }
}

}  // namespace glint
