// pow's datapath as Verilog-2005 (`glint rtl`): pow.cpp's stage layout, register for register.
#pragma once

#include <string>
#include <vector>

#include "units/pow/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

std::string pow_rtl(const hdl::DatapathPorts& ports, const std::vector<PowUnit>& groups,
                    const StageLayout& layout);

}  // namespace glint
