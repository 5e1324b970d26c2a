#include "units/lane_cost.h"

#include <algorithm>

#include "cost/builder.h"

namespace glint {

UnitCost unit_cost(const SpecularUnit& unit, bool colour_multiply, int colour_entries) {
  LaneShape lane;
  lane.in = unit.in_format();
  lane.out = unit.out_format();
  lane.skip = unit.comparator_enabled();
  // Sized to the stream: a threshold per slot, a per-material entry per datapath group. A chip of
  // fixed capacity N: N of each (any N slots may be N materials).
  lane.fixed = unit.slot_capacity() > 0;
  lane.slots = static_cast<int>(lane.fixed ? unit.slot_capacity() : unit.slots());
  lane.groups = static_cast<int>(lane.fixed ? unit.slot_capacity() : unit.datapath_groups());
  lane.slots = std::max(lane.slots, 1);
  lane.groups = std::max(lane.groups, 1);
  lane.group_bits = clog2(lane.groups);
  lane.slot_to_group = lane.fixed || unit.datapath_groups() < unit.slots();
  lane.colours = colour_entries > 0 ? colour_entries : lane.slots;
  lane.colour_bits = clog2(lane.colours);
  lane.latency = unit.timing().latency;
  lane.buffer = unit.timing().buffer_depth;
  lane.ii = unit.timing().ii;
  // The scene's materials fixed at synthesis: case ROMs (what `glint rtl` writes by default); a
  // chip of fixed capacity, or a lane asked for tables=ram, loads them: registers with a write
  // port (what `glint rtl` writes with tables=ram).
  lane.tables_ram = lane.fixed || unit.tables_ram();
  CostBuilder b;
  b.set_tables_ram(lane.tables_ram);
  comparator_stage(b, lane, unit.comparator_carries_root());
  unit.add_cost(b, lane);
  merge_buffer(b, lane, colour_multiply);
  if (colour_multiply) colour_stage(b, lane);
  return b.finish();
}

UnitTiming lane_timing(const SpecularUnit& unit, bool colour_stage) {
  UnitTiming t = unit.timing();
  if (colour_stage) t.latency += 1;
  return t;
}

}  // namespace glint
