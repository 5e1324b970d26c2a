// The lane around a unit's datapath, in Verilog-2005, and its self-checking testbench: the
// hardware of glint's timing model (src/timing/timing.h) for one unit, cycle for cycle.
//
//   in (valid/ready) -> tau comparator (per-slot threshold ROM, Källberg & Larsson 2014 eq.5)
//        -> skipped: bypass register (done at issue + 1)
//        -> computed: the unit's datapath (position 0 at issue, result at issue + 1 + L)
//        -> in-order merge buffer (B entries, B credits) -> out (valid/ready)
//
// The recurrences it implements (timing.h): a request issues at edge a when in_valid, a credit is
// free (fewer than B requests in flight; a credit returned by a retire at edge r is usable at edge
// r + 1), and, unless skipped, the datapath accepted none in the last II - 1 edges; a skipped
// result can retire from edge a + 1, a computed one from a + 1 + L; the sink retires in order, at
// most one per edge, when out_ready. The merge buffer is flow-through: a result can leave at the
// edge it arrives.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fixed/fixed_point.h"
#include "hdl/verilog.h"

namespace glint::hdl {

struct LaneParams {
  std::string unit;       // module names: glint_<unit>_lane, glint_<unit>_datapath
  std::string spec;       // the unit's canonical SPEC, for the header comment
  std::string generator;  // "glint x.y.z", for the header comment
  QFormat in, out;
  int latency = 1;                      // L
  int ii = 1;                           // initiation interval of the datapath
  int buffer = 4;                       // B: merge-buffer entries and credits
  bool comparator = true;               // skip=on
  std::vector<std::int64_t> threshold;  // per slot: skip when t <= threshold (-1: never)
  std::vector<std::uint32_t> group;     // per slot: its datapath group
  std::vector<std::string> slot_names;  // per slot, for comments
  std::size_t groups = 1;
  // tables=ram: the threshold and group tables, and every per-group table of the datapath, are
  // register arrays with a write port (verilog.h, RamTables). `ram` lists them all with their
  // selects and the port's widths (the generator elaborates once to learn them).
  bool tables_ram = false;
  RamTables ram;
};

int slot_bits(const LaneParams& p);
int group_bits(const LaneParams& p);

// The lane module glint_<unit>_lane, which instantiates glint_<unit>_datapath (written by the
// unit). Ports: clk, rst (synchronous, active high), in_valid/in_ready/in_t/in_slot,
// out_valid/out_ready/out_result/out_skipped.
// tables=ram: the lane's own tables are recorded in `ram` (selects from ram->next_select()), whose
// widths must be the port's; the header comment lists p.ram's tables.
std::string lane_module(const LaneParams& p, RamTables* ram = nullptr);

// One request of the testbench and what glint's C++ model says of it.
struct TbVector {
  std::int64_t t = 0;
  std::uint32_t slot = 0;
  bool skipped = false;
  std::int64_t result = 0;
  std::uint64_t issue = 0;   // a_i: the edge it must be accepted at
  std::uint64_t retire = 0;  // r_i: the edge it must leave at
};

// The sink's ready pattern: SinkReady (timing.h) as Verilog, ready in cycle c when the splitmix64
// hash of (seed, c) is below the probability.
struct TbSink {
  double probability = 1.0;
  std::uint64_t seed = 0;
};

// The testbench module glint_<unit>_tb: drives the requests of `vectors_file` (readmemh; the path
// may be overridden by +vectors=FILE), one offered per cycle as the source of the timing model
// always has the next one, the sink's ready pattern, and checks every result, its skip flag, the
// edge it is accepted at and the edge it leaves at. Prints "PASS <n> results" or the first
// mismatches and "FAIL"; ends with $finish (status 0) or $fatal (non-zero).
std::string testbench_module(const LaneParams& p, const TbSink& sink, std::size_t count,
                             const std::string& vectors_file, const std::string& cfg_file = "");
// tables=ram: the writes the testbench makes before the stream, three hex words a line (select,
// address, data: every entry of every table of p.ram), read with $readmemh from `cfg_file` (or
// +cfg=FILE). Empty for ROM lanes.
std::string testbench_writes(const LaneParams& p);
std::size_t testbench_write_count(const LaneParams& p);
// The vector file it reads: six hex words a request (t, slot, skipped, result, issue, retire).
std::string testbench_vectors(const LaneParams& p, const std::vector<TbVector>& v);

}  // namespace glint::hdl
