#include "units/lane_cost.h"

#include <algorithm>

#include "cost/builder.h"

namespace glint {

UnitCost unit_cost(const SpecularUnit& unit) {
  LaneShape lane;
  lane.in = unit.in_format();
  lane.out = unit.out_format();
  lane.skip = unit.comparator_enabled();
  // Sized to the stream: a threshold per slot, a per-material entry per datapath group. A chip of
  // given capacity (units/chip.h): S thresholds and M entries of every per-material table.
  lane.fixed = unit.slot_capacity() > 0 || unit.group_capacity() > 0;
  lane.slots = static_cast<int>(unit.slot_capacity() > 0 ? unit.slot_capacity() : unit.slots());
  lane.groups =
      static_cast<int>(unit.group_capacity() > 0 ? unit.group_capacity() : unit.datapath_groups());
  lane.slots = std::max(lane.slots, 1);
  lane.groups = std::max(lane.groups, 1);
  lane.group_bits = clog2(lane.groups);
  lane.slot_to_group = lane.fixed || unit.datapath_groups() < unit.slots();
  lane.latency = unit.timing().latency;
  lane.buffer = unit.timing().buffer_depth;
  lane.ii = unit.timing().ii;
  // The scene's materials fixed at synthesis: case ROMs (what `glint rtl` writes by default); a
  // chip of given capacity, or a lane asked for tables=ram (--chip ram), loads them: registers with
  // a write port (what `glint rtl` writes with tables=ram).
  lane.tables_ram = lane.fixed || unit.tables_ram();
  CostBuilder b;
  b.set_tables_ram(lane.tables_ram);
  comparator_stage(b, lane, unit.comparator_carries_root());
  unit.add_cost(b, lane);
  merge_buffer(b, lane);
  return b.finish();
}

}  // namespace glint
