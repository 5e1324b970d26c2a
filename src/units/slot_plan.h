// What a unit is elaborated for: the scene's slots and the datapath groups that serve them.
//
// A slot is one comparator threshold. Källberg & Larsson ("Optimized Phong and Blinn-Phong Glossy
// Highlights", eq.3) make tau depend on the material's lobe and on c_y, the luminance
// of light x specular colour; with white lights it is the material's own luminance (eq.6). So the
// scene needs one slot per distinct (material, c_y) pair: lights that leave c_y unchanged (white
// ones among them) share the material's slot, and a light that changes c_y gets a slot of its own
// for each material it changes.
//
// t^n does not depend on the light: the datapath (tables, coefficients, the n register's value) is
// built once per group, the slots of one material (or of several materials whose datapaths would
// be identical), and shared by them; each slot keeps its own threshold. A group's datapath is
// built from the params that cover every slot it serves: the slot of the largest c_y, whose tau
// (eq.5, eq.9) and level eps_K / c_y are the smallest, so the datapath covers every input any of
// its slots' comparators lets through.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "units/common.h"

namespace glint {

// Why a slot exists, for the elaboration report (empty when the unit was built from bare params).
struct SlotOrigin {
  std::size_t material = 0;
  std::vector<int> lights;  // the lights whose product with the material gives this c_y
  double c_y = 0;           // luminance of light x specular (Källberg eq.3; eq.6 for white)
  bool own_tau = false;     // the material has other slots: these lights change its tau
};

struct SlotPlan {
  std::vector<MaterialParams> params;  // per slot: its comparator's tau and level
  std::vector<std::uint32_t> group;    // per slot: the datapath group serving it
  std::vector<MaterialParams> groups;  // per group: the params its datapath is built from
  std::vector<SlotOrigin> origin;      // per slot, or empty
  // A chip of given capacity (units/chip.h, `--chip ram:slots=S,materials=M`): its threshold
  // table holds slot_capacity entries and every per-material table group_capacity, whatever the
  // stream; 0: sized to the stream (params.size(), groups.size()).
  std::size_t slot_capacity = 0;
  std::size_t group_capacity = 0;

  // One datapath group per slot, built from the slot's own params (no sharing).
  static SlotPlan per_slot(std::vector<MaterialParams> slots) {
    SlotPlan p;
    p.groups = slots;
    p.params = std::move(slots);
    p.group.resize(p.params.size());
    for (std::size_t s = 0; s < p.group.size(); ++s) p.group[s] = static_cast<std::uint32_t>(s);
    return p;
  }
};

// Checks that a plan is consistent: every slot names an existing group and every group serves a
// slot; origins, when given, one per slot; capacities, when given, in 1..kMaxSlotCapacity and
// holding the slots and groups. Throws std::invalid_argument.
void check_slot_plan(const SlotPlan& plan);

// The largest capacity a chip may have (slots or materials): 2^20 entries (a 20-bit id).
inline constexpr std::size_t kMaxSlotCapacity = std::size_t{1} << 20;

}  // namespace glint
