// sfu's keys (key_table.h): each declared once; SfuConfig takes its defaults from them. The SFU's
// own datapath (tables, widths, fp32) is the hardware's and has no keys.
#pragma once

#include <vector>

#include "units/key_table.h"

namespace glint {

struct SfuKeys {
  static constexpr FormatKey n{"n", uq(14, 4),
                               "shininess register format (its value then exact in fp32: at "
                               "most 24 bits)"};

  static std::vector<UnitKey> list() { return key_list(n); }
};

}  // namespace glint
