#include "eval/chip_report.h"

#include <fmt/format.h>

namespace glint {

nlohmann::json chip_json(const Chip& chip, const SlotMap& slots) {
  const bool capacity = chip.materials > 0 || chip.slots > 0;
  return {{"spec", chip.spec()},
          {"given", chip.given},
          {"tables", chip.ram ? "ram" : "rom"},
          {"materials", chip.materials > 0 ? chip.materials : slots.groups.size()},
          {"slots", chip.slots > 0 ? chip.slots : slots.params.size()},
          {"sized_to", capacity ? "capacity" : "stream"},
          {"colour_stage", false}};
}

std::string chip_line(const nlohmann::json& chip) {
  const auto m = chip.at("materials").get<std::size_t>();
  const auto s = chip.at("slots").get<std::size_t>();
  const std::string entries =
      fmt::format("{} material{} and {} threshold{}", m, m == 1 ? "" : "s", s, s == 1 ? "" : "s");
  const bool ram = chip.at("tables") == "ram";
  const std::string what =
      ram ? fmt::format("loadable tables of {}", entries)
          : fmt::format("ROMs of this input's {} (--chip ram: loaded at run time)", entries);
  return fmt::format("chip: {}{}: {}; scalar out, colour multiply outside\n",
                     chip.at("spec").get<std::string>(),
                     chip.at("given").get<bool>() ? "" : " (default)", what);
}

}  // namespace glint
