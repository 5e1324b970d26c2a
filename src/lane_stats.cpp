#include "lane_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

RowReference make_reference(const SlotMap& slots, std::size_t slot, double t) {
  RowReference r;
  r.t = t;
  r.value = reference_value(slots, slot, t);
  r.value8 = std::lround(std::clamp(r.value, 0.0, 1.0) * 255.0);
  return r;
}

LaneAccumulator::LaneAccumulator(const SpecularUnit& unit) : unit_(unit) {
  stats_.name = unit.name();
  stats_.spec = unit.canonical_spec();
  stats_.error_bound = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < unit.slots(); ++k) {
    const double b = unit.error_bound(k);
    if (std::isfinite(b))
      stats_.error_bound = std::isfinite(stats_.error_bound) ? std::max(stats_.error_bound, b) : b;
  }
  ulp_ = unit.out_format().ulp();
  out_scale_ = ulp_;  // raw -> value: exact power-of-two scale
  if (unit.in_format().width() <= 20) memo_.resize(unit.slots());
}

double LaneAccumulator::model(std::size_t slot, std::int64_t t_raw) {
  if (memo_.empty()) return unit_.model(slot, t_raw);
  std::vector<double>& m = memo_[slot];
  if (m.empty()) m.assign(std::size_t{1} << unit_.in_format().width(), -1.0);
  double& v = m[static_cast<std::size_t>(t_raw - unit_.in_format().raw_min())];
  if (v < 0) v = unit_.model(slot, t_raw);
  return v;
}

void LaneAccumulator::add(std::size_t slot, const RowReference& ref, std::int64_t t_raw,
                          bool skipped, std::int64_t out_raw) {
  const double fixed = static_cast<double>(out_raw) * out_scale_;
  ++stats_.vectors;
  stats_.skipped += skipped;
  stats_.total.add(fixed - ref.value, ref.t);
  if (!skipped) {
    const double ulps = std::fabs(fixed - model(slot, t_raw)) / ulp_;
    if (ulps > stats_.max_ulps) {
      stats_.max_ulps = ulps;
      stats_.t_at_max_ulps = ref.t;
    }
  }
  if (std::lround(std::clamp(fixed, 0.0, 1.0) * 255.0) != ref.value8) ++stats_.mismatch8;
  // FNV-1a style over the whole result word (skip flag in bit 63), with a shift-xor so every bit
  // of the word reaches every bit of the digest.
  const std::uint64_t word = static_cast<std::uint64_t>(out_raw) ^ (std::uint64_t{skipped} << 63);
  digest_ = (digest_ ^ word) * 0x100000001b3ULL;
  digest_ ^= digest_ >> 29;
}

}  // namespace glint
