#include "units/u_scaler_cost.h"

namespace glint {

std::vector<Seg> u_scaler_cost(CostBuilder& b, const LaneShape& L, int k_width, int fh,
                               const std::vector<std::int64_t>* ks) {
  const int wi = L.in.width();
  const Seg k = b.slot_table(L.groups, k_width, 1, true, "u scaler: k table (per datapath group)");
  const Seg sub = b.adder(wi, "u scaler: t - tau");
  const Seg mul = ks ? b.table_multiplier(wi, *ks, "u scaler: (t - tau) k")
                     : b.multiplier(wi, k_width, "u scaler: (t - tau) k");
  // The clamp compares the whole rounded product with 1.0 (u_scaler_rtl.cpp), then selects.
  const Seg over = b.comparator(wi + k_width + 1, "u scaler: above 1.0");
  const Seg clamp = b.mux(fh + 1, 2, "u scaler: clamp to 1");
  b.op("table_read");
  b.op("add");
  b.op("mul");
  return {parallel(k, sub), mul, over, clamp};
}

}  // namespace glint
