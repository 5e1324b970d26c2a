// Verilog-2005 text for `glint rtl`: the pieces every unit's generator shares (literals, case ROMs,
// RAM tables with their write port, pipeline registers, the datapath module's ports), and the lane
// around a unit's datapath (lane.h).
// Plain text building: no unit knowledge here (the hdl layer sees only fixed/), each unit writes
// its own stages in src/units/<unit>/rtl.cpp from its own build objects.
//
// Conventions of the generated code: one clock `clk`, rising edge; every register is written by
// non-blocking assignments in `always @(posedge clk)`; combinational logic is `assign` or
// `always @*` with blocking assignments; signed values are declared `signed` and carried as two's
// complement bit patterns; nothing depends on the simulator's x semantics (every register the
// result depends on is written before it is read).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fixed/fixed_point.h"

namespace glint::hdl {

// Bits to hold 0..n-1 (at least 1: Verilog has no zero-width vectors).
int index_bits(std::uint64_t n);
// Bits to hold the value v >= 0 (at least 1).
int value_bits(std::uint64_t v);

// A sized literal of `width` bits holding the two's-complement bits of v: 16'h8000. Decimal for
// small values (up to 9) to keep the text readable.
std::string lit(int width, std::int64_t v);
// The same as a signed literal (16'sh...): for operands of signed expressions.
std::string slit(int width, std::int64_t v);
// "[w-1:0]" (empty for w == 1 would change the type: always written).
std::string range(int width);
// A fixed-point format in words, for comments: "uq1.15 (16 bits, 15 fraction)".
std::string describe(const QFormat& f);

// A case ROM as a combinational block: `reg [W-1:0] name;` read at `addr` (an expression of
// addr_bits bits). Entries past `words` (and the default) read `fill`. Written one entry a line, so
// a reader sees the real contents, and as `always @*` + `case`, which Yosys recognises as a ROM
// (proc_rom) and Verilator as a constant table.
struct Rom {
  std::string name;
  std::string addr;  // the address expression
  int addr_bits = 1;
  int data_bits = 1;
  bool is_signed = false;
  std::vector<std::int64_t> words;
  std::int64_t fill = 0;
  std::string comment;  // one or more lines, without the leading "// "
};
std::string rom(const Rom& r);

// A value per datapath group, read at `addr` (addr_bits wide): a constant wire when every group
// has the same value (nothing to look up), else a case ROM.
std::string group_table(const std::string& name, const std::string& addr, int addr_bits, int width,
                        const std::vector<std::int64_t>& values, const std::string& what,
                        bool is_signed = false);

// tables=ram: per-slot tables as register arrays with one synchronous write port shared by the
// whole lane. At a rising edge with cfg_we high, entry cfg_addr of the table numbered cfg_sel takes
// cfg_data (its low `width` bits; a table of one entry ignores cfg_addr). The arrays have no reset
// (a material is loaded, not reset); reads are combinational, so a write is seen from the next
// cycle. Selects are numbered in the order the tables are generated: the lane's first (tau, the
// slot's group), then the datapath's.
struct RamTable {
  std::string name;  // the read wire; the array is <name>_mem
  int select = 0;
  int width = 1;
  bool is_signed = false;
  std::vector<std::int64_t> words;  // the contents a testbench loads (entries = words.size())
  std::string what;
};
struct RamTables {
  // The write port's widths, the same for the lane and the datapath module.
  int sel_bits = 1, addr_bits = 1, data_bits = 1;
  std::vector<RamTable> tables;  // in select order
  int next_select() const { return static_cast<int>(tables.size()); }
  // Widths that hold every table's select, address and data.
  void size_port();
};
// Declares table t (select t.select, its address `addr_bits` wide) and its write port, and the
// wire t.name read at `addr`; records it in `tables`.
std::string ram_table(RamTables& tables, RamTable t, const std::string& addr, int addr_bits);
// Only the array <name>_mem and its write port (the caller writes the reads); recorded too.
std::string ram_array(RamTables& tables, RamTable t);
// The write-port lines of a module's port list (cfg_we, ..., cfg_data: each on a new line, the
// caller ends the port before with a comma).
std::string ram_ports(const RamTables& tables);

// `name` (an identifier of `from` bits) as `to` bits: zero- or sign-extended, or its low `to` bits.
// Every operand of the generated arithmetic is sized this way, so that no width is implied
// (verilator -Wall's WIDTH warnings).
std::string ext(const std::string& name, int from, int to, bool is_signed = false);

// `// text` lines (text may hold several lines), indented.
std::string comment(const std::string& text, int indent = 2);

// The ports every datapath module has, so that the lane (lane.h) can instantiate any unit's:
//   input clk; input start (a computed request issues: load position 0);
//   input [WI-1:0] start_t (t in the input format); input [WG-1:0] start_group (its datapath
//   group); output [WO-1:0] result (the result register of position L).
// The module loads position 0 (the compute path's comparator register, "in") from the start_*
// inputs and advances one position per clock; the lane carries valid bits and tags beside it.
struct DatapathPorts {
  std::string module;  // e.g. glint_lut_datapath
  QFormat in, out;
  int group_bits = 1;
  std::size_t groups = 1;  // one: in_group is the constant 0
  int latency = 1;
  // tables=ram: every per-group table is a register array written through cfg_* (the module
  // gets the write port), recorded here; null: case ROMs of the built contents.
  RamTables* ram = nullptr;
};
// A value per datapath group as the lane's storage asks: group_table() above (rom), or a RAM
// table of the same contents (ram: also when every group holds the same value, since another
// material may be loaded).
std::string group_table(const DatapathPorts& p, const std::string& name, const std::string& addr,
                        int width, const std::vector<std::int64_t>& values, const std::string& what,
                        bool is_signed = false);
// The module header with its ports (and `header_comment` above it), and the closing line.
std::string datapath_header(const DatapathPorts& p, const std::string& header_comment);
std::string datapath_footer(const DatapathPorts& p);
// Position 0, the compute path's input register ("in": t as the comparator passed it, and its
// datapath group): `in_t` and `in_group`, loaded when `start`.
std::string datapath_input_stage(const DatapathPorts& p);

}  // namespace glint::hdl
