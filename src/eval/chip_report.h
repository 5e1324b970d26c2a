// The chip a run's lanes are built on (units/chip.h), as every report states it: a JSON object
// (the `chip` section of src/eval/sim_report.md) and one line of text for the table headers.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "eval/evaluate.h"
#include "units/chip.h"

namespace glint {

// {"spec", "given", "tables", "materials", "slots", "sized_to", "colour_stage"}: the chip as
// given, and the entries its tables hold for this stream.
nlohmann::json chip_json(const Chip& chip, const SlotMap& slots);

// "chip: rom (default): ... " from chip_json's object: what the tables hold, where the colour
// multiply is, and how to ask for the other chip.
std::string chip_line(const nlohmann::json& chip);

}  // namespace glint
