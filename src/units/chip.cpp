#include "units/chip.h"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>

#include "units/slot_plan.h"

namespace glint {
namespace {

std::size_t parse_count(const std::string& key, const std::string& value) {
  std::size_t v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || v < 1 ||
      v > kMaxSlotCapacity)
    // not from a spec: --chip's value, named by the command line (refuse_chip)
    throw std::invalid_argument(
        fmt::format("key '{}': '{}' is not a count in 1..{}", key, value, kMaxSlotCapacity));
  return v;
}

std::string join(const UnitSpec& spec) {
  std::string s = spec.name;
  for (std::size_t i = 0; i < spec.keys.size(); ++i)
    s += (i == 0 ? ":" : ",") + spec.keys[i].first + "=" + spec.keys[i].second;
  return s;
}

}  // namespace

std::string Chip::spec() const {
  if (!ram) return "rom";
  std::string s = "ram";
  if (materials > 0) s += fmt::format(":materials={}", materials);
  if (slots > 0) s += fmt::format("{}slots={}", materials > 0 ? "," : ":", slots);
  return s;
}

Chip parse_chip(const std::string& text) {
  Chip chip;
  chip.given = true;
  const std::size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  if (kind == "rom") {
    if (colon != std::string::npos)
      // not from a spec: --chip's value, named by the command line (refuse_chip)
      throw std::invalid_argument(
          "rom holds the stream's own materials: materials= and slots= need 'ram'");
    return chip;
  }
  if (kind != "ram")
    // not from a spec: --chip's value, named by the command line (refuse_chip)
    throw std::invalid_argument(
        fmt::format("'{}' is not a chip: 'rom', 'ram' or 'ram:materials=M,slots=S'", kind));
  chip.ram = true;
  if (colon == std::string::npos) return chip;
  const std::string keys = text.substr(colon + 1);
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = keys.find(',', start);
    const std::string item = keys.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    const std::string key = item.substr(0, eq);
    if (eq == std::string::npos)
      // not from a spec: --chip's value, named by the command line (refuse_chip)
      throw std::invalid_argument(
          fmt::format("'{}' is not KEY=VALUE (keys: materials, slots)", item));
    const std::string value = item.substr(eq + 1);
    std::size_t* field = key == "materials" ? &chip.materials
                         : key == "slots"   ? &chip.slots
                                            : nullptr;
    if (field == nullptr)
      // not from a spec: --chip's value, named by the command line (refuse_chip)
      throw std::invalid_argument(fmt::format("unknown key '{}' (keys: materials, slots)", key));
    // not from a spec: --chip's value, named by the command line (refuse_chip)
    if (*field != 0) throw std::invalid_argument(fmt::format("key '{}' given twice", key));
    *field = parse_count(key, value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return chip;
}

std::vector<UnitSpec> specs_on_chip(std::vector<UnitSpec> specs, const Chip& chip) {
  for (UnitSpec& spec : specs) {
    const std::string* tables = nullptr;
    for (const auto& [key, value] : spec.keys)
      if (key == "tables") tables = &value;
    if (tables == nullptr) {
      if (chip.ram) spec.keys.emplace_back("tables", "ram");
      continue;
    }
    // Another value is the unit's own refusal to give (KeyReader names its choices).
    if (*tables != "rom" && *tables != "ram") continue;
    if (chip.given && (*tables == "ram") != chip.ram)
      // not from a spec: --chip's value, named by the command line (refuse_chip)
      throw std::invalid_argument(fmt::format(
          "unit '{}': tables={} contradicts --chip {} (leave tables out: the chip sets it)",
          join(spec), *tables, chip.spec()));
  }
  return specs;
}

}  // namespace glint
