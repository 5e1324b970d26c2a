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
// The files are outputs of an OutputSet (io/output_set.h), declared before the run
// (declare_trace_outputs in clocked_sim.h): the VCD is written into its exclusively created
// temporary beside the target (or to standard output), and renamed into place with the run's other
// outputs when the caller commits them; a failed run leaves no VCD behind. The file may be opened
// during the simulation (the VCD window): its initial $dumpvars, at the opening time, holds every
// value settled in that time step; each later cycle's changes follow until close(), which ends the
// file with its own time.
//
// FST: the same VCD text is streamed through a pipe into Debian's vcd2fst (package gtkwave), which
// runs beside the simulation (on another core) and writes the FST into the output's private
// temporary folder beside the target (0700, a fresh name); commit() waits for it, reads the FST
// back with fst2vcd and compares what it holds with what was written (fst_read_back.h: vcd2fst
// exits 0 on a full disk with the FST cut short), and only then hands the FST to the OutputSet,
// which renames it into place. A failed run kills vcd2fst and the OutputSet
// removes the folder; vcd2fst and its files are registered with signal_cleanup.h, so SIGINT or
// SIGTERM stop it and remove them too: no file, partial or otherwise, is left behind.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/vcd_writer.h"

namespace glint {
struct TraceOutputs;
}

namespace glint::rtl {

class TraceControl {
 public:
  // Registers every traced value with the writer (called once, by open()).
  using AddTraces = std::function<void(VcdWriter&)>;

  // Writes into `outputs` (which must outlive this object); for an FST, starts vcd2fst now
  // (OutputError if it cannot be started).
  TraceControl(const TraceOutputs& outputs, AddTraces add_traces);
  ~TraceControl();  // stops vcd2fst unless committed (the OutputSet removes the files)

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
  // state), waits for vcd2fst (FST) and writes the .gtkw (gtkw_text): every file complete, for the
  // OutputSet to commit. Throws OutputError if the trace could not be written.
  void commit();

  const std::string& vcd_path() const { return vcd_path_; }  // the trace file, VCD or FST
  bool fst() const { return fst_; }
  std::string gtkw_path() const { return gtkw_path(vcd_path_); }
  // The save file of a trace at `path`: `.vcd` / `.fst` replaced by `.gtkw`, else `.gtkw` added.
  static std::string gtkw_path(const std::string& path);

 private:
  class Vcd2Fst;  // the vcd2fst process and its temporary directory

  void initial_dump(std::uint64_t t_ns);
  std::string what() const;  // the output in messages: "--vcd t.vcd" (or "VCD t.vcd")

  std::string vcd_path_;
  bool fst_;
  const TraceOutputs& outputs_;
  std::unique_ptr<Vcd2Fst> vcd2fst_;
  AddTraces add_traces_;
  VcdWriter writer_;
  bool opened_ = false, closed_ = false, committed_ = false;
  bool dump_pending_ = false;
  std::uint64_t start_ns_ = 0;
};

// True when `path` names an FST file (extension ".fst", any case): TraceFormat::kByExtension.
bool is_fst_path(const std::string& path);

// The GTKWave save file (GTKWave 3.3) for `signals` in `dump_path` (VCD or FST; an absolute path
// is recommended), for a trace whose window starts at `start_ns`:
//  - the view: kGtkwViewCycles clock periods from start_ns ([timestart], the zoom of the "*" line
//    computed for the wave pane the [size]/[sst_width]/[signals_width] lines lay out), the primary
//    marker on the window's first rising edge (so the signal pane shows values from the start);
//  - names: every trace aliased ("+{alias} name") to its name below "SystemC.top." with '/'
//    between the levels, stage qualified ("hast/mul2/power"): such an alias shows whatever
//    hier_max_level the user's gtkwaverc sets (Debian's default, 1, cuts the dotted names down to
//    their leaves, ten "t[15:0]" per unit, and would cut a dotted alias the same way);
//  - values: fixed-point signals (frac_bits > 0) as real numbers through GTKWave's fixed-point
//    shift (flag 0x40000000 with "[fpshift_count] frac_bits": raw / 2^frac_bits, signed formats
//    as signed), integers in decimal, 1-bit signals in binary;
//  - one group per unit (the second name component) that starts with the source's t and the
//    sink's result as analog step waves (four rows high), then every signal of the unit in
//    registration order, then a closed subgroup "<unit> raw" with the raw bits of its fixed-point
//    signals in decimal, aliased "<alias>[msb:0] <format>" (e.g. "hast/in/t[15:0] uq1.15").
std::string gtkw_text(const std::string& dump_path, std::uint64_t start_ns,
                      const std::vector<TracedSignal>& signals);

// The save file's view: this many clock periods from the window's start fill the wave pane.
constexpr int kGtkwViewCycles = 40;

}  // namespace glint::rtl
