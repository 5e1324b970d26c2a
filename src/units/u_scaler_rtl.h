// The u scaler (units/u_scaler.h) in Verilog, shared by hast's and horner's generators.
#pragma once

#include <string>
#include <vector>

#include "hdl/verilog.h"
#include "units/u_scaler.h"

namespace glint {

// Combinational u = min(1, round((min(t, 1) - root) k)), 0 at t <= root, as UScaler::apply: the
// wire `scaler_u` (fh + 1 bits) from the datapath's position 0 (in_t, in_group), with each group's
// root and k read from its built UScaler.
// loaded: root and k are per-material (tables=ram makes them loadable registers); false for a
// scaler that is the same for every material by construction (horner's full domain: root 0,
// k = 1, constants whatever the tables).
std::string u_scaler_rtl(const hdl::DatapathPorts& p, const std::vector<const UScaler*>& groups,
                         const QFormat& in, int fh, bool loaded = true);

}  // namespace glint
