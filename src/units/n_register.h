// The n register of the units that hold the shininess in one (pow, schlick), as the scene
// elaborates it: the key's format says how n is quantized; the register is built only as wide as
// the values the scene's datapath groups store need, so that every one of them is held exactly as
// the key's format quantizes it (a narrower register holding the same values computes the same
// results: its low zero bits and high zero bits are wiring). A chip of fixed capacity (--slots)
// must take any shininess: its register is the key's whole format.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "units/common.h"

namespace glint {

struct NRegister {
  QFormat format;         // the key's format: how every n is quantized
  QFormat built;          // the register as built (format itself for a fixed-capacity chip)
  bool fixed = false;     // a chip of fixed capacity: the whole format
  bool exact = true;      // every group's n_q equals the n it stands for
  double max_error = 0;   // the largest |n_q - n|
  std::size_t worst = 0;  // the group where it is
};

// n as the key's format stores it: rounded to nearest even, saturating, and at least one ulp (the
// smallest n the register holds: a zero would make t^0 for pow and sfu, a zero divisor for
// schlick). The caller has refused n <= 0 and n beyond the format.
std::int64_t quantize_n(double n, const QFormat& format);

// raw[g]: group g's stored value in `format`; target[g]: the n it stands for (the material's n,
// or n' for match=).
NRegister elaborate_n_register(const QFormat& format, const std::vector<std::int64_t>& raw,
                               const std::vector<double>& target, bool fixed);

// {"format", "built", "width", "exact", and when not exact "max_abs_error", "at"}; `groups`
// names the groups.
nlohmann::json n_register_json(const NRegister& n, const std::vector<MaterialParams>& groups);

}  // namespace glint
