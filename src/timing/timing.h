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

// Every field equal: how the clocked model, the fast mode's merge and next() are held to one
// another (a field added above belongs here too).
inline bool operator==(const TimingStats& a, const TimingStats& b) {
  return a.results == b.results && a.computed == b.computed && a.cycles == b.cycles &&
         a.stall_credit == b.stall_credit && a.stall_unit == b.stall_unit &&
         a.sink_wait == b.sink_wait && a.latency_min == b.latency_min &&
         a.latency_max == b.latency_max && a.latency_sum == b.latency_sum;
}
inline bool operator!=(const TimingStats& a, const TimingStats& b) {
  return !(a == b);
}

class TimingEngine {
 public:
  TimingEngine(const UnitTiming& timing, const SinkReady& sink);

  // Schedules the next request in stream order. O(1); inline, since the evaluation engine calls
  // it per request in its sequential merge.
  ResultTiming next(bool skipped) {
    return step(state_, retire_ring_.data(), sink_.probability >= 1.0, skipped);
  }
  // next() on each of `count` requests whose skip flags are bit 63 of `words` (the evaluation
  // engine's digest words), with the state in locals: next() keeps every statistic in memory,
  // which cost ~65 instructions a request.
  void next_words(const std::uint64_t* words, std::size_t count) {
    next_words(words, count, [](std::size_t) {});
  }
  // The same, calling also(k) for each request k in the loop: a caller's own sequential fold over
  // the same requests (the evaluation engine's digest) then overlaps the recurrences' chain of
  // dependent operations instead of following it.
  template <class Also>
  void next_words(const std::uint64_t* words, std::size_t count, const Also& also) {
    State st = state_;
    std::uint64_t* const ring = retire_ring_.data();
    const bool always_ready = sink_.probability >= 1.0;
    for (std::size_t k = 0; k < count; ++k) {
      step(st, ring, always_ready, (words[k] >> 63) != 0);
      also(k);
    }
    state_ = st;
  }
  TimingStats stats() const {
    TimingStats s = state_.stats;
    if (s.results == 0) s.latency_min = 0;
    return s;
  }
  const UnitTiming& timing() const { return timing_; }

 private:
  // What the recurrences carry from one request to the next. The order and retire terms of the
  // first request and the credit term of the first B are 0: last_issue and last_retire start at
  // -1 (their + 1 wraps to 0), and the ring holds each credit's first usable cycle, r + 1, with 0
  // before any result has used the entry.
  struct State {
    std::uint64_t last_issue = ~std::uint64_t{0};
    std::uint64_t last_retire = ~std::uint64_t{0};
    std::uint64_t last_compute_issue = 0;
    bool any_compute = false;
    std::size_t ring_at = 0;  // request index mod B, counted: no division per request
    TimingStats stats = untouched();
  };
  // latency_min starts at the largest value, so the minimum needs no first-result test per
  // request; stats() reports 0 until there is a result.
  static TimingStats untouched() {
    TimingStats s;
    s.latency_min = ~std::uint64_t{0};
    return s;
  }
  // One request through the recurrences: next() on the engine's state, next_words() on a copy in
  // locals (the one definition of both).
  ResultTiming step(State& st, std::uint64_t* credit_ring, bool always_ready, bool skipped);

  UnitTiming timing_;
  SinkReady sink_;
  State state_;
  std::vector<std::uint64_t> retire_ring_;  // r_{i-B} + 1 .. r_{i-1} + 1 (0: not used yet)
};

inline ResultTiming TimingEngine::step(State& st, std::uint64_t* credit_ring, bool always_ready,
                                       bool skipped) {
  const std::uint64_t order = st.last_issue + 1;
  const std::uint64_t credit = credit_ring[st.ring_at];
  const std::uint64_t unit = (!skipped && st.any_compute)
                                 ? st.last_compute_issue + static_cast<std::uint64_t>(timing_.ii)
                                 : 0;
  ResultTiming r;
  r.issue = std::max(order, std::max(credit, unit));  // not max({...}): ~15 % slower here
  // Stall attribution: the binding constraint beyond one-per-cycle order.
  TimingStats& s = st.stats;
  if (r.issue > order) {
    const std::uint64_t held = r.issue - order;
    if (credit >= unit) {
      s.stall_credit += held;
    } else {
      s.stall_unit += held;
    }
  }
  r.done = r.issue + 1 + (skipped ? 0 : static_cast<std::uint64_t>(timing_.latency));
  std::uint64_t c = std::max(r.done, st.last_retire + 1);
  const std::uint64_t earliest = c;
  if (!always_ready)
    while (!sink_.ready(c)) ++c;
  r.retire = c;
  s.sink_wait += c - earliest;

  credit_ring[st.ring_at] = r.retire + 1;
  if (++st.ring_at == retire_ring_.size()) st.ring_at = 0;
  st.last_issue = r.issue;
  st.last_retire = r.retire;
  if (!skipped) {
    st.last_compute_issue = r.issue;
    st.any_compute = true;
    ++s.computed;
  }

  const std::uint64_t lat = r.retire - r.issue;
  s.latency_min = std::min(s.latency_min, lat);
  s.latency_max = std::max(s.latency_max, lat);
  s.latency_sum += lat;
  ++s.results;
  s.cycles = r.retire + 1;
  return r;
}

}  // namespace glint
