#include "cost/sta_report.h"

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>

namespace glint {
namespace {

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// "datapath.lookup_node_hi[1]\\DFFPOSX1 (rising edge-triggered flip-flop clocked by clk)": the
// name up to the cell type Yosys' `rename -wire` appended (after a backslash), and the kind.
PathPoint path_point(const std::string& rest) {
  PathPoint p;
  const std::size_t open = rest.find(" (");
  std::string name = rest.substr(0, open);
  const std::size_t slash = name.find('\\');
  if (slash != std::string::npos) name.erase(slash);
  p.name = name;
  const std::string what = open == std::string::npos ? "" : rest.substr(open);
  if (what.find("input port") != std::string::npos)
    p.kind = "input port";
  else if (what.find("output port") != std::string::npos)
    p.kind = "output port";
  else
    p.kind = "register";
  return p;
}

// The number at the start of a report line ("   6.953    6.953   data arrival time": the first).
double first_number(const std::string& line) {
  std::istringstream in(line);
  double v = 0;
  in >> v;
  if (!in) throw std::runtime_error("synth: OpenSTA's report has no number in: " + line);
  return v;
}

}  // namespace

StaPath parse_sta_report(const std::string& text, double period_ns) {
  StaPath p;
  p.period_ns = period_ns;
  bool start = false, end = false, arrival = false, slack = false;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t first = line.find_first_not_of(' ');
    const std::string t = first == std::string::npos ? "" : line.substr(first);
    if (starts_with(t, "Error")) throw std::runtime_error("synth: OpenSTA: " + t);
    if (starts_with(t, "Startpoint: ")) {
      p.start = path_point(t.substr(12));
      start = true;
    } else if (starts_with(t, "Endpoint: ")) {
      p.end = path_point(t.substr(10));
      end = true;
    } else if (!arrival && t.find("data arrival time") != std::string::npos) {
      p.arrival_ns = first_number(t);
      arrival = true;
    } else if (t.find("library setup time") != std::string::npos) {
      p.setup_ns = -first_number(t);  // printed as the required time's decrement
    } else if (t.find("slack (") != std::string::npos) {
      p.slack_ns = first_number(t);
      slack = true;
    }
  }
  const char* missing = !start     ? "Startpoint"
                        : !end     ? "Endpoint"
                        : !arrival ? "data arrival time"
                        : !slack   ? "slack"
                                   : nullptr;
  if (missing != nullptr)
    throw std::runtime_error(fmt::format(
        "synth: OpenSTA's timing report has no '{}' line (no constrained path, or the report was "
        "cut short)",
        missing));
  return p;
}

}  // namespace glint
