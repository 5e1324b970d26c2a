#include "timing/timing.h"

#include <algorithm>
#include <stdexcept>

namespace glint {

TimingEngine::TimingEngine(const UnitTiming& timing, const SinkReady& sink)
    : timing_(timing), sink_(sink) {
  if (timing.latency < 0 || timing.ii < 1 || timing.buffer_depth < 1)
    throw std::invalid_argument("timing: latency >= 0, ii >= 1 and buffer depth >= 1 required");
  if (!(sink.probability > 0.0))
    throw std::invalid_argument("timing: sink ready probability must be > 0");
  retire_ring_.assign(static_cast<std::size_t>(timing.buffer_depth), 0);
}

ResultTiming TimingEngine::next(bool skipped) {
  const std::size_t slot = ring_at_;
  const std::uint64_t order = any_ ? last_issue_ + 1 : 0;
  const std::uint64_t credit = index_ >= retire_ring_.size() ? retire_ring_[slot] + 1 : 0;
  const std::uint64_t unit =
      (!skipped && any_compute_) ? last_compute_issue_ + static_cast<std::uint64_t>(timing_.ii) : 0;
  ResultTiming r;
  r.issue = std::max({order, credit, unit});
  // Stall attribution: the binding constraint beyond one-per-cycle order.
  if (r.issue > order) {
    const std::uint64_t held = r.issue - order;
    if (credit >= unit) {
      stats_.stall_credit += held;
    } else {
      stats_.stall_unit += held;
    }
  }
  r.done = r.issue + 1 + (skipped ? 0 : static_cast<std::uint64_t>(timing_.latency));
  std::uint64_t c = std::max(r.done, any_ ? last_retire_ + 1 : 0);
  const std::uint64_t earliest = c;
  if (sink_.probability < 1.0)
    while (!sink_.ready(c)) ++c;
  r.retire = c;
  stats_.sink_wait += c - earliest;

  retire_ring_[slot] = r.retire;
  last_issue_ = r.issue;
  last_retire_ = r.retire;
  if (!skipped) {
    last_compute_issue_ = r.issue;
    any_compute_ = true;
    ++stats_.computed;
  }
  any_ = true;
  ++index_;
  if (++ring_at_ == retire_ring_.size()) ring_at_ = 0;

  const std::uint64_t lat = r.retire - r.issue;
  stats_.latency_min = stats_.results ? std::min(stats_.latency_min, lat) : lat;
  stats_.latency_max = std::max(stats_.latency_max, lat);
  stats_.latency_sum += lat;
  ++stats_.results;
  stats_.cycles = r.retire + 1;
  return r;
}

}  // namespace glint
