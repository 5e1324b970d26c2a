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

}  // namespace glint
