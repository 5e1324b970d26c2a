#include "cost/builder.h"

namespace glint {

void comparator_stage(CostBuilder& b, const LaneShape& L, bool carry_root) {
  const int wi = L.in.width();
  std::vector<Seg> path;
  if (L.skip || carry_root) {
    path.push_back(b.slot_table(L.slots, wi, 1, true,
                                carry_root ? "tau/root table (per slot)" : "tau table (per slot)"));
    b.request_op("table_read");
  }
  if (L.skip) {
    path.push_back(b.comparator(wi, "tau comparator"));
    b.request_op("compare");
  }
  b.reg(wi + (L.skip ? 1 : 0) + L.slot_bits + (carry_root ? wi : 0), "comparator register", true);
  b.stage("comparator", path);
}

void merge_buffer(CostBuilder& b, const LaneShape& L, bool colour) {
  const int w = L.out.width() + (colour ? L.slot_bits : 0);
  b.reg(w, "merge buffer", true, L.buffer);
  if (L.buffer > 1) b.mux(w, L.buffer, "merge buffer read mux");
}

void colour_stage(CostBuilder& b, const LaneShape& L) {
  const int wo = L.out.width();
  const Seg tab = b.slot_table(L.slots, 3 * wo, 1, true, "colour: RGB table (per slot)");
  const Seg mul = b.multiplier(wo, wo, "colour: highlight x R, G, B", 3);
  b.op("table_read");
  b.op("mul", 3);
  b.reg(3 * wo, "colour: RGB result", true);
  b.stage("colour", {tab, mul});
}

}  // namespace glint
