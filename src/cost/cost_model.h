// Hardware cost proxies of a specular unit: area (gate equivalents), critical path (gate delays of
// the slowest pipeline stage) and an energy proxy (operations executed per request), from the
// unit's datapath and widths. `glint sim` prints them per unit.
//
// These are PROXIES for comparing architectures, not synthesis results. Every constant below is a
// textbook / standard-cell-datasheet figure; they are to be calibrated against Yosys synthesis of
// the same datapaths later (the formulas stay, the constants move).
//
// ---- Area: gate equivalents (GE, 1 GE = one NAND2) --------------------------------------------
// Sources: cell areas of a typical 45 nm standard-cell library relative to its NAND2_X1 (the
// Nangate FreePDK45 Open Cell Library datasheet, approximate: NAND2_X1 0.80 um^2, FA_X1 ~4.3-4.9,
// DFF_X1 ~4.5, DLH_X1 ~2.7, MUX2_X1 ~1.9, AND2_X1 ~1.1 um^2) and the usual textbook ranges (Weste
// & Harris, "CMOS VLSI Design": full adder 5-7 GE, DFF 4-6 GE, 2:1 mux ~2.3 GE, ROM bit 0.25-0.5
// GE). Rounded, not exact library values: the Yosys calibration replaces them.
//
//   adder / subtractor, W bits     W fa_ge                  ripple/prefix: ~W full adders
//   multiplier, A x B bits         A B (fa_ge + and2_ge)    array/Wallace: A B ANDs + ~A B FAs
//   divider, R rows x D bits       R (D + 1) (fa_ge + mux2_ge)
//                                  restoring array, one controlled subtractor row per quotient
//                                  bit built in hardware: R = all quotient bits when pipelined,
//                                  R = 1 when iterative (its state registers are listed apart)
//   comparator, W bits             W cmp_bit_ge             a subtractor's carry chain
//   register, W bits               W dff_ge
//   mux, W bits x K inputs         W (K - 1) mux2_ge
//   barrel shifter, W x S levels   W S mux2_ge              S = shift-amount bits
//   leading-zero detector, W bits  W lzd_bit_ge
//   table, E entries x W bits      ROM (fixed function):  E W rom_bit_ge
//                                  per-slot storage (written when materials load, `where` says
//                                  "per slot"): W (E latch_ge + (E - 1) mux2_ge), a latch array and
//                                  its read-mux tree. Banks behind one read port (the lut's table
//                                  per slot: the slot id is the high address) count as one table
//                                  of count x entries; banks read in different stages (horner's
//                                  coefficient per stage) have a tree each. Tables read at i and
//                                  i + 1 (interpolation) are banked odd/even: the second read costs
//                                  no extra storage or mux tree. A latch array is what a standard-
//                                  cell flow builds without a memory compiler (Yosys maps it to
//                                  flip-flops: dff_ge instead of latch_ge); a compiled SRAM would
//                                  be ~1 GE per bit for large tables.
// Rounding to nearest adds a constant; it is folded into a multiplier's compression tree or an
// adder already there (free), and costs an incrementer (adder) only after a divider or a shifter.
//
// ---- Critical path: gate delays (~FO4) ---------------------------------------------------------
//   adder, comparator, W bits      2 ceil(log2 W) + 2                (prefix adder)
//   multiplier, A x B              1 (AND) + 3 L + adder(A + B)      (L = Dadda/Wallace levels that
//                                                                     reduce min(A, B) rows to two,
//                                                                     ~log1.5(rows / 2); 3 per FA)
//   divider row (D-bit divisor)    adder(D + 1) + 2 (the restore mux)
//   table read, E entries          ceil(log2 E) + 2
//   mux, K inputs                  2 ceil(log2 K);  barrel shifter, S levels: 2 S
//   leading-zero detector, W bits  2 ceil(log2 W)
//   register overhead per stage    3 (clock-to-q + setup)
// A stage's delay is the sum along its path (parallel parts: the slower one) plus the register
// overhead; the critical path is the slowest stage (comparator stage, the unit's stages as
// timing() counts them, the optional colour stage). An iterative divider's stage is its loop: one
// row + the load mux.
//
// ---- Energy proxy ------------------------------------------------------------------------------
// ops_per_computed: operations of one request that reaches the compute unit, by kind: "mul",
// "add", "div_step" (quotient bits: the same for pipelined and iterative), "table_read" (words),
// "shift", "lzd", "compare", "reg_bits" (pipeline register bits written, the iterative divider's
// state once per quotient bit). ops_per_request: every request, skipped or not: the comparator's
// "compare" and "table_read" (tau), and "reg_bits" of the comparator register and the merge-buffer
// entry (the bypass path of a skipped result).
//
// ---- What a lane contains (inventory) ----------------------------------------------------------
// comparator stage (tau table, comparator, register carrying t, the skip flag, the slot id and,
// for hast/horner, the root tau to the u scaler), the unit's stages as its own files describe them
// (src/units/<unit>/<unit>.cpp, beside its datapath), the merge buffer (timing buffer_depth entries
// of the output width and its read mux), and with colour_multiply an RGB stage after the merge
// buffer (3 multipliers out x out, a per-slot colour table, 3 x out register; operand-isolated for
// skipped results). Tables that hold 1.0 (log2 at the last node, t^n at t = 1) or 2.0 (exp2) carry
// the bit for it. cost/builder.h places the parts; units/lane_cost.h puts a lane together.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace glint {

