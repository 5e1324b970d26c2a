// lut's keys (key_table.h): each declared once; LutConfig takes its defaults from them.
#pragma once

#include <vector>

#include "units/key_table.h"

namespace glint {

struct LutKeys {
  static constexpr IntKey bits{"bits", 6, 1, 16, "table address bits (2^b + 1 entries)"};
  static constexpr IntKey table_frac{
      "table_frac", kAutoInt, 0, 40, "table entry fraction bits (auto: out + 2)", true};

  static std::vector<UnitKey> list() { return key_list(bits, table_frac); }
};

}  // namespace glint
