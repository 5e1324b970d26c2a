// Static timing of a library-mapped lane: OpenSTA (Debian package opensta, the `sta` program) on
// Yosys' netlist with the lane's SDC (hdl/sdc.h), read back into the worst setup path.
#pragma once

#include <string>

#include "cli/external_tool.h"
#include "cost/sta_report.h"

namespace glint::cli {

// Runs OpenSTA on `netlist` (structural Verilog of library cells, top module `top`) with the
// library `liberty` and the constraints `sdc`, in `work`.
StaPath run_sta(WorkFolder& work, const std::string& liberty, const std::string& netlist,
                const std::string& top, const std::string& sdc, double period_ns);

}  // namespace glint::cli
