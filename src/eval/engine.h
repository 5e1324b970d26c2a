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
// squares, the digest and the timing recurrences, which are sequential folds). With few lanes a
// run's shared work and its pass through every lane are one task (while its rows are in the
// core's cache; a run that meets a slot not yet begun waits for it), and the merges of one window
// overlap the runs of the next; with many (at least two per thread), each lane's window is one
// task, and the threads take the windows of a span of several in any order that keeps each lane's
// in stream order: no thread waits at the end of a window for the others.
// Side work (the reader parsing the next rows) then runs beside the lanes' windows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
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

  // Work done beside an add()'s rows, a step per call, on one thread at a time: each call returns
  // whether it wants another. add() returns once it has stopped.
  using SideWork = std::function<bool()>;

  // The next rows of the stream through every lane; each lane's statistics are complete when it
  // returns. `out` (may be null) receives every row's reference and each lane's results. `side`
  // (may be empty) runs beside the lanes when overlaps_side_work() and the runs are the engine's
  // choice (run_rows 0), else before the rows.
  void add(const VectorRow* rows, std::size_t count, BatchResults* out = nullptr,
           const SideWork& side = {});
  // add() but for the last window's merges, which may wait for the next add_open() or add() to
  // run beside its rows (a stream read in blocks would otherwise merge on one thread at the end of
  // every block): the lanes' statistics and timing are complete after finish().
  void add_open(const VectorRow* rows, std::size_t count);
  void finish();

  // The deferral bound of the last rows, 2^deferred_exponent(): references at most that (of rows
  // every lane skips) were left to the lanes (eval/deferral.h).
  int deferred_exponent() const { return deferral_.exponent(); }

  // Whether an engine of `lanes` lanes on `threads` threads runs side work beside its lanes:
  // whole windows per lane (at least two lanes per thread), more than one thread.
  static bool overlaps_side_work(std::size_t lanes, int threads);

 private:
  void add_rows(const VectorRow* rows, std::size_t count, BatchResults* out, const SideWork& side,
                bool complete);
  bool whole_windows() const;
  std::size_t merge_group_size() const;
  void add_window(const VectorRow* rows, std::size_t count, std::size_t offset, BatchResults* out);
  void add_span(const VectorRow* rows, std::size_t count, std::size_t offset, BatchResults* out,
                const SideWork& side, bool& side_more);
  void prepare(const VectorRow* rows, std::size_t count, std::size_t offset, BatchResults* out,
               std::size_t at = 0);
  void prepare_run(const VectorRow* rows, std::size_t a, std::size_t b, std::size_t offset,
                   BatchResults* out, std::size_t at, std::vector<std::uint32_t>& fresh);
  bool begin_fresh(const std::vector<std::vector<std::uint32_t>>& fresh);
  void run_group(std::size_t first, std::size_t size, const RowsView& view, std::size_t count,
                 std::size_t offset, BatchResults* out);
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
  SharedDeferral deferral_;
  std::vector<double> t_;
  std::vector<std::uint32_t> slot_;
  std::vector<double> reference_;
  // Per lane, per run: the partials of this window and (when merges overlap) of the last one.
  std::vector<std::vector<LanePartial>> partials_[2];
  int current_ = 0;
  bool pending_ = false;  // partials_[1 - current_] still to merge
};

}  // namespace glint
