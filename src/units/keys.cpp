#include "units/keys.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace glint {

KeyReader::KeyReader(const UnitSpec& spec, const std::vector<UnitKey>& known) : spec_(spec) {
  for (const auto& [k, v] : spec.keys) {
    const bool ok = std::any_of(known.begin(), known.end(),
                                [&key = k](const UnitKey& uk) { return uk.key == key; });
    // refusal: keys.unknown
    if (!ok) fail(k, v, "unknown key (see `glint units`)");
  }
}

const std::string* KeyReader::find(const std::string& key) const {
  for (const auto& [k, v] : spec_.keys)
    if (k == key) return &v;
  return nullptr;
}

QFormat KeyReader::format(const std::string& key, QFormat def) const {
  const std::string* v = find(key);
  if (!v) return def;
  try {
    return parse_q_format(*v);
  } catch (const std::invalid_argument& e) {
    // refusal: keys.format
    fail(key, *v, e.what());
  }
}

int KeyReader::integer(const std::string& key, int def, int lo, int hi, bool allow_auto) const {
  const std::string* v = find(key);
  if (!v || (allow_auto && *v == "auto")) return def;
  int out = 0;
  auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), out);
  if (ec != std::errc() || p != v->data() + v->size() || out < lo || out > hi)
    // refusal: keys.integer
    fail(key, *v, fmt::format("expected an integer in {}..{}", lo, hi));
  return out;
}

std::optional<double> KeyReader::real(const std::string& key, double lo, double hi) const {
  const std::string* v = find(key);
  if (!v) return std::nullopt;
  // strtod, not from_chars: libstdc++ before 11 has no floating-point from_chars.
  char* end = nullptr;
  const double x = v->empty() ? 0.0 : std::strtod(v->c_str(), &end);
  if (v->empty() || end != v->c_str() + v->size() || !std::isfinite(x) || !(x >= lo && x < hi))
    // refusal: keys.real
    fail(key, *v, fmt::format("expected a number x with {} <= x < {}", lo, hi));
  return x;
}

bool KeyReader::flag(const std::string& key, bool def) const {
  const std::string* v = find(key);
  if (!v) return def;
  if (*v == "on" || *v == "1" || *v == "true" || *v == "yes") return true;
  if (*v == "off" || *v == "0" || *v == "false" || *v == "no") return false;
  // refusal: keys.flag
  fail(key, *v, "expected on or off");
}

std::string KeyReader::choice(const std::string& key, const std::string& def,
                              const std::vector<std::string>& allowed) const {
  const std::string* v = find(key);
  if (!v) return def;
  if (std::find(allowed.begin(), allowed.end(), *v) == allowed.end())
    // refusal: keys.choice
    fail(key, *v, "expected one of " + fmt::format("{}", fmt::join(allowed, "|")));
  return *v;
}

void KeyReader::fail(const std::string& key, const std::string& value,
                     const std::string& why) const {
  // not from a spec: the throw of every fail() call, each tagged where it is called
  throw std::invalid_argument(fmt::format("key '{}' = '{}': {}", key, value, why));
}

std::string key_values(const std::vector<KeyValue>& kv) {
  std::string out = kv.size() == 1 ? "key " : "keys ";
  for (std::size_t i = 0; i < kv.size(); ++i) {
    if (i > 0) out += ", ";
    // A value that states its resolution ("'auto' (4)") carries its own quotes.
    const bool quoted = kv[i].value.rfind('\'', 0) == 0;
    out += fmt::format(quoted ? "'{}' = {}" : "'{}' = '{}'", kv[i].key, kv[i].value);
  }
  return out;
}

std::string auto_value(bool given, long long resolved) {
  return given ? std::to_string(resolved) : fmt::format("'auto' ({})", resolved);
}

std::vector<UnitKey> common_keys() {
  return {
      {"in", "input format of t (clamped to [0, 1], rounded to nearest)", kDefaultIn.name()},
      {"out", "output format of the highlight", kDefaultOut.name()},
      {"skip",
       "tau comparator on|off: skips t where the unit's own output is <= eps_K/c_y, never above "
       "Källberg's tau (eq.5, §3)",
       "on"},
      {"buffer", "merge-buffer entries (timing; auto: latency + 3, full throughput)", "auto"},
      {"tables",
       "per-slot tables (tau thresholds, per-material tables) as rom: case ROMs of the scene's "
       "materials, or ram: registers with a write port (glint rtl: cfg_*), loaded at run time",
       "rom"}};
}

CommonKeys read_common_keys(const KeyReader& keys) {
  CommonKeys c;
  c.in = keys.format("in", kDefaultIn);
  c.out = keys.format("out", kDefaultOut);
  // A format without a fraction bit cannot carry a highlight: uq1.0 holds 0 and 1 only (its
  // input rounding alone is a whole-range error), so it is refused rather than reported.
  for (const auto& [key, f] : {std::pair<const char*, QFormat>{"in", c.in}, {"out", c.out}}) {
    if (f.frac_bits < 1 || f.raw_one() == 0)
      // refusal: keys.fraction_bit
      throw std::invalid_argument(
          fmt::format("key '{}' = '{}': needs at least one fraction bit and must represent 1.0",
                      key, f.name()));
  }
  c.skip = keys.flag("skip", true);
  c.buffer = keys.integer("buffer", -1, 1, 1 << 16, true);
  c.tables_ram = keys.choice("tables", "rom", {"rom", "ram"}) == "ram";
  return c;
}

}  // namespace glint
