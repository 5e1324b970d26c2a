// The VCD of a clocked run and its GTKWave save file.
//
// SystemC's VCD writer (2.3.4) turns every '.' of a traced name into a $scope level under its own
// root scope "SystemC", so the names top.<unit>.<stage>.<signal> appear as
// SystemC > top > <unit> > <stage> > <signal>. Fixed-point values are traced as raw bits of their
// true width (RawBits), 1-bit handshakes as wires.
//
// The file is written under a temporary name beside the target and renamed by commit(), like every
// glint output: a failed run leaves no VCD behind. It may be opened during the simulation (the VCD
// window): its first dump holds every value at that time, and SystemC writes the value changes of
// each later time step until close().
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_common.h"

namespace glint::rtl {

class TraceControl {
 public:
  using AddTraces = std::function<void(sc_core::sc_trace_file*, std::vector<TracedSignal>&)>;

  // Checks now that the temporary file can be created (throws std::runtime_error otherwise).
  TraceControl(std::string vcd_path, AddTraces add_traces);
  ~TraceControl();  // closes and removes the temporary unless committed

  TraceControl(const TraceControl&) = delete;
  TraceControl& operator=(const TraceControl&) = delete;

  void open();   // creates the trace file and registers every signal (once)
  void close();  // stops tracing (idempotent)
  bool opened() const { return opened_; }
  // Simulation time (ns) at which the file was opened: the window's start.
  std::uint64_t start_ns() const { return start_ns_; }
  const std::vector<TracedSignal>& signals() const { return signals_; }

  // Closes, renames the VCD into place and writes the .gtkw beside it (same name, .gtkw
  // extension): one group per unit (the second name component), raw values in decimal, signed
  // formats as signed.
  void commit();

  const std::string& vcd_path() const { return vcd_path_; }
  std::string gtkw_path() const;

 private:
  std::string vcd_path_;
  std::string temp_base_;  // SystemC appends ".vcd"
  AddTraces add_traces_;
  sc_core::sc_trace_file* tf_ = nullptr;
  bool opened_ = false, committed_ = false;
  std::uint64_t start_ns_ = 0;
  std::vector<TracedSignal> signals_;
};

// The GTKWave save file text for `signals` in `vcd_path` (absolute path recommended), starting the
// view at `start_ns`.
std::string gtkw_text(const std::string& vcd_path, std::uint64_t start_ns,
                      const std::vector<TracedSignal>& signals);

}  // namespace glint::rtl
