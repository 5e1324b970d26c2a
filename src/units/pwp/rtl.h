// pwp's datapath as Verilog-2005 (`glint rtl`): pwp.cpp's stage layout, register for register, and
// the coefficient banks that both the Verilog and the cost inventory read.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "units/pwp/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

// Bank j: c_j of every segment of every group, group-major, 2^segments rows a group (the rows a
// group does not use, when its span holds fewer codes, read 0); its width holds every word, in
// two's complement when one is negative.
struct PwpBank {
  std::vector<std::int64_t> words;
  int width = 1;
  bool is_signed = false;
};
PwpBank pwp_bank(const std::vector<PwpUnit>& groups, int segments, int j);

std::string pwp_rtl(const hdl::DatapathPorts& ports, const PwpConfig& c,
                    const std::vector<PwpUnit>& groups, const StageLayout& layout);

}  // namespace glint
