// Accuracy statistics of one simulated lane, fed one retired result at a time (by the fast mode's
// batch loop or by the clocked mode's scoreboard). Plain C++: the same accumulation for both modes.
#pragma once

#include <cstdint>
#include <vector>

#include "evaluate.h"
#include "units.h"

namespace glint {

// The float reference of one request, computed once and shared by every lane.
struct RowReference {
  double t = 0;
  double value = 0;  // reference_value(): max(0,t)^n or the Gaussian lobe
  long value8 = 0;   // round(255 * value): the 8-bit display code
};
RowReference make_reference(const SlotMap& slots, std::size_t slot, double t);

class LaneAccumulator {
 public:
  explicit LaneAccumulator(const SpecularUnit& unit);

  void add(std::size_t slot, const RowReference& ref, std::int64_t t_raw, bool skipped,
           std::int64_t out_raw);
  // A digest of every (skipped, out_raw) in stream order: bit-accurate regression in 64 bits.
  std::uint64_t digest() const { return digest_; }
  const UnitStats& stats() const { return stats_; }
  UnitStats& stats() { return stats_; }

 private:
  double model(std::size_t slot, std::int64_t t_raw);

  const SpecularUnit& unit_;
  UnitStats stats_;
  std::uint64_t digest_ = 0xcbf29ce484222325ULL;
  double ulp_ = 0, out_scale_ = 0;
  // The unit's real-valued model per (slot, input raw), memoised when the input is <= 20 bits:
  // a long stream revisits the same 2^16 inputs, and the model is the costly part of the check.
  std::vector<std::vector<double>> memo_;
};

}  // namespace glint
