// Energy of a request stream through one lane at a node (issue 26, item 3): the lane's switching
// activity on the stream (eval/activity.h) weighted by the node's per-part energies
// (cost/energy.h), split by stage and into register, clock, datapath and leakage energy. `glint
// sim` and `glint render` both count with lane_energy, so the same requests give the same figure.
//
// Per stage of the lane: the comparator stage, the unit's stages (its layout, as the activity
// counts them) and the merge buffer with the lane's control (placed after the last stage):
//   register   the stage's register bit toggles x register_bit: the comparator register's (t,
//              loaded by the requests that enter the datapath), the unit's staged values', the
//              merge buffer entries' (each request's result written in turn), and the lane's
//              tags, counters and valid bits (LaneActivity::control_toggles, in the merge
//              buffer's stage).
//   clock      flip-flops the stage holds (its inventory's registers, a RAM table's storage) x the
//              cycles they are clocked x clock_bit: the comparator's and unit's registers on the
//              cycles clock gating leaves (all with gating none or operand), tables and the merge
//              buffer's on every cycle (they are loaded when materials load, or serve every
//              request).
//   datapath   each part of the stage: its switching bits x pJ a bit (cost/energy.h) x the summed
//              toggle fraction of the registers feeding the stage over the stream (toggles /
//              bits): the lane's input t for the comparator stage, the comparator register for
//              the unit's first stage, the previous stage's registers for the others, the results
//              written for the merge buffer. A pipelined divider's rows are all placed in its first
//              row's stage.
//   leakage    the stage's area at the node x leakage_nw_per_um2 x cycles x the clock period, the
//              lane at its maximum clock (UnitCost::critical_path_ns).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cost/cost_model.h"
#include "cost/energy.h"
#include "eval/activity.h"

namespace glint {

struct EnergyParts {
  double register_pj = 0, clock_pj = 0, datapath_pj = 0, leakage_pj = 0;
  // datapath_pj by the kind of its weight (cost/energy.h), and the switching bits each kind's
  // weight multiplies (summed over the stream: part_switching_bits x its input's toggle fraction).
  KindArray datapath_kinds{}, switching_bits{};
  double total() const { return register_pj + clock_pj + datapath_pj + leakage_pj; }
  EnergyParts& operator+=(const EnergyParts& o);
};

struct StageEnergy {
  std::string stage;
  EnergyParts pj;  // over the stream
};

struct LaneEnergy {
  std::string node;
  Gating gating = Gating::kNone;
  std::size_t requests = 0, computed = 0;
  std::uint64_t cycles = 0;
  double clock_ns = 0;
  std::vector<StageEnergy> stages;  // comparator, the unit's stages, merge buffer
  EnergyParts total;                // the sum of the stages

  double per_request() const;
  double per_computed() const;
};

LaneEnergy lane_energy(const UnitCost& cost, const LaneActivity& activity, const EnergyWeights& w);

// The report's "energy" entry (src/eval/sim_report.md): totals and pJ per request, per computed
// request and, given, per shaded pixel; the parts, the datapath's split by kind and the stages in
// pJ per request.
nlohmann::json energy_json(const LaneEnergy& e,
                           std::optional<std::uint64_t> shaded_pixels = std::nullopt);
// Its line in the text reports.
std::string format_energy(const nlohmann::json& energy);

}  // namespace glint
