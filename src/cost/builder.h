// The cost builder every unit describes its hardware with: each primitive it places adds its area
// (gate equivalents), returns its delay as a path segment, and the unit closes each pipeline stage
// with the segments on its path. Operation counts (the energy proxy) are recorded beside.
//
// The lane parts every unit shares (the comparator stage and the merge buffer) are here too; a
// unit's own stages live in its own files (src/units/<unit>/), and units/lane_cost.h puts a whole
// lane together. Constants and formulas: cost/cost_model.h.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cost/cost_model.h"
#include "fixed/fixed_point.h"

namespace glint {

// One element on a stage's path.
struct Seg {
  std::string label;
  double delay = 0;
};

// Two things side by side: the stage waits for the slower.
inline Seg parallel(const Seg& a, const Seg& b) {
  return {"(" + a.label + " || " + b.label + ")", std::max(a.delay, b.delay)};
}

// Things one after the other, as one segment.
inline Seg series(const std::vector<Seg>& segs) {
  Seg out;
  for (const Seg& g : segs) {
    out.label += (out.label.empty() ? "" : " + ") + g.label;
    out.delay += g.delay;
  }
  return out;
}

// Collects the inventory, the stage paths and the operation counts of one lane.
class CostBuilder {
 public:
  CostBuilder() : k_(cost_constants()) {}
  // Per-slot tables as registers with a write port (LaneShape::tables_ram) or as case ROMs.
  void set_tables_ram(bool ram) { tables_ram_ = ram; }

