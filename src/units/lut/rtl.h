// lut's datapath as Verilog-2005 (`glint rtl`): lut.cpp's stage layout, register for register.
#pragma once

#include <string>
#include <vector>

#include "units/lut/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

std::string lut_rtl(const hdl::DatapathPorts& ports, const LutConfig& c,
                    const std::vector<LutUnit>& groups, const StageLayout& layout);

}  // namespace glint
