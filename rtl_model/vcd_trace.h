// The VCD of a clocked run and its GTKWave save file, written by glint's VcdWriter (vcd_writer.h)
// rather than SystemC's (sc_create_vcd_trace_file), which cost ~95% of a traced run.
//
// Every '.' of a traced name opens a $scope level under the root scope "SystemC" (the layout
// SystemC's writer used, kept so the names stay SystemC.top.<unit>.<stage>.<signal>). Fixed-point
// values are raw bits of their true width (RawBits), 1-bit handshakes scalars.
//
// Sampling: the values of cycle c (everything the processes of rising edge c and its delta cycles
// wrote) are read once, at the falling edge that follows (sample_cycle), and written under the
// rising edge's time with the clock's rise; the clock's fall follows at the falling edge's time.
// The reset state (before cycle 0) is read by sample_reset, before the first rising edge.
//
// The file is written under a temporary name beside the target and renamed by commit(), like every
// glint output: a failed run leaves no VCD behind. It may be opened during the simulation (the VCD
// window): its initial $dumpvars, at the opening time, holds every value settled in that time
// step; each later cycle's changes follow until close(), which ends the file with its own time.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/vcd_writer.h"

namespace glint::rtl {

class TraceControl {
 public:
  // Registers every traced value with the writer (called once, by open()).
  using AddTraces = std::function<void(VcdWriter&)>;

  // Creates the temporary file now (throws std::runtime_error if it cannot).
  TraceControl(std::string vcd_path, AddTraces add_traces);
  ~TraceControl();  // closes and removes the temporary unless committed

  TraceControl(const TraceControl&) = delete;
  TraceControl& operator=(const TraceControl&) = delete;

  // Registers every signal and writes the header (once); the initial dump is written by the next
  // sample, with the values of the current time step.
  void open();
  // Ends the file at the current simulation time (idempotent).
  void close();
  bool opened() const { return opened_; }
  bool tracing() const { return opened_ && !closed_; }
  // The values after rising edge `rise_ns` have settled (called at the following falling edge,
  // `fall_ns`).
  void sample_cycle(std::uint64_t rise_ns, std::uint64_t fall_ns);
  // The reset state (time 0) has settled (called once, before the first rising edge).
  void sample_reset();
  // Simulation time (ns) at which the file was opened: the window's start.
  std::uint64_t start_ns() const { return start_ns_; }
  const std::vector<TracedSignal>& signals() const { return writer_.signals(); }

  // Closes (opening first if the window never opened, so the file is a valid VCD of the final
  // state), renames the VCD into place and writes the .gtkw beside it (same name, .gtkw
  // extension): one group per unit (the second name component), raw values in decimal, signed
  // formats as signed. Throws std::runtime_error if the VCD could not be written.
  void commit();

  const std::string& vcd_path() const { return vcd_path_; }
  std::string gtkw_path() const;

 private:
  void initial_dump(std::uint64_t t_ns);

  std::string vcd_path_;
  std::string temp_path_;
  AddTraces add_traces_;
  VcdWriter writer_;
  bool opened_ = false, closed_ = false, committed_ = false;
  bool dump_pending_ = false;
  std::uint64_t start_ns_ = 0;
};

// The GTKWave save file text for `signals` in `vcd_path` (absolute path recommended), starting the
// view at `start_ns`.
std::string gtkw_text(const std::string& vcd_path, std::uint64_t start_ns,
                      const std::vector<TracedSignal>& signals);

}  // namespace glint::rtl
