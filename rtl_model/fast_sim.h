// Fast mode: transaction-level simulation of the specular lanes with temporal decoupling.
//
// One SC_THREAD reads requests in batches, runs every lane's datapath (the same functions the
// clocked modules call) and schedules each result with TimingEngine, the recurrences the clocked
// mode implements cycle by cycle (src/timing.h). SystemC time advances once per batch, by the
// cycles the batch took: cycle stamps come from latency, II and stalls instead of from clock edges,
// which is what makes long streams cheap. Both modes must give identical outputs and cycle counts
// (tests/rtl_model/test_rtl_*.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "timing/timing.h"
#include "units/catalogue.h"

namespace glint {

inline constexpr std::size_t kEngineBatch = 262144;

struct FastOptions {
  SinkReady sink;
  // Requests per temporal-decoupling quantum when results go out a row at a time (on_result);
  // the evaluation engine (eval/engine.h) takes at least kEngineBatch per quantum, so that its
  // threads stay busy.
  std::size_t batch = 4096;
  int threads = 1;  // the engine's threads (results do not depend on it)
  double clock_period_ns = 1.0;
};

struct FastResult {
  std::size_t lane;
  const VectorRow* row;
  std::int64_t t_raw;
  bool skipped;
  std::int64_t out_raw;
  ResultTiming timing;
};

// Elaborates the fast-mode module for `units` (one lane each, fed the same stream), runs it to the
// end of the stream and returns each lane's timing statistics. `accumulators` (one per lane, may be
// empty) collect the accuracy statistics; `on_result` (may be empty) sees every result in order.
// With accumulators and no on_result the lanes run in the evaluation engine; otherwise a row at a
// time (the same results and cycles).
// Elaborates SystemC: call once per process.
std::vector<TimingStats> run_fast(const std::vector<const SpecularUnit*>& units,
                                  const SlotMap& slots,
                                  const std::function<bool(VectorRow&)>& next_row,
                                  const FastOptions& options,
                                  std::vector<LaneAccumulator>* accumulators,
                                  const std::function<void(const FastResult&)>& on_result = {});

// The same, fed a block of rows at a time: `next_block` replaces the contents of its argument
// with the next rows of the stream and returns false at its end (VectorReader::next_block's
// contract). A call per row through std::function cost ~40 instructions a row, more than the
// engine's own timing recurrences.
std::vector<TimingStats> run_fast_blocks(
    const std::vector<const SpecularUnit*>& units, const SlotMap& slots,
    const std::function<bool(std::vector<VectorRow>&)>& next_block, const FastOptions& options,
    std::vector<LaneAccumulator>* accumulators,
    const std::function<void(const FastResult&)>& on_result = {});

}  // namespace glint
