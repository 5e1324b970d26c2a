// sfu's datapath as Verilog-2005 (`glint rtl`): sfu.cpp's stage layout, register for register.
#pragma once

#include <string>
#include <vector>

#include "units/sfu/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

std::string sfu_rtl(const hdl::DatapathPorts& ports, const std::vector<SfuUnit>& groups,
                    const StageLayout& layout);

}  // namespace glint
