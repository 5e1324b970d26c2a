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
#include <utility>
#include <vector>

#include "cost/cost_model.h"
#include "cost/node.h"
#include "fixed/fixed_point.h"

namespace glint {

// One element on a stage's path: its delay in gate levels and at the node (cost/node.h), and
// which kind of part it is (arithmetic parts in a row overlap at the node: CostBuilder::close).
// A composite (series, parallel) keeps the primitives of its slowest branch in path order.
struct Seg {
  enum class Part { kOther, kAdder, kMultiplier, kComparator, kMux };
  Seg() = default;
  Seg(std::string l, double d, double n = 0, Part p = Part::kOther, std::vector<Seg> c = {})
      : label(std::move(l)), delay(d), ns(n), part(p), chain(std::move(c)) {}
  std::string label;
  double delay = 0;
  double ns = 0;
  Part part = Part::kOther;
  std::vector<Seg> chain;  // a composite's primitives along its slowest branch; empty: itself
};

inline const char* kind_name(Seg::Part p) {
  switch (p) {
    case Seg::Part::kAdder:
      return "adder";
    case Seg::Part::kMultiplier:
      return "multiplier";
    case Seg::Part::kComparator:
      return "comparator";
    case Seg::Part::kMux:
      return "mux";
    default:
      return "other";
  }
}

// The primitives a segment stands for, in path order.
inline std::vector<Seg> atoms(const Seg& s) {
  return s.chain.empty() ? std::vector<Seg>{s} : s.chain;
}

// Two things side by side: the stage waits for the slower.
inline Seg parallel(const Seg& a, const Seg& b) {
  return {"(" + a.label + " || " + b.label + ")", std::max(a.delay, b.delay), std::max(a.ns, b.ns),
          Seg::Part::kOther, atoms(a.ns >= b.ns ? a : b)};
}

// Things one after the other, as one segment.
inline Seg series(const std::vector<Seg>& segs) {
  Seg out;
  for (const Seg& g : segs) {
    out.label += (out.label.empty() ? "" : " + ") + g.label;
    out.delay += g.delay;
    out.ns += g.ns;
    for (Seg& a : atoms(g)) out.chain.push_back(std::move(a));
  }
  return out;
}

// Collects the inventory, the stage paths and the operation counts of one lane.
class CostBuilder {
 public:
  CostBuilder() : k_(cost_constants()), n_(node_osu018()) {}
  // Per-slot tables as registers with a write port (LaneShape::tables_ram) or as case ROMs.
  void set_tables_ram(bool ram) { tables_ram_ = ram; }

