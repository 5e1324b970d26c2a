// The chip a lane is built on: where its per-material tables come from and how many entries it
// holds. Every command states it (report headers, JSON) and prices, simulates and writes the lane
// on it, so that an answer never rests on an assumption the output does not name.
//
//   rom   Every per-material table (the comparator's thresholds, n, spans, coefficients, the t^n
//         and log2/exp2 tables) is a case ROM of the stream's materials, fixed at synthesis: a
//         unit built for known scenes, as the papers' units are. The default.
//   ram   The tables are registers with a write port that the driver loads when it loads a
//         material, as a GPU does. `materials=M` gives every per-material table M entries and
//         `slots=S` the comparator S thresholds (each, when not given, the stream's count); a
//         chip of given capacity must take any shininess, so n registers are the key's whole
//         format.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "units/unit.h"

namespace glint {

struct Chip {
  bool ram = false;
  std::size_t materials = 0;  // ram: entries of every per-material table (0: the stream's groups)
  std::size_t slots = 0;      // ram: comparator thresholds (0: the stream's slots)
  bool given = false;         // chosen by the user (--chip), not the default

  // "rom", "ram", "ram:materials=16,slots=64": what --chip takes back.
  std::string spec() const;
};

// Parses --chip's value. Throws std::invalid_argument with a message naming the key and value.
Chip parse_chip(const std::string& text);

// The specs as lanes of `chip`: on a ram chip every spec without a tables key gets tables=ram, and
// one that asks for tables=rom is refused (std::invalid_argument naming the spec and the chip);
// on the default chip a spec's own tables=ram stands (that lane loads its tables), on a rom chip
// the user chose it is refused the same way.
std::vector<UnitSpec> specs_on_chip(std::vector<UnitSpec> specs, const Chip& chip);

}  // namespace glint
