// Scoreboard: the lane's sink. Its `ready` is registered: the value visible at edge c is
// SinkReady::ready(c), the deterministic backpressure pattern TimingEngine uses. At an edge where
// the merge head is valid and ready is high the head retires (cycle r_i); a valid head held by a
// low ready counts one sink-wait cycle.
//
// For every retired result it checks the value and the skip flag against the datapath
// (SpecularUnit::eval_with_skip / skip) and the stream order, counts mismatches (0 in a correct
// model), fills the lane's TimingStats (results, computed, cycles, sink_wait, latency) exactly as
// TimingEngine does, and hands the result to a callback with its row and ResultTiming.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/rtl_common.h"
#include "rtl_model/sim_control.h"
#include "rtl_model/vector_source.h"
#include "timing/timing.h"
#include "units/catalogue.h"

namespace glint::rtl {

class Scoreboard : public sc_core::sc_module, public Traceable, public ClockedStage {
 public:
  using Callback =
      std::function<void(const VectorRow& row, const Result& result, const ResultTiming& timing)>;

  In<bool> head_valid;
  In<Result> head;
  Register<bool> ready;  // registered: SinkReady::ready(c) at edge c

  // `expect_none`: the lane's stream is empty (the lane is done from the start).
  Scoreboard(sc_core::sc_module_name name, const SpecularUnit& unit, const SinkReady& sink,
             const RowRing& rows, SimControl& control, Callback on_result, bool expect_none,
             bool tracing);

  // results, computed, cycles, sink_wait and latency; the comparator adds the stall counts.
  const TimingStats& stats() const { return stats_; }
  std::uint64_t mismatches() const { return mismatches_; }
  bool done() const { return done_; }

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override;
  void tick() override;

 private:
  void retire(const Result& r, std::uint64_t cycle);

  const SpecularUnit& unit_;
  const SinkReady sink_;
  const RowRing& rows_;
  SimControl& control_;
  Callback on_result_;
  const bool tracing_;
  bool ready_now_;
  bool done_ = false;
  bool past_window_ = false;
  std::uint64_t cycle_ = 0;
  std::uint64_t next_seq_ = 0;
  std::uint64_t mismatches_ = 0;
  TimingStats stats_;

  bool retire_trace_ = false;
  RawBits result_trace_;
  RawBits seq_trace_{32, false};  // the retired request's id
};

}  // namespace glint::rtl
