// Switching activity of a lane on a request stream (issue 26 item 3): how many register bits
// toggle, and how many are clocked, stage by stage, when the requests go through the lane in
// order as it schedules them (timing/timing.h's recurrences, the sink always ready: the stream
// glint rtl's testbench offers).
//
// Toggles come from the bit-accurate staged evaluation (eval_staged, the values the SystemC model
// traces and glint rtl's registers hold): a register of width w holding request i's value after
// request i - 1's changes popcount((v_i ^ v_{i-1}) & (2^w - 1)) bits. Dynamic energy is a sum of
// such toggles weighted by each part's switched capacitance (the weights, at a node, are not
// here); what the tau skip saves is exactly these toggles, so the skip's effect depends on what
// the hardware does with a skipped request (Gating):
//   none     the datapath is fed every request; the comparator only zeroes the result: a skipped
//            request toggles the stages as a computed one does;
//   operand  a skipped request does not enter the datapath: its stage registers keep the last
//            computed request's values (operand isolation / enable-held registers), no toggles;
//   clock    as operand, and the stage registers are clock-gated on the skipped request's cycles:
//            their clock load is not switched either.
// The lane's cycles are its own schedule's, from reset to the cycle the last result leaves: a
// request the datapath takes waits for its initiation interval, one the comparator skips (and
// keeps out of the datapath) passes a cycle after the previous one, so an iterative unit with the
// skip spends far fewer cycles than requests x II. With gating none every request enters the
// datapath, so every one waits for the II. Every register bit is clocked once a cycle except
// where clock gating stops it (the stage registers then run II cycles per request they take):
// clocked_bits counts that load, which clock energy is proportional to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "timing/timing.h"

namespace glint {

class SpecularUnit;

enum class Gating : std::uint8_t { kNone, kOperand, kClock };
const char* to_string(Gating g);  // "none", "operand", "clock"
// "none", "operand" or "clock"; throws std::invalid_argument naming the value otherwise.
Gating parse_gating(const std::string& text);

struct StageActivity {
  std::string name;                // the stage's name in the unit's layout
  int bits = 0;                    // register bits of the stage (all its positions)
  std::uint64_t toggles = 0;       // register bit toggles over the stream
  std::uint64_t clocked_bits = 0;  // register bits clocked over the stream (bits x cycles)
};

struct LaneActivity {
  Gating gating = Gating::kNone;
  std::size_t requests = 0;  // the stream's requests
  std::size_t computed = 0;  // those the comparator kept
  std::uint64_t cycles = 0;  // the lane's schedule: reset to the last result's retire
  std::vector<StageActivity> stages;
  // Beside the unit's stages, for the energy (eval/energy.h; not in activity_json): the lane's
  // input t (in_bits wide) toggles at the port on every request (the tau comparator's operand),
  // and in the datapath's input register on the requests that enter it (the comparator register:
  // every request with gating none, computed ones otherwise); the merge buffer's entries
  // (buffer_depth words of out_bits, written in turn) toggle with each request's lane result (0
  // when skipped); the stage registers are clocked on clocked_cycles.
  int in_bits = 0, out_bits = 0;
  std::uint64_t port_toggles = 0, entry_toggles = 0, output_toggles = 0;
  std::uint64_t clocked_cycles = 0;
  // The lane's control flip-flops around the datapath (hdl/lane.cpp), their toggles as the
  // schedule determines them: the issue and head tags (one step mod B a request), the tags beside
  // the L + 1 positions and the bypass tag (copies of the issue tag), the in-flight credit counter
  // (+1 an issue, -1 a retire), the II counter, the bypass's and positions' valid bits (a rise and
  // a fall a run of consecutive issues) and the merge buffer's valid and skipped bits (an entry is
  // written only by a result that cannot leave as it arrives).
  std::uint64_t control_toggles = 0;

  std::uint64_t toggles() const;
  std::uint64_t clocked_bits() const;
};

// One request: the slot it reads and its t in the unit's input format.
struct ActivityRequest {
  std::size_t slot = 0;
  std::int64_t t_raw = 0;
};

// The activity of a request stream through one unit's pipeline, a request at a time in stream
// order. The registers start at 0 (the reset state), so the first request's set bits count as
// toggles.
class ActivityCounter {
 public:
  ActivityCounter(const SpecularUnit& unit, Gating gating);
  void add(std::size_t slot, std::int64_t t_raw);
  // The counts so far, the credits of the results still in flight returned as they drain.
  LaneActivity activity() const;
  const SpecularUnit& unit() const { return unit_; }

 private:
  const SpecularUnit& unit_;
  std::uint64_t ii_ = 1;
  TimingEngine schedule_;  // the lane's, the sink always ready
  LaneActivity activity_;
  std::vector<std::size_t> stage_of_;  // per flat register index of the staged values
  std::vector<int> width_of_;
  std::vector<std::int64_t> values_, held_;
  std::int64_t port_t_ = 0, entry_t_ = 0;
  std::vector<std::int64_t> entries_;  // the merge buffer's words
  std::size_t next_entry_ = 0;
  // The control registers' state (control_toggles).
  void count_control(const ResultTiming& r, bool skipped, bool enters);
  std::uint64_t tag_step_toggles_ = 0;  // issue_tag's toggles, stepping 0, 1, .. B - 1, 0, ..
  std::uint64_t in_flight_ = 0;
  std::deque<std::uint64_t> retires_;  // cycles of the retires not yet counted, in order
  // The cycle after the last bypassed and the last started request's issue (none yet: never).
  std::uint64_t last_bypass_ = ~std::uint64_t{0}, last_start_ = ~std::uint64_t{0};
  std::vector<bool> entry_skipped_;
};

// The report's "activity" entry (src/eval/sim_report.md) and its line in the text report.
nlohmann::json activity_json(const LaneActivity& a);
std::string format_activity(const nlohmann::json& activity);

// The same over a whole stream.
LaneActivity measure_activity(const SpecularUnit& unit, const std::vector<ActivityRequest>& stream,
                              Gating gating);

}  // namespace glint
