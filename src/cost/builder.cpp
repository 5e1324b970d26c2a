#include "cost/builder.h"

#include <optional>

namespace glint {

void comparator_stage(CostBuilder& b, const LaneShape& L, bool carry_root) {
  const int wi = L.in.width();
  // Per slot: its threshold and, when slots share datapath groups, its group's id (otherwise the
  // slot id is the group id). Without the comparator only the id is left to look up.
  std::optional<Seg> tau, root;
  const int w = (L.skip ? wi : 0) + (L.slot_to_group ? L.group_bits : 0);
  if (w > 0) {
    tau = b.slot_table(L.slots, w, 1, true,
                       !L.skip           ? "group id table (per slot)"
                       : L.slot_to_group ? "tau table (per slot, with its group id)"
                                         : "tau table (per slot)");
    b.request_op("table_read");
  }
  // hast/horner: the u scaler's root is the datapath group's (its slots' smallest tau), not a
  // slot's threshold.
  if (carry_root) {
    root = b.slot_table(L.groups, wi, 1, true, "root table (per datapath group)");
    b.request_op("table_read");
  }
  std::vector<Seg> path;
  std::optional<Seg> beside_compare;
  if (tau && root && !L.slot_to_group) {
    path.push_back(parallel(*tau, *root));  // both read by the slot id
  } else {
    if (tau) path.push_back(*tau);
    beside_compare = root;  // read by the group id the tau entry gives
  }
  if (L.skip) {
    const Seg cmp = b.comparator(wi, "tau comparator");
    path.push_back(beside_compare ? parallel(*beside_compare, cmp) : cmp);
    b.request_op("compare");
  } else if (beside_compare) {
    path.push_back(*beside_compare);
  }
  b.reg(wi + (L.skip ? 1 : 0) + L.group_bits + (carry_root ? wi : 0), "comparator register", true);
  b.stage("comparator", path);
}

void merge_buffer(CostBuilder& b, const LaneShape& L, bool colour) {
  const int w = L.out.width() + (colour ? L.colour_bits : 0);
  b.reg(w, "merge buffer", true, L.buffer);
  if (L.buffer > 1) b.mux(w, L.buffer, "merge buffer read mux");
}

void colour_stage(CostBuilder& b, const LaneShape& L) {
  const int wo = L.out.width();
  const Seg tab = b.slot_table(L.colours, 3 * wo, 1, true, "colour: RGB table (per colour)");
  const Seg mul = b.multiplier(wo, wo, "colour: highlight x R, G, B", 3);
  b.op("table_read");
  b.op("mul", 3);
  b.reg(3 * wo, "colour: RGB result", true);
  b.stage("colour", {tab, mul});
}

}  // namespace glint
