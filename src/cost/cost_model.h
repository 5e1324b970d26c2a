// Hardware cost proxies of a specular unit: area (gate equivalents), critical path (gates of logic
// depth in the slowest pipeline stage) and an energy proxy (operations executed per request), from
// the unit's datapath and widths. `glint sim` prints them per unit.
//
// These are PROXIES for comparing architectures, fitted to Yosys: every constant below comes from
// primitive sweeps through `glint synth`'s generic flow (tests/calibration/primitives.py ->
// primitives.csv, fitted by tests/calibration/fit.py; Yosys 0.23, GE = CMOS transistors / 4 as
// glint synth prices them, flip-flops with enable or reset included). The formulas follow the
// flow's netlists; the residual of each fit is written beside its constant. The whole lane is held
// to the synthesized calibration set (tests/calibration/set.json) by the ctest `calibration`.
//
// ---- Area: gate equivalents (GE, 1 GE = one NAND2 = 4 transistors) ----------------------------
//   adder / subtractor, W bits     W add_bit_ge
//   multiplier, A x B bits         mul_ab_ge A B + mul_sum_ge (A + B), signed: the s* constants;
//                                  by a constant k (a one-entry table): the multiplier of k's
//                                  significant bits x 0.85 ones / bits; by a table of several
//                                  values: one partial-product row per bit any value sets
//   divider, R rows x D bits       R (D + 1) (add_bit_ge + mux2_ge): restoring array, a row per
//                                  quotient bit built in hardware (the RTL's row is a subtractor
//                                  whose borrow is the quotient bit, and the restore mux):
//                                  R = all quotient bits when pipelined, R = 2 when iterative
//                                  (the first quotient bit's row and the row the loop reuses)
//   comparator, W bits             W cmp_bit_ge
//   register, W bits               W dff_ge (a datapath stage register: plain D flip-flops);
//                                  W dffe_ge for the lane's registers, which hold under
//                                  backpressure (a flip-flop with enable: the mux folded in)
//   mux, W bits x K inputs         W (K - 1) mux2_ge
//   barrel shifter, W x S levels   W S shift_bit_ge
//   leading-one detector, W bits   W lzd_bit_ge (the priority chain pow's RTL writes)
//   glue gates                     gate_ge each (two-input AND/OR: the merge buffer's selects)
//   table, E entries x W bits      rom: Yosys folds a case ROM of constants into logic whose size
//                                  depends on what it holds, so a ROM of known contents costs
//                                  rom_node_ge per node of its reduced decision diagram (per
//                                  output bit, address MSB first; constant and single-literal
//                                  functions are wires); one of unknown contents E W rom_bit_ge,
//                                  and nothing for E <= 2 (each bit is a constant or an address
//                                  bit). ram (registers with a write port, loaded when materials
//                                  load: a chip of fixed capacity, --slots): E W ram_bit_ge +
//                                  (E - 1) W ram_mux_ge (the write decoder and the read mux).
//   Per-slot tables (units/lane_cost.cpp, LaneShape::tables_ram): rom when the scene fixes the
//   materials at synthesis (key tables=rom, the default: what `glint rtl` writes as case ROMs
//   with the real contents, the proxy reading the same contents where the unit's cost knows
//   them), ram with key tables=ram or for a chip of fixed capacity (--slots): what `glint rtl`
//   writes with tables=ram, register arrays with one write port; held to seven synthesized
//   tables=ram lanes of the calibration set with these constants (no refit).
//
// ---- Critical path: logic depth in gates (what glint synth measures) ----------------------------
//   adder, W bits                  add_depth0 + add_depth_log log2 W
//   comparator, W bits             cmp_depth0 + cmp_depth_log log2 W
//   multiplier, A x B              mul_depth0 + mul_depth_min log2 min(A, B) + mul_depth_sum
//                                  log2(A + B)
//   divider row (D-bit divisor)    adder(D + 2) + 1 (the subtractor's borrow, the restore mux)
//   table read, E entries          ROM: rom_depth0 + rom_depth_log log2 E; RAM: the read mux
//   mux, K inputs                  1 for K = 2, else mux_depth0 + mux_depth_log ceil(log2 K)
//   barrel shifter, S levels       S;  leading-one detector, W bits: W - 2 (a priority chain)
//   register overhead per stage    0 (depth counts gates from a register to a register)
// A stage's delay is the sum along its path (parallel parts: the slower one); the critical path
// is the slowest stage (comparator stage, the unit's stages as timing() counts them). An iterative
// divider's stage is its loop: one row + the load mux.
//
// ---- Energy proxy ------------------------------------------------------------------------------
// ops_per_computed: operations of one request that reaches the compute unit, by kind: "mul",
// "add", "div_step" (quotient bits: the same for pipelined and iterative), "table_read" (words),
// "shift", "lzd", "compare", "reg_bits" (pipeline register bits written, the iterative divider's
// state once per quotient bit; the tags carried beside the unit). ops_per_request: every request,
// skipped or not: the comparator's "compare" and "table_read" (tau), and "reg_bits" of the
// comparator register, the merge-buffer entry, the bypass tag and the counters.
//
// ---- What a lane contains (inventory) ----------------------------------------------------------
// comparator stage (tau table, comparator, and the register after it: the datapath's input, t and
// the group id), the unit's stages as its own files describe them (src/units/<unit>/<unit>.cpp,
// beside its datapath, following the Verilog src/units/<unit>/rtl.cpp writes), the merge buffer
// as hdl/lane.cpp writes it (buffer_depth entries of the output width with valid and skipped bits,
// their write select and decode, the read mux, a tag and valid bit beside every position of the
// unit, the bypass tag, the credit, issue, head and II counters). No colour stage: the lane
// returns the scalar highlight, as `glint rtl` writes it. Tables that hold 1.0 (log2 at the last
// node, t^n at t = 1) or 2.0 (exp2) carry the bit for it. cost/builder.h places the parts;
// units/lane_cost.h puts a lane together.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace glint {

