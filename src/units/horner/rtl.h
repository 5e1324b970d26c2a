// horner's datapath as Verilog-2005 (`glint rtl`): horner.cpp's stage layout, register for
// register.
#pragma once

#include <string>
#include <vector>

#include "units/horner/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

std::string horner_rtl(const hdl::DatapathPorts& ports, const std::vector<HornerUnit>& groups,
                       const StageLayout& layout);

}  // namespace glint
