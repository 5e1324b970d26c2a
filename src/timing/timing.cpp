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

void TimingEngine::next_words(const std::uint64_t* words, std::size_t count) {
  // The first B requests (no credit term yet) and the very first (no order term) through next().
  std::size_t k = 0;
  for (; k < count && (index_ < retire_ring_.size() || !any_); ++k) next((words[k] >> 63) != 0);
  if (k == count) return;
  const std::uint64_t ii = static_cast<std::uint64_t>(timing_.ii);
  const std::uint64_t latency = static_cast<std::uint64_t>(timing_.latency);
  const std::size_t depth = retire_ring_.size();
  const bool always_ready = sink_.probability >= 1.0;
  std::uint64_t* const ring = retire_ring_.data();
  std::size_t at = ring_at_;
  std::uint64_t last_issue = last_issue_, last_retire = last_retire_;
  std::uint64_t last_compute = last_compute_issue_;
  bool any_compute = any_compute_;
  TimingStats s = stats_;
  const std::size_t first = k;
  for (; k < count; ++k) {
    const bool skipped = (words[k] >> 63) != 0;
    const std::uint64_t order = last_issue + 1;
    const std::uint64_t credit = ring[at] + 1;
    const std::uint64_t unit = (!skipped && any_compute) ? last_compute + ii : 0;
    const std::uint64_t issue = std::max(order, std::max(credit, unit));
    if (issue > order) {
      const std::uint64_t held = issue - order;
      if (credit >= unit) {
        s.stall_credit += held;
      } else {
        s.stall_unit += held;
      }
    }
    const std::uint64_t done = issue + 1 + (skipped ? 0 : latency);
    std::uint64_t c = std::max(done, last_retire + 1);
    if (!always_ready) {
      const std::uint64_t earliest = c;
      while (!sink_.ready(c)) ++c;
      s.sink_wait += c - earliest;
    }
    ring[at] = c;
    last_issue = issue;
    last_retire = c;
    if (!skipped) {
      last_compute = issue;
      any_compute = true;
      ++s.computed;
    }
    if (++at == depth) at = 0;
    const std::uint64_t lat = c - issue;  // results > 0: the first request went through next()
    s.latency_min = std::min(s.latency_min, lat);
    s.latency_max = std::max(s.latency_max, lat);
    s.latency_sum += lat;
  }
  s.results += count - first;
  s.cycles = last_retire + 1;
  stats_ = s;
  index_ += count - first;
  ring_at_ = at;
  last_issue_ = last_issue;
  last_retire_ = last_retire;
  last_compute_issue_ = last_compute;
  any_compute_ = any_compute;
}

}  // namespace glint
