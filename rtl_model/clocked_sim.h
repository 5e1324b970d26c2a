// Clocked mode of the SystemC specular unit: one lane per unit, every register a process on the
// rising clock edge, cycle-accurate to the recurrences of src/timing.h.
//
//   VectorSource -> TauComparator --+--> bypass register --------------------+--> ResultMerge
//                                   |                                        |    (B entries)
//                                   +--> compute unit -----------------------+         |
//                                                                                  Scoreboard
//
// Cycle 0 is the first rising edge after the start of simulation (rtl_common.h); with it the
// clocked model's issue, done and retire cycles, and every TimingStats field, equal TimingEngine's
// for the same skip sequence, the unit's UnitTiming and SinkReady.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "rtl_model/row_stream.h"
#include "timing/timing.h"
#include "units/catalogue.h"

namespace glint {

// The trace file's format: VCD as written, or FST (GTKWave's compressed format, 5-10x smaller and
// faster to open; the VCD is streamed through vcd2fst, Debian package gtkwave).
enum class TraceFormat {
  kByExtension,  // FST when the path ends in ".fst", VCD otherwise (so `--vcd out.fst` gives FST)
  kVcd,
  kFst,
};

class OutputSet;
class OutputFile;

// A trace's files as outputs of the caller's OutputSet (output_set.h), made by
// declare_trace_outputs: the trace (a temporary for a VCD, standard output for "-", or a private
// folder vcd2fst writes an FST into) and the GTKWave save file beside it.
struct TraceOutputs {
  std::string path;  // as given
  bool fst = false;
  OutputFile* trace = nullptr;
  OutputFile* save = nullptr;  // null when the trace goes to standard output
};

// Declares the trace at `path` and its save file (same name, .gtkw: rtl::TraceControl::gtkw_path)
// in `outputs`, named `option` ("--vcd") in messages: checked, and created, now. "-" is standard
// output (a VCD without a save file; an FST needs a file: OutputError).
TraceOutputs declare_trace_outputs(OutputSet& outputs, const std::string& path, TraceFormat format,
                                   const std::string& option);

struct ClockedOptions {
  // Trace output (empty: none), VCD or FST (trace_format). A GTKWave save file is written beside
  // it (same name, .gtkw). run_clocked declares both in an OutputSet of its own and commits them at
  // the end of a successful run.
  std::string vcd_path;
  TraceFormat trace_format = TraceFormat::kByExtension;
  // Instead of vcd_path: the trace goes into outputs the caller declared (declare_trace_outputs),
  // and run_clocked only writes them; the caller commits them with its other outputs, so that all
  // are written or none.
  const TraceOutputs* trace_outputs = nullptr;
  // VCD window of vector indices: tracing starts in the cycle the first lane's source presents
  // vector vcd_first and stops one cycle after every lane retired vector vcd_last (or its last).
  std::uint64_t vcd_first = 0, vcd_last = std::numeric_limits<std::uint64_t>::max();
  SinkReady sink;
};

struct LaneOutput {
  std::size_t lane;
  const VectorRow& row;  // valid during the callback only
  std::int64_t t_raw;
  bool skipped;
  std::int64_t out_raw;
  ResultTiming timing;
};

// Diagnostics of a run (optional out-parameter of run_clocked).
struct ClockedRunInfo {
  std::vector<std::string> labels;         // per lane: VCD scope name (unit name, or name_k)
  std::vector<std::uint64_t> mismatches;   // per lane: results differing from the datapath
  std::vector<std::size_t> max_occupancy;  // per lane: merge-buffer entries used at most
  std::uint64_t sim_cycles = 0;            // rising edges simulated
  std::string vcd_path, gtkw_path;         // written files (empty without VCD)
  bool fst = false;                        // vcd_path is an FST file
  std::uint64_t vcd_start_ns = 0;          // simulation time of the first VCD dump
  std::vector<std::string> traced;         // hierarchical names of the traced signals
};

// Elaborates one lane per unit (only the given units), runs until every lane's stream is drained
// and retired, then returns per-lane TimingStats (filled as TimingEngine fills them). `on_result`
// (may be empty) sees every retired result in stream order per lane. Throws what the streams or the
// callback throw, std::invalid_argument for bad options, std::logic_error if a result differs from
// the datapath (a model bug) or if SystemC has already elaborated in this process (SystemC allows
// one elaboration per process).
std::vector<TimingStats> run_clocked(const std::vector<const SpecularUnit*>& units,
                                     const SlotMap& slots,
                                     const std::function<std::unique_ptr<RowStream>()>& open_stream,
                                     const ClockedOptions& options,
                                     const std::function<void(const LaneOutput&)>& on_result,
                                     ClockedRunInfo* info = nullptr);

}  // namespace glint
