// The cost builder every unit describes its hardware with: each primitive it places adds its area
// (gate equivalents), returns its delay as a path segment, and the unit closes each pipeline stage
// with the segments on its path. Operation counts (the energy proxy) are recorded beside.
//
// The lane parts every unit shares (the comparator stage, the merge buffer, the optional colour
// stage) are here too; a unit's own stages live in its own files (src/units/<unit>/), and
// units/lane_cost.h puts a whole lane together. Constants and formulas: cost/cost_model.h.
#pragma once

#include <fmt/format.h>

#include <algorithm>
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

  // ---- primitives: each returns its path segment ----
  Seg adder(int w, const std::string& where) {
    add({"adder", w, 0, 1, w * k_.fa_ge, where});
    return {fmt::format("add {}", w), adder_delay(w)};
  }
  Seg multiplier(int a, int b, const std::string& where, int count = 1) {
    add({"multiplier", a, b, count, count * a * b * (k_.fa_ge + k_.and2_ge), where});
    return {fmt::format("mul {}x{}", a, b), multiplier_delay(a, b)};
  }
  // rows: quotient rows built in hardware (all quotient bits pipelined, 1 iterative).
  Seg divider(int rows, int divisor, const std::string& where) {
    add({"divider", rows, divisor, 1, rows * (divisor + 1) * (k_.fa_ge + k_.mux2_ge), where});
    return {fmt::format("div row {}", divisor + 1), divider_row_delay(divisor)};
  }
  Seg comparator(int w, const std::string& where) {
    add({"comparator", w, 0, 1, w * k_.cmp_bit_ge, where});
    return {fmt::format("cmp {}", w), adder_delay(w)};
  }
  Seg mux(int w, int inputs, const std::string& where) {
    add({"mux", w, inputs, 1, w * (inputs - 1) * k_.mux2_ge, where});
    return {fmt::format("mux{} {}", inputs, w), k_.mux_delay * clog2(inputs)};
  }
  Seg shifter(int w, int levels, const std::string& where) {
    add({"shifter", w, levels, 1, w * levels * k_.mux2_ge, where});
    return {fmt::format("shift {}x{}", w, levels), k_.mux_delay * levels};
  }
  Seg lzd(int w, const std::string& where) {
    add({"lzd", w, 0, 1, w * k_.lzd_bit_ge, where});
    return {fmt::format("lzd {}", w), 2.0 * clog2(w)};
  }
  Seg rom(int entries, int w, const std::string& where) {
    add({"table", entries, w, 1, static_cast<double>(entries) * w * k_.rom_bit_ge, where});
    return {fmt::format("rom {}x{}", entries, w), table_delay(entries)};
  }
  // Per-slot storage, `banks` of `entries` words. shared_port: the banks are one table addressed
  // by (bank, entry); otherwise every bank has its own read-mux tree.
  Seg slot_table(int entries, int w, int banks, bool shared_port, const std::string& where) {
    auto one = [&](double e) { return w * (e * k_.latch_ge + (e - 1) * k_.mux2_ge); };
    const double ge =
        shared_port ? one(static_cast<double>(entries) * banks) : banks * one(entries);
    add({"table", entries, w, banks, ge, where});
    const int e = shared_port ? entries * banks : entries;
    return {fmt::format("table {}x{}", e, w), table_delay(e)};
  }
  // A pipeline register written by every computed request (or every request).
  void reg(int w, const std::string& where, bool per_request = false, int count = 1) {
    add({"register", w, 0, count, count * w * k_.dff_ge, where});
    (per_request ? request_ : computed_)["reg_bits"] += w;
  }
  // State registers written `writes` times per computed request (iterative divider).
  void state_reg(int w, const std::string& where, double writes) {
    add({"register", w, 0, 1, w * k_.dff_ge, where});
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
  // RGB entries of the colour stage and the id the merge buffer carries to it.
  int colours = 1, colour_bits = 0;
  int latency = 1, buffer = 1;
};

// Comparator stage: tau per slot (for hast/horner also the root per datapath group), the compare,
// and the register that carries t, the skip flag, the group id and (carry_root) the root to the u
// scaler.
void comparator_stage(CostBuilder& b, const LaneShape& L, bool carry_root);
// The in-order merge buffer (its entries carry the colour id when the colour stage follows: the
// entry is reserved at issue, so the id is written there, not carried through the unit).
void merge_buffer(CostBuilder& b, const LaneShape& L, bool colour);
// The RGB multiply after the merge buffer (coloured streams).
void colour_stage(CostBuilder& b, const LaneShape& L);

}  // namespace glint
