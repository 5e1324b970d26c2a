// What `glint synth --liberty FILE` needs from a Liberty cell library: the names of its
// sequential cells, so that the flip-flops of a mapped netlist are counted by cell name, and its
// smallest 2-input NAND, the unit of NAND2 equivalents, and its smallest buffer.
#pragma once

#include <set>
#include <string>
#include <string_view>

namespace glint {

// The cells of `text` whose group holds an ff, latch, ff_bank or latch_bank group: every
// `cell ( NAME )` (NAME optionally quoted) up to the next one. A scanner, not std::regex:
// libstdc++'s regex recurses once per character a `\s*` matches, and a library with a long run of
// blanks after `cell` overflowed the stack (SIGSEGV at ~100 000).
std::set<std::string> liberty_registers(std::string_view text);

// The library's smallest combinational cell whose function is a 2-input NAND (!(A B), !(A&B),
// (A B)' ...) and its area; an empty cell when it has none.
struct Nand2 {
  std::string cell;
  double area = 0;
};
Nand2 liberty_nand2(std::string_view text);

// The library's smallest buffer: a combinational cell with one input pin whose output's function
// is that pin, with delay tables (cell_rise or intrinsic_rise). abc buffers high fan-out nets with
// it (cmd_synth.cpp); "" when the library has none.
std::string liberty_buffer(std::string_view text);

}  // namespace glint
