// The u scaler's hardware (units/u_scaler.h) in the cost model: shared by hast and horner.
#pragma once

#include <cstdint>
#include <vector>

#include "cost/builder.h"

namespace glint {

// u = (t - root) k clamped to [0, 1] at fh fraction bits: the k table (per datapath group, k_width
// bits), a subtractor, a multiplier and the clamp. Returns the stage path.
// ks: the k of every datapath group when the lane's tables are ROMs of known contents (a constant
// multiplier for one material, fewer partial-product rows for bits no k sets), else null.
std::vector<Seg> u_scaler_cost(CostBuilder& b, const LaneShape& L, int k_width, int fh,
                               const std::vector<std::int64_t>* ks = nullptr);

}  // namespace glint