struct Primitive {
  // "adder", "multiplier", "divider", "comparator", "register", "table", "mux", "shifter", "lzd"
  std::string kind;
  // adder/comparator/register/lzd: width_a bits; multiplier: a x b; divider: quotient rows built x
  // divisor bits; table: entries (width_a, per bank) x entry width (width_b); mux: width_a bits x
  // width_b inputs; shifter: width_a data bits x width_b shift-amount bits (levels).
  int width_a = 0, width_b = 0;
  int count = 1;      // identical copies (tables: banks, e.g. one per slot)
  double ge = 0;      // gate equivalents of all `count` of them
  std::string where;  // e.g. "u scaler", "stage 3", "log2 table"

  nlohmann::json to_json() const;
  static Primitive from_json(const nlohmann::json& j);
};

// Delay of one pipeline stage and what lies on its path.
struct StageDelay {
  std::string stage;  // "comparator", "stage 1", ..., "colour"
  double delay = 0;   // gate delays, register overhead included
  std::string path;   // e.g. "table 2 + mul 18x16 + add 33 + reg"
};

struct UnitCost {
  std::vector<Primitive> inventory;
  double area_ge = 0;        // sum of the inventory's ge
  double critical_path = 0;  // gate delays of the slowest stage
  std::string critical_stage;
  std::vector<StageDelay> stages;  // every stage, in pipeline order
  std::map<std::string, double> ops_per_computed;
  std::map<std::string, double> ops_per_request;

  nlohmann::json to_json() const;
  static UnitCost from_json(const nlohmann::json& j);
};

// Area and delay constants (see the header comment for the sources).
struct CostConstants {
  // area, GE
  double nand2_ge = 1.0;     // the unit
  double and2_ge = 1.33;     // partial-product AND (AND2_X1 / NAND2_X1)
  double fa_ge = 6.0;        // full adder, mid of the 5-7 GE range (FA_X1 ~5.3-6.1 GE)
  double dff_ge = 5.7;       // D flip-flop without reset (DFF_X1 ~5.7 GE; textbook 4-6)
  double latch_ge = 3.3;     // level-sensitive latch of a latch-array storage bit (DLH_X1 ~3.3 GE)
  double mux2_ge = 2.33;     // 2:1 mux (MUX2_X1 ~2.3 GE)
  double rom_bit_ge = 0.35;  // synthesised fixed-function ROM, per bit (0.25-0.5 GE)
  double cmp_bit_ge = 3.0;   // magnitude comparator per bit: carry chain, no sum XORs (~fa/2)
  double lzd_bit_ge = 2.0;   // leading-zero detector per input bit (OR/mux tree)
  // delay, gate delays
  double and_delay = 1;       // partial-product AND
  double fa_level_delay = 3;  // one 3:2 compressor level of a multiplier tree
  double mux_delay = 2;       // one 2:1 mux level
  double reg_delay = 3;       // register overhead per stage (clock-to-q + setup)
};
const CostConstants& cost_constants();

// The delay formulas of the header comment (gate delays).
double adder_delay(int width);
double multiplier_delay(int width_a, int width_b);
double divider_row_delay(int divisor_bits);
double table_delay(int entries);
int multiplier_tree_levels(int rows);  // Dadda levels from `rows` partial products to two

// Smallest b with 2^b >= x (0 for x <= 1).
inline int clog2(long long x) {
  int b = 0;
  while ((1LL << b) < x) ++b;
  return b;
}

}  // namespace glint
