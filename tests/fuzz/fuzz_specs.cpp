// Unit SPEC parsing alone, fast (the units harness builds a unit per input, at tens of inputs per
// second): parse_unit_spec, the unit's name against the catalogue, every key against the unit's
// list (KeyReader) and every key the units share (read_common_keys: formats, skip, buffer), and
// every key's value through each kind of declared key. A spec written back as NAME:k=v,...
// parses to the same spec. std::invalid_argument is a refusal (exit 2); anything else a finding.
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz.h"
#include "units/catalogue.h"
#include "units/keys.h"

namespace glint::fuzz {

namespace {

std::string spec_text(const UnitSpec& spec) {
  std::string out = spec.name;
  char sep = ':';
  for (const auto& [k, v] : spec.keys) {
    out += sep + k + "=" + v;
    sep = ',';
  }
  return out;
}

// Each reader on a key's value, the key declared as each kind of key (units/key_table.h): a
// refusal names the key (invalid_argument), nothing else.
void read_every_way(const KeyReader& keys, const std::string& key) {
  static constexpr std::string_view kWords[] = {"a", "minimax", "width", "none"};
  const auto attempt = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument&) {
    }
  };
  attempt([&] { keys.read(FormatKey{key, uq(1, 15), ""}); });
  attempt([&] { keys.read(IntKey{key, 0, -1000, 1000, "", true}); });
  attempt([&] { keys.read(RealKey{key, 0.0, 1.0, ""}); });
  attempt([&] { keys.read(FlagKey{key, false, ""}); });
  attempt([&] { keys.read(ChoiceKey{key, "a", kWords, ""}); });
}

}  // namespace

int specs(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  UnitSpec spec;
  try {
    spec = parse_unit_spec(text);
  } catch (const std::invalid_argument&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("parse_unit_spec threw something other than invalid_argument: ") + e.what());
  }
  try {
    const UnitSpec again = parse_unit_spec(spec_text(spec));
    if (again.name != spec.name || again.keys != spec.keys) fail("a spec written back differs");
  } catch (const std::invalid_argument& e) {
    fail(std::string("a spec written back does not parse: ") + e.what());
  }
  try {
    const UnitInfo& info = unit_info(spec.name);
    const KeyReader keys(spec, info.keys);
    (void)read_common_keys(keys);
    for (const auto& kv : spec.keys) read_every_way(keys, kv.first);
  } catch (const std::invalid_argument&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("reading the keys threw something other than invalid_argument: ") + e.what());
  }
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(specs)
