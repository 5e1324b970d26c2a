// schlick's datapath as Verilog-2005 (`glint rtl`): schlick.cpp's stage layout, register for
// register, with the pipelined or the iterative divider.
#pragma once

#include <string>
#include <vector>

#include "units/schlick/datapath.h"

namespace glint {
namespace hdl {
struct DatapathPorts;
}

std::string schlick_rtl(const hdl::DatapathPorts& ports, const std::vector<SchlickUnit>& groups,
                        bool iterative, const StageLayout& layout);

}  // namespace glint