struct Primitive {
  // "adder", "multiplier", "divider", "comparator", "register", "table", "mux", "shifter", "lzd",
  // "gates" (width_a two-input gates of glue logic)
  std::string kind;
  // adder/comparator/register/lzd: width_a bits; multiplier: a x b; divider: quotient rows built x
  // divisor bits; table: entries (width_a, per bank) x entry width (width_b); mux: width_a bits x
  // width_b inputs; shifter: width_a data bits x width_b shift-amount bits (levels).
  int width_a = 0, width_b = 0;
  int count = 1;      // identical copies (tables: banks, e.g. one per slot)
  double ge = 0;      // gate equivalents of all `count` of them
  std::string where;  // e.g. "u scaler", "stage 3", "log2 table"
  double um2 = 0;     // at the node (cost/node.h); in node_json, not in to_json
  // At the node, neither in to_json: the NodeConstants part it is priced as ("adder", "rom",
  // "dffe", ...) and its um2 before that part's lane_area factor.
  std::string node_part{};
  double um2_unfitted = 0;
  // For the energy (cost/energy.h), neither in to_json: the stage it was placed in (0 the
  // comparator stage, 1.. the unit's, UnitCost::stages.size() the merge buffer and lane control
  // placed after the last), and the flip-flops it holds (registers; a RAM table's storage).
  int stage = 0;
  int held_bits = 0;

  nlohmann::json to_json() const;
  static Primitive from_json(const nlohmann::json& j);
};

// Delay of one pipeline stage and what lies on its path.
struct StageDelay {
  std::string stage;  // "comparator", "stage 1", ...
  double delay = 0;   // gates of logic depth (glint synth's measure)
  std::string path;   // e.g. "table 2 + mul 18x16 + add 33 + reg"
  double ns = 0;      // at the node (cost/node.h), register overhead included
  // At the node: each primitive along the path, its own delay and what it counts in `ns` (less
  // where it overlaps its neighbours: CostBuilder::close).
  struct Part {
    std::string label;
    std::string kind;  // "adder", "multiplier", "comparator", "mux" or "other"
    double ns = 0, counted_ns = 0;
  };
  std::vector<Part> parts;
};

