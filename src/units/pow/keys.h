// pow's keys (key_table.h): each declared once; PowConfig takes its defaults from them.
#pragma once

#include <vector>

#include "units/key_table.h"

namespace glint {

struct PowKeys {
  static constexpr FormatKey n{"n", uq(14, 4), "shininess register format"};
  static constexpr IntKey log_bits{"log_bits", 8, 1, 16,
                                   "log2 table address bits (2^b + 1 entries)"};
  static constexpr IntKey log_frac{"log_frac", 24, 4, 30, "log2 table entry fraction bits"};
  static constexpr IntKey y_frac{"y_frac", 20, 4, 30, "fraction bits of y = n log2 t"};
  static constexpr IntKey exp_bits{"exp_bits", 6, 1, 16, "exp2 table address bits"};
  static constexpr IntKey exp_frac{"exp_frac", 24, 4, 30, "exp2 table entry fraction bits"};

  static std::vector<UnitKey> list() {
    return key_list(n, log_bits, log_frac, y_frac, exp_bits, exp_frac);
  }
};

}  // namespace glint
