#include "cli/synth_sta.h"

#include <fmt/format.h>

#include <stdexcept>

namespace glint::cli {

StaPath run_sta(WorkFolder& work, const std::string& liberty, const std::string& netlist,
                const std::string& top, const std::string& sdc, double period_ns) {
  const std::string sdc_file = work.file(top + ".sdc"), script = work.file("sta.tcl");
  const std::string report = work.file("sta.log");
  write_text(sdc_file, sdc);
  write_text(script, fmt::format("read_liberty {{{}}}\nread_verilog {{{}}}\nlink_design {}\n"
                                 "read_sdc {{{}}}\nreport_checks -path_delay max -digits 4\n",
                                 liberty, netlist, top, sdc_file));
  const int status =
      run_tool("sta", {"-no_splash", "-exit", script}, report, work.path(),
               "synth --liberty needs OpenSTA: `sta` is not on PATH (Debian package opensta; "
               ".ci/bootstrap installs it)");
  const std::string text = read_text(report);
  if (status != 0)
    throw std::runtime_error(fmt::format("synth: OpenSTA failed (exit {}):\n{}", status, text));
  return parse_sta_report(text, period_ns);
}

}  // namespace glint::cli
