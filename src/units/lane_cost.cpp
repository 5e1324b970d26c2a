#include "units/lane_cost.h"

#include <algorithm>

#include "cost/builder.h"

namespace glint {

UnitCost unit_cost(const SpecularUnit& unit, bool colour_multiply) {
  LaneShape lane;
  lane.in = unit.in_format();
  lane.out = unit.out_format();
  lane.skip = unit.comparator_enabled();
  lane.slots = static_cast<int>(unit.slots());
  lane.slot_bits = clog2(std::max(lane.slots, 1));
  lane.latency = unit.timing().latency;
  lane.buffer = unit.timing().buffer_depth;
  CostBuilder b;
  comparator_stage(b, lane, unit.comparator_carries_root());
  unit.add_cost(b, lane);
  merge_buffer(b, lane, colour_multiply);
  if (colour_multiply) colour_stage(b, lane);
  return b.finish();
}

}  // namespace glint