  // ---- primitives: each returns its path segment ----
  Seg adder(int w, const std::string& where) {
    add({"adder", w, 0, 1, w * k_.add_bit_ge, where});
    return {fmt::format("add {}", w), adder_delay(w)};
  }
  // is_signed: two's-complement operands (the RTL's `signed` product: a wider tree).
  Seg multiplier(int a, int b, const std::string& where, int count = 1, bool is_signed = false) {
    add({"multiplier", a, b, count, count * multiplier_ge(a, b, is_signed), where});
    return {fmt::format("mul {}x{}", a, b), multiplier_delay(a, b)};
  }
  // A multiplier whose b operand is the constant k (a per-material value when the scene has one
  // material: Yosys folds its one-entry table and builds shift-and-add rows for k's one bits).
  // Fitted on 12 constant multipliers (12-24 x 4-16 bits, primitives.csv): the full multiplier of
  // k's significant bits scaled by 0.85 x its ones / bits; 10 of them within +-10 %, the worst
  // +24 % (24 x 4055) and +29 % (12 x 9).
  Seg const_multiplier(int a, std::int64_t k, const std::string& where, bool is_signed = false) {
    unsigned long long m = static_cast<unsigned long long>(k < 0 ? -k : k);
    while (m != 0 && (m & 1) == 0) m >>= 1;
    const int bits = m == 0 ? 0 : 64 - __builtin_clzll(m);
    const int ones = __builtin_popcountll(m);
    if (ones <= 1) return {fmt::format("mul {}x{} (shift)", a, k), 0};  // a power of two: wires
    const double ge = multiplier_ge(a, bits, is_signed) * std::min(1.0, 0.85 * ones / bits);
    add({"multiplier", a, bits, 1, ge, where + " (by a constant)"});
    return {fmt::format("mul {}xk{}", a, bits), multiplier_delay(a, ones)};
  }
  // A multiplier whose b operand is read from a ROM of these (non-negative) values, one per
  // datapath group: one value is a constant multiplier; otherwise a bit that is 0 in every entry
  // is a constant 0 column and Yosys builds no partial products for it, so the tree has one row
  // per bit set in any entry.
  Seg table_multiplier(int a, const std::vector<std::int64_t>& values, const std::string& where,
                       bool is_signed = false) {
    if (std::all_of(values.begin(), values.end(), [&](std::int64_t v) { return v == values[0]; }))
      return const_multiplier(a, values.front(), where, is_signed);
    unsigned long long any = 0;
    for (std::int64_t v : values) any |= static_cast<unsigned long long>(v);
    return multiplier(a, __builtin_popcountll(any), where, 1, is_signed);
  }
  // rows: quotient rows built in hardware (all quotient bits pipelined, 1 iterative).
  Seg divider(int rows, int divisor, const std::string& where) {
    // A row as the RTL writes it: the quotient bit from a comparator, the subtraction beside it
    // (Yosys shares no logic between them) and the restore mux.
    add({"divider", rows, divisor, 1,
         rows * (divisor + 1) * (k_.add_bit_ge + k_.cmp_bit_ge + k_.mux2_ge), where});
    return {fmt::format("div row {}", divisor + 1), divider_row_delay(divisor)};
  }
  Seg comparator(int w, const std::string& where) {
    add({"comparator", w, 0, 1, w * k_.cmp_bit_ge, where});
    return {fmt::format("cmp {}", w), comparator_delay(w)};
  }
  Seg mux(int w, int inputs, const std::string& where) {
    add({"mux", w, inputs, 1, w * (inputs - 1) * k_.mux2_ge, where});
    return {fmt::format("mux{} {}", inputs, w), mux_delay(inputs)};
  }
  Seg shifter(int w, int levels, const std::string& where) {
    add({"shifter", w, levels, 1, w * levels * k_.shift_bit_ge, where});
    return {fmt::format("shift {}x{}", w, levels), static_cast<double>(levels)};
  }
  Seg lzd(int w, const std::string& where) {
    add({"lzd", w, 0, 1, w * k_.lzd_bit_ge, where});
    return {fmt::format("lzd {}", w), std::max(1.0, w - 2.0)};
  }
  // n two-input gates of glue logic (AND/OR: the flow's $_AND_, $_ANDNOT_, ...; 6 transistors).
  Seg gates(int n, const std::string& where) {
    add({"gates", n, 0, 1, n * k_.gate_ge, where});
    return {fmt::format("gates {}", n), 1};
  }
  // A fixed-function ROM of known contents (the same for every material: pow's log2 and exp2).
  Seg rom(const std::vector<std::int64_t>& words, int w, const std::string& where, int copies = 1) {
    const int entries = static_cast<int>(words.size());
    add({"table", entries, w, copies, copies * rom_ge(words, w), where});
    return {fmt::format("rom {}x{}", entries, w), table_delay(entries)};
  }
  // Per-slot storage, `banks` of `entries` words. shared_port: the banks are one table addressed
  // by (bank, entry); otherwise every bank has its own read port. As a ROM (the scene's materials
  // fixed at synthesis) of contents the caller knows (`words`, all banks, bank-major) or not; as
  // registers with a write port (ram: a chip of fixed capacity).
  Seg slot_table(int entries, int w, int banks, bool shared_port, const std::string& where,
                 const std::vector<std::int64_t>* words = nullptr) {
    const bool ram = tables_ram_;
    const int e = shared_port ? entries * banks : entries;
    const int tables = shared_port ? 1 : banks;
    double ge = 0;
    if (ram) {
      ge = tables * w * (e * k_.ram_bit_ge + (e - 1) * k_.ram_mux_ge);
    } else if (words != nullptr && shared_port) {
      ge = rom_ge(*words, w);
    } else if (words != nullptr) {  // a ROM a bank, each of `entries` words
      for (int k = 0; k < banks; ++k) {
        const auto first = words->begin() + static_cast<std::ptrdiff_t>(k) * entries;
        ge += rom_ge(std::vector<std::int64_t>(first, first + entries), w);
      }
    } else if (e > 2) {
      ge = tables * static_cast<double>(e) * w * k_.rom_bit_ge;
    }
    add({"table", entries, w, banks, ge, where});
    return {fmt::format("{} {}x{}", ram ? "ram" : "rom", e, w),
            ram ? mux_delay(e) : table_delay(e)};
  }
  // A pipeline register written by every computed request (or every request).
  // Per-request registers are the lane's: they hold under backpressure (flip-flops with enable).
  void reg(int w, const std::string& where, bool per_request = false, int count = 1) {
    add({"register", w, 0, count, count * w * (per_request ? k_.dffe_ge : k_.dff_ge), where});
    (per_request ? request_ : computed_)["reg_bits"] += w;
  }
  // State registers written `writes` times per computed request (iterative divider).
  void state_reg(int w, const std::string& where, double writes) {
    add({"register", w, 0, 1, w * k_.dffe_ge, where});
    computed_["reg_bits"] += w * writes;
  }