  // ---- primitives: each returns its path segment ----
  Seg adder(int w, const std::string& where) {
    add({"adder", w, 0, 1, w * k_.add_bit_ge, where}, n_.adder);
    return {fmt::format("add {}", w), adder_delay(w), n_.adder.delay.at(w, w, 0),
            Seg::Part::kAdder};
  }
  // is_signed: two's-complement operands (the RTL's `signed` product: a wider tree).
  Seg multiplier(int a, int b, const std::string& where, int count = 1, bool is_signed = false) {
    add({"multiplier", a, b, count, count * multiplier_ge(a, b, is_signed), where}, n_.multiplier);
    return {fmt::format("mul {}x{}", a, b), multiplier_delay(a, b),
            n_.multiplier.delay.at(a + b, std::min(a, b), 0), Seg::Part::kMultiplier};
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
    add({"multiplier", a, bits, 1, ge, where + " (by a constant)"}, n_.multiplier);
    return {fmt::format("mul {}xk{}", a, bits), multiplier_delay(a, ones),
            n_.multiplier.delay.at(a + ones, std::min(a, ones), 0), Seg::Part::kMultiplier};
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
    // A row as the RTL writes it: one subtractor of the partial remainder's D + 1 bits whose
    // borrow is the quotient bit, and the restore mux.
    add({"divider", rows, divisor, 1, rows * (divisor + 1) * (k_.add_bit_ge + k_.mux2_ge), where},
        n_.divider);
    return {fmt::format("div row {}", divisor + 1), divider_row_delay(divisor),
            n_.divider.delay.at(divisor + 1, divisor + 1, 0)};
  }
  Seg comparator(int w, const std::string& where) {
    add({"comparator", w, 0, 1, w * k_.cmp_bit_ge, where}, n_.comparator);
    return {fmt::format("cmp {}", w), comparator_delay(w), n_.comparator.delay.at(w, w, 0),
            Seg::Part::kComparator};
  }
  Seg mux(int w, int inputs, const std::string& where) {
    add({"mux", w, inputs, 1, w * (inputs - 1) * k_.mux2_ge, where}, n_.mux);
    return {fmt::format("mux{} {}", inputs, w), mux_delay(inputs), select_ns(n_.mux, inputs, w),
            Seg::Part::kMux};
  }
  Seg shifter(int w, int levels, const std::string& where) {
    add({"shifter", w, levels, 1, w * levels * k_.shift_bit_ge, where}, n_.shifter);
    return {fmt::format("shift {}x{}", w, levels), static_cast<double>(levels),
            n_.shifter.delay.at(levels, w, 0)};
  }
  Seg lzd(int w, const std::string& where) {
    add({"lzd", w, 0, 1, w * k_.lzd_bit_ge, where}, n_.lzd);
    return {fmt::format("lzd {}", w), std::max(1.0, w - 2.0), n_.lzd.delay.at(w, w, 0)};
  }
  // n two-input gates of glue logic (AND/OR: the flow's $_AND_, $_ANDNOT_, ...; 6 transistors).
  Seg gates(int n, const std::string& where) {
    add({"gates", n, 0, 1, n * k_.gate_ge, where}, n_.gates);
    return {fmt::format("gates {}", n), 1, n_.gates.delay.at(1, 1, 0)};
  }
  // A fixed-function ROM of known contents (the same for every material: pow's log2 and exp2).
  Seg rom(const std::vector<std::int64_t>& words, int w, const std::string& where, int copies = 1) {
    const int entries = static_cast<int>(words.size());
    add({"table", entries, w, copies, copies * rom_ge(words, w), where}, n_.rom);
    return {fmt::format("rom {}x{}", entries, w), table_delay(entries),
            n_.rom.delay.at(w, entries, 0)};
  }
  // Per-slot storage, `banks` of `entries` words. shared_port: the banks are one table addressed
  // by (bank, entry); otherwise every bank has its own read port. As a ROM (the scene's materials
  // fixed at synthesis) of contents the caller knows (`words`, all banks, bank-major) or not; as
  // registers with a write port (ram: a chip of fixed capacity). read_banks: a RAM read as that
  // many arrays, each with its own read mux (lut's even and odd t^n banks). computed_address: its
  // read address is computed in the stage (lut's from t), not read from the id register.
  Seg slot_table(int entries, int w, int banks, bool shared_port, const std::string& where,
                 const std::vector<std::int64_t>* words = nullptr, int read_banks = 1,
                 bool computed_address = false) {
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
    add({"table", entries, w, banks, ge, where}, ram ? n_.ram : n_.rom, ram ? e * w * tables : 0);
    // Loaded through a write port from the lane's inputs: the entry's decode, then its enable to
    // the w flip-flops of every table written with it.
    if (ram)
      lane_path(where + ": write port", {{"decode", 0, clog2(e) * n_.gates.delay.at(1, 1, 0)},
                                         {"enable", 0, select_ns(n_.mux, 2, w * tables)}});
    // A RAM's read is a mux of its entries whose select drives every mux of its array through
    // the buffer tree the flow builds (log2 of its loads deep). A table addressed by the group or
    // slot id alone shares that register with the stage's other such tables: stage() prices the
    // select's load of all of them.
    const double loads = static_cast<double>(e) * w / read_banks;
    if (ram && shared_port && banks == 1) {
      id_loads_ += loads;
      id_loads_max_ = std::max(id_loads_max_, loads);
    }
    return {fmt::format("{} {}x{}", ram ? "ram" : "rom", e, w), ram ? mux_delay(e) : table_delay(e),
            !ram               ? n_.rom.delay.at(w, e, 0)
            : computed_address ? n_.ram_computed.delay.at(clog2(e), loads, loads)
                               : n_.ram.delay.at(clog2(e), loads, loads)};
  }
  // A pipeline register written by every computed request (or every request).
  // Per-request registers are the lane's: they hold under backpressure (flip-flops with enable).
  void reg(int w, const std::string& where, bool per_request = false, int count = 1) {
    add({"register", w, 0, count, count * w * (per_request ? k_.dffe_ge : k_.dff_ge), where},
        per_request ? n_.dffe : n_.dff, count * w);
    (per_request ? request_ : computed_)["reg_bits"] += w;
  }
  // State registers written `writes` times per computed request (iterative divider).
  void state_reg(int w, const std::string& where, double writes) {
    add({"register", w, 0, 1, w * k_.dffe_ge, where}, n_.dffe, w);
    computed_["reg_bits"] += w * writes;
  }

  const NodeConstants& node() const { return n_; }

  void op(const std::string& kind, double n = 1) { computed_[kind] += n; }
  void request_op(const std::string& kind, double n = 1) { request_[kind] += n; }