struct UnitCost {
  std::vector<Primitive> inventory;
  double area_ge = 0;        // sum of the inventory's ge
  double critical_path = 0;  // gates of logic depth of the slowest stage
  std::string critical_stage;
  std::vector<StageDelay> stages;  // every stage, in pipeline order
  std::map<std::string, double> ops_per_computed;
  std::map<std::string, double> ops_per_request;
  // At the node (cost/node.h): the lane's own control paths beside the stages, the area in um2,
  // and the slowest of stages and lane paths in ns. Not in to_json (the generic figures every
  // report and golden holds); node_json() has them.
  std::vector<StageDelay> lane_paths;
  std::string node;
  double area_um2 = 0;
  double critical_path_ns = 0;
  std::string critical_path_node;  // the stage or lane path it is

  nlohmann::json to_json() const;
  // {"node", "area_um2", "critical_path_ns", "max_clock_mhz", "critical_path", "paths"}.
  nlohmann::json node_json() const;
  static UnitCost from_json(const nlohmann::json& j);
};

// Area and delay constants, fitted (tests/calibration/fit.py on primitives.csv; "worst" is the
// largest relative residual of the fit over its points).
struct CostConstants {
  // area, GE
  double nand2_ge = 1.0;     // the unit
  double add_bit_ge = 13.0;  // 18 adders/subtractors 8-41 bits; worst +16 % (8 bits), else < 5 %
  double cmp_bit_ge = 8.87;  // 9 comparators 8-41 bits; worst +3 %
  double mul_ab_ge = 12.38;  // unsigned A x B, 19 shapes 8x8..41x41: worst +7 % (16x4)
  double mul_sum_ge = -7.5;
  double smul_ab_ge = 13.06;  // signed, the same 19 shapes: worst +13 % (16x4), else < 6 %
  double smul_sum_ge = -2.7;
  double dff_ge = 4.0;  // $_DFF_P_: 16 transistors (exact: Yosys' own figure)
  double dffe_ge = 7.0;
  double gate_ge = 1.5;   // a two-input AND/OR/ANDNOT: 6 transistors (Yosys' figure, exact)      //
                          // with enable: + the folded 2:1 mux (glint synth's pricing, exact)
  double mux2_ge = 3.28;  // per bit and extra input; 15 muxes 8-32 bits x 2-16; worst +19 %
  double shift_bit_ge = 2.67;  // per bit and level; 12 shifters 12-24 bits x 2-5; worst +16 %
  double lzd_bit_ge = 4.67;    // 3 priority chains 12-24 bits; worst +33 % (12 bits)
  double rom_node_ge = 1.75;   // per decision-diagram node; 24 ROMs of 9-257 entries x 8, 16 bits,
                               // random and t^n contents: median residual 22 %, worst +995 % (a
                               // t^n table that is almost all zeros, which ABC folds further)
  double rom_bit_ge = 0.54;    // unknown contents, per bit (random ROMs of 2-257 entries)
  double ram_bit_ge = 7.77;    // registers with a write port: 20 arrays 1-257 x 8, 16; worst 11 %
  double ram_mux_ge = 2.48;
  // delay, gates
  double add_depth0 = -0.82, add_depth_log = 3.57;   // worst +6 %
  double cmp_depth0 = -2.13, cmp_depth_log = 3.47;   // worst +10 %
  double mul_depth0 = -11.55, mul_depth_min = 4.65,  // 38 multipliers; worst +7 %
      mul_depth_sum = 5.27;
  double mux_depth0 = 2.6, mux_depth_log = 1.3;  // K > 2; K = 2 is one $_MUX_
  double rom_depth0 = 0.0, rom_depth_log = 1.1;  // 3-257 entries: +-2 gates
  double reg_delay = 0;                          // depth starts at a register's output
};
const CostConstants& cost_constants();

// The delay formulas of the header comment (gates of logic depth).
double adder_delay(int width);
double multiplier_delay(int width_a, int width_b);
double divider_row_delay(int divisor_bits);
double comparator_delay(int width);
double table_delay(int entries);
double mux_delay(int inputs);
// GE of a multiplier (signed: two's complement operands, as the RTL declares them).
double multiplier_ge(int width_a, int width_b, bool is_signed);
// GE of a case ROM of these contents (`width` bits a word): decision-diagram nodes x rom_node_ge.
double rom_ge(const std::vector<std::int64_t>& words, int width);

// Smallest b with 2^b >= x (0 for x <= 1).
inline int clog2(long long x) {
  int b = 0;
  while ((1LL << b) < x) ++b;
  return b;
}

}  // namespace glint