  void op(const std::string& kind, double n = 1) { computed_[kind] += n; }
  void request_op(const std::string& kind, double n = 1) { request_[kind] += n; }

  // Closes a stage: its path in series plus the register overhead.
  void stage(const std::string& name, const std::vector<Seg>& path) {
    StageDelay s{name, k_.reg_delay, ""};
    for (const Seg& g : path) {
      s.delay += g.delay;
      s.path += g.label + " + ";
    }
    s.path += "reg";
    stages_.push_back(std::move(s));
  }

  UnitCost finish() {
    UnitCost c;
    c.inventory = std::move(inv_);
    for (const Primitive& p : c.inventory) c.area_ge += p.ge;
    c.stages = std::move(stages_);
    for (const StageDelay& s : c.stages) {
      if (s.delay > c.critical_path) {
        c.critical_path = s.delay;
        c.critical_stage = s.stage;
      }
    }
    for (auto& [kind, n] : computed_)
      if (n != 0) c.ops_per_computed[kind] = n;
    for (auto& [kind, n] : request_)
      if (n != 0) c.ops_per_request[kind] = n;
    return c;
  }

 private:
  void add(Primitive p) {
    if (p.ge <= 0) return;  // zero-width parts (e.g. no interpolation bits) are not built
    inv_.push_back(std::move(p));
  }

  const CostConstants& k_;
  bool tables_ram_ = false;
  std::vector<Primitive> inv_;
  std::vector<StageDelay> stages_;
  std::map<std::string, double> computed_, request_;
};

// What every part of a lane shares: the unit's formats, whether it skips, its slots, datapath
// groups and timing.
struct LaneShape {
  QFormat in, out;
  bool skip = true;
  // Comparator thresholds (entries of the tau table) and datapath groups (entries of every
  // per-material table: n, span, k, coefficients, t^n tables), each the stream's count or, for a
  // chip of fixed capacity, that capacity.
  int slots = 1, groups = 1;
  // The group id the pipeline carries to the per-material tables.
  int group_bits = 0;
  // Slots share datapath groups (or a fixed-capacity chip, which may have to): each tau entry
  // names its group (otherwise the slot id is the group id).
  bool slot_to_group = false;
  // A chip of fixed capacity (--slots): registers hold what any scene may need.
  bool fixed = false;
  // Per-slot tables as registers with a write port (loaded at material load) rather than case
  // ROMs of the scene's materials: a chip of fixed capacity (cost_model.h, "tables").
  bool tables_ram = false;
  int latency = 1, buffer = 1, ii = 1;
};

// Comparator stage: tau per slot (for hast/horner also the root per datapath group), the compare,
// and the register after it (the datapath's input: t and the group id).
void comparator_stage(CostBuilder& b, const LaneShape& L, bool carry_root);
// The in-order merge buffer, with the control hdl/lane.cpp writes around it: each entry's valid and
// skipped bits and its write select (a bypassed result or the datapath's), the tag and valid bit
// carried beside every position of the unit, the credit, issue and head counters (and the II
// counter), the read mux at the head.
void merge_buffer(CostBuilder& b, const LaneShape& L);

}  // namespace glint
