#include "units/keys.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
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

QFormat KeyReader::read(const FormatKey& k) const {
  return format(std::string(k.name), k.def);
}

int KeyReader::read(const IntKey& k) const {
  return integer(std::string(k.name), k.def, k.lo, k.hi, k.takes_auto);
}

bool KeyReader::read(const FlagKey& k) const {
  return flag(std::string(k.name), k.def);
}

std::string KeyReader::read(const ChoiceKey& k) const {
  return choice(std::string(k.name), std::string(k.def), k.choices());
}

std::optional<double> KeyReader::read(const RealKey& k) const {
  const std::string* v = find(std::string(k.name));
  if (!v || *v == "none") return std::nullopt;
  return real(std::string(k.name), k.lo, k.hi);
}

void put_key(nlohmann::json& config, const FormatKey& k, const QFormat& value) {
  config[std::string(k.name)] = value.name();
}

void put_key(nlohmann::json& config, const IntKey& k, int value) {
  config[std::string(k.name)] = value;
}

void put_key(nlohmann::json& config, const FlagKey& k, bool value) {
  config[std::string(k.name)] = on_off(value);
}

void put_key(nlohmann::json& config, const ChoiceKey& k, std::string_view value) {
  if (!k.in_canonical_at_default && value == k.def) return;
  config[std::string(k.name)] = std::string(value);
}

void put_key(nlohmann::json& config, const RealKey& k, std::optional<double> value) {
  if (value) config[std::string(k.name)] = *value;
}

UnitKey key_entry(const FormatKey& k) {
  return {std::string(k.name), std::string(k.doc), k.def.name(), "uqI.F or sqI.F"};
}

UnitKey key_entry(const IntKey& k) {
  const bool is_auto = k.takes_auto && k.def == kAutoInt;
  return {std::string(k.name), std::string(k.doc), is_auto ? "auto" : std::to_string(k.def),
          fmt::format("{}..{}{}", k.lo, k.hi, k.takes_auto ? " or auto" : "")};
}

UnitKey key_entry(const FlagKey& k) {
  return {std::string(k.name), std::string(k.doc), on_off(k.def), "on or off"};
}

UnitKey key_entry(const ChoiceKey& k) {
  return {std::string(k.name), std::string(k.doc), std::string(k.def),
          fmt::format("{}", fmt::join(k.choices(), "|"))};
}

UnitKey key_entry(const RealKey& k) {
  return {std::string(k.name), std::string(k.doc), "none",
          fmt::format("{} <= x < {}, or none", k.lo, k.hi)};
}

std::vector<UnitKey> common_keys() {
  using K = CommonKeyTable;
  return key_list(K::in, K::out, K::skip, K::buffer, K::tables);
}

CommonKeys read_common_keys(const KeyReader& keys) {
  CommonKeys c;
  using K = CommonKeyTable;
  c.in = keys.read(K::in);
  c.out = keys.read(K::out);
  // A format without a fraction bit cannot carry a highlight: uq1.0 holds 0 and 1 only (its
  // input rounding alone is a whole-range error), so it is refused rather than reported.
  for (const auto& [key, f] : {std::pair<const char*, QFormat>{"in", c.in}, {"out", c.out}}) {
    if (f.frac_bits < 1 || f.raw_one() == 0)
      // refusal: keys.fraction_bit
      throw std::invalid_argument(
          fmt::format("key '{}' = '{}': needs at least one fraction bit and must represent 1.0",
                      key, f.name()));
  }
  c.skip = keys.read(K::skip);
  c.buffer = keys.read(K::buffer);
  c.tables_ram = keys.read(K::tables) == "ram";
  return c;
}

}  // namespace glint
