// What every unit's Verilog generator (src/units/<unit>/rtl.cpp) shares about its stage layout:
// each register of stages() becomes a Verilog register named <stage>_<register>, declared at its
// format's width, so the generated pipeline has the layout's stages and registers by name.
#pragma once

#include <string>

#include "units/stages.h"

namespace glint {

// "<stage>_<register>", e.g. "lookup_node_lo".
std::string rtl_reg(const Stage& s, std::size_t r);
// The stage's heading (its name, positions and `what`) and its registers' declarations.
std::string rtl_stage_registers(const Stage& s, const std::string& what);
// The layout's stage called `name` (std::logic_error if there is none: a generator out of step
// with its own layout).
const Stage& rtl_stage(const StageLayout& layout, const std::string& name);

}  // namespace glint
