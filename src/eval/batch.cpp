#include "eval/engine.h"
#include "eval/evaluate.h"

namespace glint {

void Evaluator::add_batch(const VectorRow* rows, std::size_t count, BatchResults& out,
                          int threads) {
  run_engine(rows, count, &out, threads);
}

void Evaluator::add_rows(const VectorRow* rows, std::size_t count, int threads) {
  run_engine(rows, count, nullptr, threads);
}

void Evaluator::run_engine(const VectorRow* rows, std::size_t count, BatchResults* out,
                           int threads) {
  if (!engine_ || engine_threads_ != threads) {
    std::vector<LaneAccumulator*> lanes;
    for (auto& lane : lanes_) lanes.push_back(&lane);
    EngineOptions options;
    options.threads = threads;
    engine_ = std::make_unique<EvalEngine>(slots_, std::move(lanes), std::vector<TimingEngine*>{},
                                           options);
    engine_threads_ = threads;
  }
  engine_->add(rows, count, out);
}

}  // namespace glint
