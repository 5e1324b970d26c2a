#include "rtl_model/fast_sim.h"

#include <algorithm>
#include <exception>
#include <systemc>

#include "eval/engine.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/sc_setup.h"

namespace glint {
namespace {

class FastLanes : public sc_core::sc_module {
 public:
  FastLanes(sc_core::sc_module_name name, const std::vector<const SpecularUnit*>& units,
            const SlotMap& slots, const std::function<bool(std::vector<VectorRow>&)>& next_block,
            const FastOptions& options, std::vector<LaneAccumulator>* accumulators,
            const std::function<void(const FastResult&)>& on_result)
      : sc_module(name),
        units_(units),
        slots_(slots),
        next_block_(next_block),
        options_(options),
        accumulators_(accumulators),
        on_result_(on_result) {
    for (const SpecularUnit* u : units) engines_.emplace_back(u->timing(), options.sink);
    SC_HAS_PROCESS(FastLanes);
    SC_THREAD(run);
  }

  // An exception thrown inside the thread (a bad row, a failing callback) would reach SystemC as
  // an "uncaught exception" report; it is kept here and rethrown after sc_start() returns.
  std::exception_ptr error() const { return error_; }

  std::vector<TimingStats> stats() const {
    std::vector<TimingStats> s;
    for (const auto& e : engines_) s.push_back(e.stats());
    return s;
  }

 private:
  void run() {
    try {
      work();
    } catch (...) {
      error_ = std::current_exception();
    }
  }

  // Temporal decoupling: one wait per batch, by the cycles the batch spanned (in the engine, the
  // cycles merged so far: a batch's last window is merged beside the next batch's rows, and the
  // last wait after EvalEngine::finish()).
  void advance(std::uint64_t& now_cycles) {
    std::uint64_t end = now_cycles;
    for (const TimingEngine& e : engines_) end = std::max(end, e.stats().cycles);
    if (end > now_cycles) {
      wait(sc_core::sc_time(options_.clock_period_ns * static_cast<double>(end - now_cycles),
                            sc_core::SC_NS));
      now_cycles = end;
    }
  }

  void work() {
    if (accumulators_ && !accumulators_->empty() && !on_result_) {
      work_in_engine();
    } else {
      work_by_row();
    }
    // No clock and no further events: sc_start() returns on its own (no sc_stop, whose info
    // message would land on stdout).
  }

  void work_in_engine() {
    std::vector<LaneAccumulator*> lanes;
    std::vector<TimingEngine*> timing;
    for (std::size_t l = 0; l < units_.size(); ++l) {
      lanes.push_back(&(*accumulators_)[l]);
      timing.push_back(&engines_[l]);
    }
    EngineOptions eo;
    eo.threads = options_.threads;
    eo.window_rows = 32768;
    EvalEngine engine(slots_, std::move(lanes), std::move(timing), eo);
    const std::size_t batch = std::max(kEngineBatch, options_.batch);
    std::vector<VectorRow> rows, block;
    std::uint64_t now_cycles = 0;
    bool more = true;
    while (more) {
      more = next_block_(block);
      if (more && rows.empty() && block.size() >= batch) {
        // A block as large as a batch goes in as it is: no copy, and the source keeps its
        // storage (a vector it refills in place).
        engine.add_open(block.data(), block.size());
        advance(now_cycles);
        continue;
      }
      if (more) rows.insert(rows.end(), block.begin(), block.end());
      if (!rows.empty() && (rows.size() >= batch || !more)) {
        engine.add_open(rows.data(), rows.size());
        advance(now_cycles);
        rows.clear();
      }
    }
    engine.finish();
    advance(now_cycles);
  }

  void work_by_row() {
    const std::size_t batch = std::max<std::size_t>(1, options_.batch);
    std::vector<VectorRow> rows(batch);
    std::vector<RowReference> refs(batch);
    std::vector<std::size_t> slot(batch);
    const bool stats = accumulators_ && !accumulators_->empty();
    std::uint64_t now_cycles = 0;
    for (;;) {
      std::size_t n = 0;
      while (n < batch && next_row(rows[n])) ++n;
      if (n == 0) break;
      for (std::size_t i = 0; i < n; ++i) {
        slot[i] = slots_.slot(rows[i]);
        if (stats) refs[i] = make_reference(slots_, slot[i], rows[i].t);
      }
      for (std::size_t l = 0; l < units_.size(); ++l) {
        const SpecularUnit& u = *units_[l];
        TimingEngine& engine = engines_[l];
        const QFormat in = u.in_format();
        for (std::size_t i = 0; i < n; ++i) {
          const std::int64_t t_raw = quantize_input(rows[i].t, in);
          const bool skipped = u.skip(slot[i], t_raw);
          const std::int64_t out = skipped ? 0 : u.eval(slot[i], t_raw);
          const ResultTiming timing = engine.next(skipped);
          if (stats) (*accumulators_)[l].add(slot[i], refs[i], t_raw, skipped, out);
          if (on_result_) on_result_(FastResult{l, &rows[i], t_raw, skipped, out, timing});
        }
      }
      advance(now_cycles);
    }
  }

  const std::vector<const SpecularUnit*>& units_;
  const SlotMap& slots_;
  const std::function<bool(std::vector<VectorRow>&)>& next_block_;
  // Rows of the last block not yet taken a row at a time (next_row).
  std::vector<VectorRow> pending_;
  std::size_t pending_at_ = 0;
  bool ended_ = false;

  bool next_row(VectorRow& row) {
    while (pending_at_ == pending_.size()) {
      if (ended_ || !next_block_(pending_)) {
        // The source may have changed the block before saying there is no more.
        ended_ = true;
        pending_.clear();
        pending_at_ = 0;
        return false;
      }
      pending_at_ = 0;
    }
    row = pending_[pending_at_++];
    return true;
  }
  FastOptions options_;
  std::vector<LaneAccumulator>* accumulators_;
  const std::function<void(const FastResult&)>& on_result_;
  std::vector<TimingEngine> engines_;
  std::exception_ptr error_;
};

}  // namespace

std::vector<TimingStats> run_fast_blocks(
    const std::vector<const SpecularUnit*>& units, const SlotMap& slots,
    const std::function<bool(std::vector<VectorRow>&)>& next_block, const FastOptions& options,
    std::vector<LaneAccumulator>* accumulators,
    const std::function<void(const FastResult&)>& on_result) {
  FastLanes lanes("fast", units, slots, next_block, options, accumulators, on_result);
  sc_core::sc_start();
  resync_sanitizer_stack();
  if (lanes.error()) std::rethrow_exception(lanes.error());
  return lanes.stats();
}

std::vector<TimingStats> run_fast(const std::vector<const SpecularUnit*>& units,
                                  const SlotMap& slots,
                                  const std::function<bool(VectorRow&)>& next_row,
                                  const FastOptions& options,
                                  std::vector<LaneAccumulator>* accumulators,
                                  const std::function<void(const FastResult&)>& on_result) {
  const std::size_t block = std::max<std::size_t>(1, options.batch);
  return run_fast_blocks(
      units, slots,
      [&](std::vector<VectorRow>& rows) {
        rows.resize(block);
        std::size_t n = 0;
        while (n < rows.size() && next_row(rows[n])) ++n;
        rows.resize(n);
        return n > 0;
      },
      options, accumulators, on_result);
}

}  // namespace glint
