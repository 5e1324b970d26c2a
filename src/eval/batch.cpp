#include "eval/engine.h"
#include "eval/evaluate.h"

namespace glint {

void Evaluator::add_batch(const VectorRow* rows, std::size_t count, BatchResults& out,
                          int threads) {
  run_engine(rows, count, &out, threads);
}

void Evaluator::add_rows(const VectorRow* rows, std::size_t count, int threads,
                         const std::function<bool()>& side) {
  run_engine(rows, count, nullptr, threads, side);
}

bool Evaluator::overlaps_side_work(int threads) const {
  return EvalEngine::overlaps_side_work(lanes_.size(), threads);
}

void Evaluator::run_engine(const VectorRow* rows, std::size_t count, BatchResults* out, int threads,
                           const std::function<bool()>& side) {
  if (!engine_ || engine_threads_ != threads) {
    std::vector<LaneAccumulator*> lanes;
    for (auto& lane : lanes_) lanes.push_back(&lane);
    EngineOptions options;
    options.threads = threads;
    // Half the engine's default: the last window of a span, which one thread runs while the
    // other may have nothing left, costs less (glint eval on two threads: wall x0.97).
    options.window_rows = 32768;
    engine_ = std::make_unique<EvalEngine>(slots_, std::move(lanes), std::vector<TimingEngine*>{},
                                           options);
    engine_threads_ = threads;
  }
  engine_->add(rows, count, out, side);
}

}  // namespace glint
