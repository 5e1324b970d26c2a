// parse_sta_report (cost/sta_report.h): OpenSTA's worst-path report as `glint synth --liberty`
// reads it, on reports of the shape OpenSTA 2019 prints (the start, end, arrival, setup and
// slack lines), and the reports it must refuse: an error line, or a line missing.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "cost/sta_report.h"

namespace {

using glint::parse_sta_report;

// Cut from a real run (glint synth lut --liberty osu018): the lines the parser reads and some it
// must skip.
const std::string kRegisterPath =
    R"(Startpoint: datapath.lookup_node_hi[1]\\DFFPOSX1 (rising edge-triggered flip-flop clocked by clk)
Endpoint: datapath.interp_result[0]\\DFFPOSX1 (rising edge-triggered flip-flop clocked by clk)
Path Group: clk
Path Type: max

    Delay      Time   Description
-------------------------------------------------------------
   0.0000    0.0000   clock clk (rise edge)
   0.2470    0.2470 v datapath.lookup_node_hi[1]\\DFFPOSX1/Q (DFFPOSX1)
   0.1590    6.9530 v datapath.interp_result[0]\\DFFPOSX1/D (DFFPOSX1)
             6.9530   data arrival time

  10.0000   10.0000   clock clk (rise edge)
  -0.1570    9.8430   library setup time
             9.8430   data required time
-------------------------------------------------------------
             9.8430   data required time
            -6.9530   data arrival time
-------------------------------------------------------------
             2.8900   slack (MET)
)";

TEST(StaReport, RegisterToRegister) {
  const glint::StaPath p = parse_sta_report(kRegisterPath, 10);
  EXPECT_EQ(p.start.name, "datapath.lookup_node_hi[1]");
  EXPECT_EQ(p.start.kind, "register");
  EXPECT_EQ(p.end.name, "datapath.interp_result[0]");
  EXPECT_DOUBLE_EQ(p.arrival_ns, 6.953);  // the first arrival line, not the subtraction's
  EXPECT_DOUBLE_EQ(p.setup_ns, 0.157);
  EXPECT_DOUBLE_EQ(p.slack_ns, 2.89);
  EXPECT_DOUBLE_EQ(p.min_period_ns(), 7.11);
}

TEST(StaReport, PortsAndAViolatedClock) {
  const std::string text = R"(Startpoint: in_t[3] (input port clocked by clk)
Endpoint: out_result[0] (output port clocked by clk)
             4.5000   data arrival time
   2.0000    2.0000   clock clk (rise edge)
  -0.0000    2.0000   output external delay
            -2.5000   slack (VIOLATED)
)";
  const glint::StaPath p = parse_sta_report(text, 2);
  EXPECT_EQ(p.start.kind, "input port");
  EXPECT_EQ(p.start.name, "in_t[3]");
  EXPECT_EQ(p.end.kind, "output port");
  EXPECT_DOUBLE_EQ(p.setup_ns, 0);
  EXPECT_DOUBLE_EQ(p.min_period_ns(), 4.5);
}

TEST(StaReport, AnErrorOrAMissingLineIsRefused) {
  EXPECT_THROW(parse_sta_report("Error: net.v, line 3 syntax error\n" + kRegisterPath, 10),
               std::runtime_error);
  EXPECT_THROW(parse_sta_report("No paths found.\n", 10), std::runtime_error);
  for (const char* line : {"Startpoint:", "Endpoint:", "data arrival time", "slack ("}) {
    std::string cut = kRegisterPath;
    for (std::size_t at = cut.find(line); at != std::string::npos; at = cut.find(line))
      cut.erase(at, cut.find('\n', at) - at);
    try {
      parse_sta_report(cut, 10);
      ADD_FAILURE() << "a report without '" << line << "' was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("no '"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
