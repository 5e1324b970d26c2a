// OpenSTA's report of the worst setup path (`report_checks -path_delay max`), read back: what
// `glint synth --liberty` states as the critical path (cli/synth_sta.h runs the tool).
#pragma once

#include <string>

namespace glint {

// One end of a timing path: a register (its name in the RTL, e.g. datapath.interp_result[3], or
// a private cell name where Yosys kept none) or a port of the lane.
struct PathPoint {
  std::string name;
  std::string kind;  // "register", "input port" or "output port"
};

// The worst setup path of the clock.
struct StaPath {
  double period_ns = 0;   // the SDC's clock period
  double slack_ns = 0;    // required - arrival (negative: the period is too short)
  double arrival_ns = 0;  // data arrival at the end point
  double setup_ns = 0;    // the end point's library setup time (0 at an output port)
  PathPoint start, end;
  // The shortest period this path allows, and the fastest clock: the period less the slack.
  double min_period_ns() const { return period_ns - slack_ns; }
};

// OpenSTA's `report_checks -path_delay max` text for a clock of `period_ns`. A report that names
// an error, or lacks the start point, end point, arrival or slack, throws std::runtime_error
// saying which (an exit status of 0 is no proof that the report is whole).
StaPath parse_sta_report(const std::string& text, double period_ns);

}  // namespace glint
