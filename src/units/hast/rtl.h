// hast's datapath as Verilog-2005 (`glint rtl`): hast.cpp's stage layout, register for register.
#pragma once

#include <string>
#include <vector>

#include "units/hast/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

std::string hast_rtl(const hdl::DatapathPorts& ports, const HastConfig& c,
                     const std::vector<HastUnit>& groups, const StageLayout& layout);

}  // namespace glint
