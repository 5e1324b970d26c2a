#include "rtl_model/scoreboard.h"

#include <algorithm>

namespace glint::rtl {

Scoreboard::Scoreboard(sc_core::sc_module_name name, const SpecularUnit& unit,
                       const SinkReady& sink, const RowRing& rows, SimControl& control,
                       Callback on_result, bool expect_none, bool tracing)
    : sc_core::sc_module(name),
      head_valid("head_valid"),
      head("head"),
      ready("ready", sink.ready(0)),
      unit_(unit),
      sink_(sink),
      rows_(rows),
      control_(control),
      on_result_(std::move(on_result)),
      tracing_(tracing),
      ready_now_(sink.ready(0)),
      result_trace_(unit.out_format().width(), unit.out_format().is_signed) {
  if (expect_none) {
    done_ = true;
    past_window_ = true;
    control_.lane_done(0);
    control_.lane_past_window(0);
  }
}

void Scoreboard::tick() {
  const std::uint64_t c = cycle_++;
  bool retired = false;
  if (head_valid.now()) {
    if (ready_now_) {
      retire(head.now(), c);
      retired = true;
    } else {
      ++stats_.sink_wait;
    }
  }
  ready_now_ = sink_.ready(c + 1);
  ready.write(ready_now_);
  if (tracing_) retire_trace_ = retired;
}

void Scoreboard::retire(const Result& r, std::uint64_t cycle) {
  const ResultTiming t{r.issue, r.done, cycle};
  const bool skipped = unit_.skip(r.slot, r.t_raw);
  if (r.seq != next_seq_ || r.skipped != skipped ||
      r.value != unit_.eval_with_skip(r.slot, r.t_raw))
    ++mismatches_;
  ++next_seq_;

  const std::uint64_t latency = cycle - r.issue;
  stats_.latency_min = stats_.results ? std::min(stats_.latency_min, latency) : latency;
  stats_.latency_max = std::max(stats_.latency_max, latency);
  stats_.latency_sum += latency;
  ++stats_.results;
  if (!r.skipped) ++stats_.computed;
  stats_.cycles = cycle + 1;
  if (tracing_) {
    result_trace_.set(r.value);
    seq_trace_.set(static_cast<std::int64_t>(r.seq & 0xffffffffu));
  }

  if (on_result_) {
    try {
      on_result_(rows_.at(r.seq), r, t);
    } catch (...) {
      control_.fail(std::current_exception());
    }
  }
  if (!past_window_ && (r.seq >= control_.window_last() || r.last)) {
    past_window_ = true;
    control_.lane_past_window(cycle);
  }
  if (r.last && !done_) {
    done_ = true;
    control_.lane_done(cycle);
  }
}

void Scoreboard::add_traces(VcdWriter& vcd, const std::string& prefix) const {
  const std::string p = prefix + ".sink.";
  trace_bool(vcd, retire_trace_, p + "valid");
  trace_bool(vcd, ready, p + "ready");
  trace_raw(vcd, seq_trace_, p + "seq");
  trace_raw(vcd, result_trace_, p + "result", unit_.out_format().frac_bits);
}

}  // namespace glint::rtl
