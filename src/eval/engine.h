// The evaluation engine under `glint eval`, `glint sim`'s fast mode, `glint sweep` and the
// renderer: a stream of rows through every lane (a unit's datapath, its accuracy statistics and
// optionally its timing recurrences), on several threads, with the results of one thread bit for
// bit.
//
// Rows go in windows. Per window: the shared work on threads (each row's slot and float
// reference, computed once for every lane), the slots first used in it begun in stream order
// (their contracts), then each lane's rows in runs on threads (LaneAccumulator::accumulate:
// quantization, comparator, the datapath's result from the per-code memo, the statistics that
// merge exactly) and each lane's runs merged in stream order (LaneAccumulator::merge: the sum of
// squares, the digest and the timing recurrences, which are sequential folds). With few lanes the
// merges of one window overlap the runs of the next; with many, each lane's window is one task.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "eval/evaluate.h"
#include "io/thread_pool.h"
#include "timing/timing.h"

namespace glint {

struct EngineOptions {
  int threads = 1;
  std::size_t window_rows = 65536;  // rows per window (memory: ~16 bytes per row and lane)
  std::size_t run_rows = 0;         // rows per run of a lane; 0: chosen from threads and lanes
};

class EvalEngine {
 public:
  // One lane per accumulator; timing (empty, or one per lane, null for none) gets each lane's skip
  // pattern in stream order. The accumulators, engines and slots must outlive the engine.
  EvalEngine(const SlotMap& slots, std::vector<LaneAccumulator*> lanes,
             std::vector<TimingEngine*> timing, const EngineOptions& options);
  ~EvalEngine();

  // The next rows of the stream through every lane; each lane's statistics are complete when it
  // returns. `out` (may be null) receives every row's reference and each lane's results.
  void add(const VectorRow* rows, std::size_t count, BatchResults* out = nullptr);

 private:
  void add_window(const VectorRow* rows, std::size_t count, std::size_t offset, BatchResults* out);
  void prepare(const VectorRow* rows, std::size_t count, std::size_t offset, BatchResults* out);
  std::size_t runs_per_lane(std::size_t count) const;
  void merge_pending();
  void merge(const std::vector<LanePartial>& runs, std::size_t lane);

  const SlotMap& slots_;
  std::vector<LaneAccumulator*> lanes_;
  std::vector<TimingEngine*> timing_;
  EngineOptions options_;
  ThreadPool pool_;
  std::vector<std::uint8_t> slot_known_;  // slots begun in every lane
  std::vector<double> deferred_t_;        // per slot (deferred_t)
  std::vector<double> defer_t_;           // the same, 0 where some lane computes such rows
  std::vector<double> t_;
  std::vector<std::uint32_t> slot_;
  std::vector<double> reference_;
  // Per lane, per run: the partials of this window and (when merges overlap) of the last one.
  std::vector<std::vector<LanePartial>> partials_[2];
  int current_ = 0;
  bool pending_ = false;  // partials_[1 - current_] still to merge
};

}  // namespace glint
