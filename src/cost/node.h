// The cost proxy at a real node: area in um2 and path delays in ns of the library `glint synth
// --liberty` maps to, from per-part constants measured on primitives mapped to that library and
// timed by OpenSTA (tests/calibration/primitives.py --liberty, fitted by node_fit.py --primitives;
// src/cost/README.md, "At a real node"). GE and gate levels stay the proxy's generic measure; these
// are the same parts priced at the node.
//
// Why per part and not one ns per level: the flow (abc -liberty for the clock period, buffered
// and sized) maps an adder to a carry chain whose delay grows with its width while a
// comparator's stays almost flat, and a register that selects among many words (a RAM read, the
// merge buffer's head) drives every mux of its array through a buffer tree: its delay grows with
// the log of the number of loads.
#pragma once

#include <string>
#include <vector>

namespace glint {

// Delay of one part on a path: c0 + per_x x + per_log2 log2(y) + per_load loads + per_load2
// loads^2, where x, y and the loads are the part's own measures (cost/builder.h, per kind; a
// select's loads are its y: the buffer tree). The load terms are for a flow that leaves such nets
// unbuffered (there a RAM read of 65 x 16 bits took 52 ns, of 257 x 16 788 ns on OSU 0.18 um);
// the built-in node's fit gives them 0.
struct NodeDelay {
  double c0 = 0, per_x = 0, per_log2 = 0, per_load = 0, per_load2 = 0;
  double at(double x, double y, double loads) const;
};

// One kind of part: library um2 per proxy GE, and its delay. lane_area: what a lane's part of
// this kind keeps of that area (abc shares logic across the parts of a lane, which primitives
// mapped alone cannot show; fitted on the calibration lanes: node_fit.py --lanes).
struct NodePart {
  double um2_per_ge = 0;
  NodeDelay delay;
  double lane_area = 1;
};

// What a part counts of its own delay where arithmetic parts follow one another on a path
// (CostBuilder::close): an adder right before a multiplier, and an adder, comparator or select
// after a multiplier (or after such a part). Fitted on the calibration lanes, not the primitives:
// the overlap exists only between parts.
struct NodeOverlap {
  double adder_before_multiplier = 1, adder_after = 1, comparator_after = 1, mux_after = 1;
};

struct NodeConstants {
  std::string name;     // what --node takes: "osu018"
  std::string library;  // what it is, for reports
  // A register-to-register path with nothing between: clock-to-Q and setup (ns).
  double reg_ns = 0;
  // ram: a register array read by a register (the id, the merge buffer's head); ram_computed: by
  // an address computed in the stage (lut's t^n banks).
  NodePart adder, comparator, multiplier, divider, mux, shifter, lzd, gates, rom, ram, ram_computed,
      dff, dffe;
  NodeOverlap overlap;
};

// The name of one of k's parts ("adder", "rom", "dffe", ...), by its address.
std::string node_part_name(const NodeConstants& k, const NodePart& p);

// The built-in node (the only one with constants).
const NodeConstants& node_osu018();
// The node of that name, or nullptr.
const NodeConstants* find_node(const std::string& name);
// Names --node accepts.
std::vector<std::string> node_names();

}  // namespace glint