  // Closes a stage: its path in series plus the register overhead.
  void stage(const std::string& name, const std::vector<Seg>& path) {
    StageDelay s = close(name, path);
    // The id register loaded by every id-addressed table of the stage, not only the one on the
    // path: the load term of all of them in place of the largest's.
    if (id_loads_ > id_loads_max_)
      s.ns += n_.ram.delay.at(0, id_loads_, id_loads_) -
              n_.ram.delay.at(0, id_loads_max_, id_loads_max_);
    id_loads_ = id_loads_max_ = 0;
    stages_.push_back(std::move(s));
  }
  // A path of the lane's own control (merge buffer, table write port) from a register to a
  // register or a port: priced at the node beside the stages (a real node's worst path is often
  // one of them), not in the gate-level critical path the generic calibration holds.
  void lane_path(const std::string& name, const std::vector<Seg>& path) {
    lane_paths_.push_back(close(name, path));
  }
  // A mux of `inputs` words of `w` bits whose select comes from one register: the flow buffers
  // the select, so its delay grows with the log of the muxes it drives (cost/node.h).
  double select_ns(const NodePart& p, int inputs, int w) const {
    const double loads = static_cast<double>(inputs) * w;
    return p.delay.at(clog2(inputs), loads, loads);
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
    c.lane_paths = std::move(lane_paths_);
    c.node = n_.name;
    for (const Primitive& p : c.inventory) c.area_um2 += p.um2;
    for (const auto* list : {&c.stages, &c.lane_paths})
      for (const StageDelay& s : *list)
        if (s.ns > c.critical_path_ns) {
          c.critical_path_ns = s.ns;
          c.critical_path_node = s.stage;
        }
    for (auto& [kind, n] : computed_)
      if (n != 0) c.ops_per_computed[kind] = n;
    for (auto& [kind, n] : request_)
      if (n != 0) c.ops_per_request[kind] = n;
    return c;
  }

 private:
  void add(Primitive p, const NodePart& node, int held_bits = 0) {
    if (p.ge <= 0) return;  // zero-width parts (e.g. no interpolation bits) are not built
    p.um2_unfitted = p.ge * node.um2_per_ge;
    p.um2 = p.um2_unfitted * node.lane_area;
    p.node_part = node_part_name(n_, node);
    p.stage = static_cast<int>(stages_.size());  // the stage being described
    p.held_bits = held_bits;
    inv_.push_back(std::move(p));
  }
  // At the node, arithmetic parts in a row overlap: the flow's carry chains are ripple-like, and
  // an adder's low bits feed a multiplier's first rows while its carries still run; a product's
  // low bits reach the adder, comparator or select after it long before its top bits, and abc,
  // mapping for delay, merges their chains. So a part right before a multiplier, or after one
  // (or after such a part), counts a fraction of its own delay (NodeConstants::overlap, fitted on
  // the calibration lanes: node_fit.py --lanes). Gate levels keep the generic model's sum.
  StageDelay close(const std::string& name, const std::vector<Seg>& path) const {
    StageDelay s{name, k_.reg_delay, "", n_.reg_ns, {}};
    std::vector<Seg> chain;
    for (const Seg& g : path) {
      s.delay += g.delay;
      s.path += g.label + " + ";
      for (Seg& a : atoms(g)) chain.push_back(std::move(a));
    }
    s.path += "reg";
    bool after_multiplier = false;
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const Seg& a = chain[i];
      const bool before_multiplier =
          i + 1 < chain.size() && chain[i + 1].part == Seg::Part::kMultiplier;
      const NodeOverlap& o = n_.overlap;
      double f = 1;
      if (a.part == Seg::Part::kAdder && before_multiplier)
        f = o.adder_before_multiplier;
      else if (after_multiplier && a.part == Seg::Part::kAdder)
        f = o.adder_after;
      else if (after_multiplier && a.part == Seg::Part::kComparator)
        f = o.comparator_after;
      else if (after_multiplier && a.part == Seg::Part::kMux)
        f = o.mux_after;
      s.ns += f * a.ns;
      s.parts.push_back({a.label, kind_name(a.part), a.ns, f * a.ns});
      after_multiplier = a.part == Seg::Part::kMultiplier || (after_multiplier && f < 1);
    }
    return s;
  }

  const CostConstants& k_;
  const NodeConstants& n_;
  bool tables_ram_ = false;
  std::vector<Primitive> inv_;
  std::vector<StageDelay> stages_, lane_paths_;
  double id_loads_ = 0, id_loads_max_ = 0;  // RAM reads by the id register in the open stage
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
