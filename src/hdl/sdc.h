// The timing constraints of a lane (SDC, Synopsys Design Constraints as OpenSTA and most tools
// read them), written by `glint rtl` beside the Verilog and used by `glint synth` for OpenSTA.
#pragma once

#include <string>

#include "hdl/lane.h"

namespace glint::hdl {

// The default clock period, in ns: 100 MHz, well above what a lane reaches at OSU 0.18 um, so
// that the reported slack is positive and the critical path reads as period - slack.
inline constexpr double kDefaultClockPeriodNs = 10.0;

// The constraints of glint_<unit>_lane: one clock `clk` of `period_ns`; every other input
// arrives, and every output is taken, at that clock's edge with no external delay, as if the
// neighbouring stages were registers of the same clock. A path through the lane's ports (the
// comparator from in_t to in_ready, the merge buffer's flow-through head to out_result) then has
// the whole period, as a register-to-register path does.
std::string lane_sdc(const LaneParams& p, double period_ns);

}  // namespace glint::hdl
