// Energy at a real node (issue 26, item 3): one energy per toggle per part kind, derived from the
// library's internal_power tables and pin capacitances (src/cost/energy_weights.py writes
// energy_osu018.h), and how many bits of each part of a lane's inventory switch.
//
// The model, per part of the inventory (cost/builder.h places them, each in its stage):
//   register bit   register_bit per data toggle (the staged values': eval/activity.h), and
//                  clock_bit per bit per cycle it is clocked (every cycle, but for the cycles clock
//                  gating stops);
//   datapath part  its switching bits (part_switching) x the toggle fraction of the registers
//                  feeding its stage x the kind's weight: each net of the part is assumed to toggle
//                  as often as its inputs do (no glitches, no carry ripple beyond one bit: what
//                  the scale factors below absorb once fitted);
//   leakage        the lane's area at the node x leakage_nw_per_um2 x cycles x the clock period.
// The scale factors are fitted to a gate-level reference (EnergyScale, below).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cost/cost_model.h"

namespace glint {

// pJ per toggle (per cycle for clock_bit); written by energy_weights.py, then scaled.
struct EnergyWeights {
  std::string node;
  double voltage = 0, load_pf = 0, slew_ns = 0;  // the operating point the tables were read at
  double register_bit = 0;                       // a flip-flop's data toggle
  double clock_bit = 0;                          // a flip-flop clocked for one cycle
  double adder_bit = 0;       // one bit of an adder (or a divider row's subtractor)
  double multiplier_bit = 0;  // one partial-product bit of a multiplier
  double comparator_bit = 0;  // one bit of a comparator
  double mux_bit = 0;         // one 2:1 mux bit (muxes, shifter levels, a divider's restore)
  double table_bit = 0;       // one decision node of a table read's path
  double gate = 0;            // one glue gate (merge-buffer selects, leading-one chains)
  double leakage_nw_per_um2 = 0;
};

// A factor per part kind on the library's first-principles weights, fitted against the gate-level
// reference (tests/calibration/power_osu018.json, OpenSTA's report_power on the mapped lanes) by
// tests/calibration/energy_fit.py, which writes them to cost/energy_fit_osu018.h with their
// residuals. The defaults, 1, are the library's weights unfitted.
struct EnergyScale {
  double register_bit = 1, clock_bit = 1, adder_bit = 1, multiplier_bit = 1, comparator_bit = 1,
         mux_bit = 1, table_bit = 1, gate = 1, leakage = 1;
};
const EnergyScale& energy_scale();

// The scaled weights of the node of that name, or nullptr (a node without energy weights).
const EnergyWeights* find_energy(const std::string& node);

// A datapath part's switching: `bits` of weight `pj_per_bit` switch when its inputs toggle once
// each (0 bits for registers: their toggles are counted, not estimated). Per kind:
//   adder, comparator   width_a bits;       multiplier   width_a x width_b partial products;
//   divider             rows x (divisor + 1) subtractor bits and as many restore mux bits;
//   mux                 width x (inputs - 1) 2:1 mux bits (the whole tree sees its inputs);
//   shifter             width x levels mux bits;  lzd, gates   width_a gates;
//   table               word bits x log2(entries) decision nodes, per bank: the read's path
//                       (a RAM's storage is clocked register bits: Primitive::held_bits).
// All times `count`.
struct PartSwitching {
  double bits = 0;
  double pj_per_bit = 0;
  double pj() const { return bits * pj_per_bit; }
};
PartSwitching part_switching(const Primitive& p, const EnergyWeights& w);

// The datapath's energy by the kind of weight it is counted with, so that a gate-level fit can
// tell tables from multipliers (tests/calibration/energy_fit.py): a shifter's levels and a
// divider's restores are mux bits, its subtractors adder bits, leading-one chains glue gates.
enum class SwitchKind : std::uint8_t { kAdder, kMultiplier, kComparator, kMux, kTable, kGate };
inline constexpr std::size_t kSwitchKinds = 6;
const char* to_string(SwitchKind k);  // "adder", "multiplier", "comparator", "mux", "table", "gate"
using KindArray = std::array<double, kSwitchKinds>;  // a figure per SwitchKind
// The part's switching bits (part_switching's) split by those kinds: a divider's are adder and
// mux bits alike. Times kind_weights(w), kind by kind, they make part_switching's pJ.
KindArray part_switching_bits(const Primitive& p);
KindArray kind_weights(const EnergyWeights& w);

}  // namespace glint
