#include "units/u_scaler_cost.h"

namespace glint {

std::vector<Seg> u_scaler_cost(CostBuilder& b, const LaneShape& L, int k_width, int fh) {
  const int wi = L.in.width();
  const Seg k = b.slot_table(L.groups, k_width, 1, true, "u scaler: k table (per datapath group)");
  const Seg sub = b.adder(wi, "u scaler: t - tau");
  const Seg mul = b.multiplier(wi, k_width, "u scaler: (t - tau) k");
  const Seg clamp = b.mux(fh + 1, 2, "u scaler: clamp to 1");
  b.op("table_read");
  b.op("add");
  b.op("mul");
  return {parallel(k, sub), mul, clamp};
}

}  // namespace glint
