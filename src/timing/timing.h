// The cycle-level behaviour of one specular lane, as recurrences: the single definition of timing
// that both SystemC modes must reproduce (rtl_model/ clocked processes cycle by cycle, the fast
// mode by calling TimingEngine directly per batch).
//
// A lane: source -> comparator -> (compute unit | bypass) -> in-order merge buffer -> sink.
//   - The source always has the next request ready (a vector file or memory stream).
//   - The comparator accepts ("issues") at most one request per cycle. Request i issues at
//         a_i = max(a_{i-1} + 1,                      one per cycle
//                   r_{i-B} + 1          (i >= B),     a merge-buffer credit: B entries, a credit
//                                                      freed at retire cycle r is usable at r + 1
//                   c_prev + II          (computed),   the compute unit's initiation interval
//                   0)
//     where c_prev is the issue cycle of the previous computed (not skipped) request.
//   - Its result is done at d_i = a_i + 1 (skipped: the bypass register) or a_i + 1 + L
//     (computed: comparator register + L unit stages).
//   - The sink retires in order, one per cycle, when it is ready:
//         r_i = min { c >= max(d_i, r_{i-1} + 1) : ready(c) }.
//   - Backpressure therefore propagates from the sink through the merge buffer's credits to the
//     comparator; the compute pipeline itself never stalls (its slot is reserved at issue).
// Cycle counts: total = r_last + 1; latency_i = r_i - a_i; stall cycles = cycles in which the
// comparator held a request it could not issue (split by cause).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace glint {

// Timing parameters of one unit, plain data (derived from its SPEC).
struct UnitTiming {
  int latency = 1;       // L: compute-unit stages
  int ii = 1;            // initiation interval of the compute unit
  int buffer_depth = 8;  // B: merge-buffer entries (credits)
};

// Deterministic sink backpressure: ready in a cycle with the given probability, from a hash of
// (seed, cycle) so every mode and every re-run sees the same pattern.
// The least sink-ready probability a run accepts: the sink then takes a result every 1/p cycles
// on average, so a run lasts ~vectors/p cycles; much below this a run is, in effect, endless.
inline constexpr double kMinSinkReady = 0.01;

struct SinkReady {
  double probability = 1.0;
  std::uint64_t seed = 0;

  bool ready(std::uint64_t cycle) const {
    if (probability >= 1.0) return true;
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (cycle + 1);  // splitmix64
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53 < probability;
  }
};

struct ResultTiming {
  std::uint64_t issue = 0;   // a_i
  std::uint64_t done = 0;    // d_i
  std::uint64_t retire = 0;  // r_i
};

struct TimingStats {
  std::uint64_t results = 0;
  std::uint64_t computed = 0;
  std::uint64_t cycles = 0;        // r_last + 1
  std::uint64_t stall_credit = 0;  // issue held by a full merge buffer
  std::uint64_t stall_unit = 0;    // issue held by the compute unit's II
  std::uint64_t sink_wait = 0;     // done results held by sink backpressure (result-cycles)
  std::uint64_t latency_min = 0, latency_max = 0, latency_sum = 0;

  std::uint64_t stall_cycles() const { return stall_credit + stall_unit; }
  double latency_mean() const { return results ? double(latency_sum) / double(results) : 0.0; }
  double throughput() const { return cycles ? double(results) / double(cycles) : 0.0; }
};

class TimingEngine {
 public:
  TimingEngine(const UnitTiming& timing, const SinkReady& sink);

  // Schedules the next request in stream order. O(1); inline, since the evaluation engine calls
  // it per request in its sequential merge.
  ResultTiming next(bool skipped);
  // next() on each of `count` requests whose skip flags are bit 63 of `words` (the evaluation
  // engine's digest words), the same recurrences and statistics with the state in locals: next()
  // keeps every statistic in memory, which cost ~65 instructions a request.
  void next_words(const std::uint64_t* words, std::size_t count);
  const TimingStats& stats() const { return stats_; }
  const UnitTiming& timing() const { return timing_; }

 private:
  UnitTiming timing_;
  SinkReady sink_;
  TimingStats stats_;
  std::vector<std::uint64_t> retire_ring_;  // r_{i-B} .. r_{i-1}
  std::size_t ring_at_ = 0;                 // index_ mod B, counted: no division per request
  std::uint64_t index_ = 0;
  std::uint64_t last_issue_ = 0, last_retire_ = 0, last_compute_issue_ = 0;
  bool any_ = false, any_compute_ = false;
};

inline ResultTiming TimingEngine::next(bool skipped) {
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
