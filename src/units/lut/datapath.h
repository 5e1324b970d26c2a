// Table + linear interpolation per material: the baseline Schlick (1994) names ("tabulate S_n(t)
// and interpolate", Bishop & Weimer 1986), one table per shininess.
//
// Datapath: the table spans [t0, 1] with t0 = 1 - 2^-s, the largest power-of-two span that still
// covers [tau, 1] when skipping (t0 = 0 otherwise), so the index is a bit field of t - t0 and no
// multiplier is needed to scale t. 2^bits + 1 entries of t^n rounded to `table_frac` bits; the
// output is T[i] + (T[i+1] - T[i]) r / 2^rbits, formed exactly and rounded once.
//
// Error bound against t^n: the largest chord error over the segments (exact: at the tangent point
// t* = (slope / n)^(1/(n-1)) of each segment) + ½ ulp of the table + ½ ulp_out final rounding
// (error_bound()). The three parts: approximation = the chord error (float_model interpolates
// exact t^n nodes), parameter quantization = the table rounding (model() interpolates the rounded
// entries, a convex combination, so at most ½ ulp of the table), datapath = the final rounding
// alone (the interpolation is formed exactly and rounded once: ½ ulp).
//
// Storage: when the span holds fewer input codes than the table has segments (bits > Fi - s, pad
// > 0), the inputs read only every 2^pad-th entry, with a zero remainder. Only those entries are
// kept (the ROM's other entries show only in the staged evaluation, as the node_hi register, and
// are computed there on demand): lut:bits=16 would otherwise keep 2^16 + 1 entries per material
// of which at most 2^15 + 1 are ever read. Entries are at most 2^table_frac <= 2^30 (the width
// check), so 32 bits hold them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "units/common.h"
#include "units/lut/keys.h"
#include "units/stages.h"

namespace glint {

struct LutConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  int bits = LutKeys::bits.def;              // table address bits: 2^bits + 1 entries
  int table_frac = LutKeys::table_frac.def;  // entry fraction bits; kAutoInt: out.frac_bits + 2
  bool skip = CommonKeyTable::skip.def;
  bool table_frac_auto = false;  // resolved from table_frac=auto (refusals say so)
};

class LutUnit {
 public:
  LutUnit(const LutConfig& cfg, const MaterialParams& m);

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (lut.cpp's layout): position 1 holds the index, the remainder
  // and the two table values, position 2 the result. t <= t0 leaves position 1 alone.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    if (t_raw <= t0_raw_) {
      probe(2, 0, 0);
      return 0;
    }
    const std::int64_t t = t_raw > one_in_ ? one_in_ : t_raw;
    // The hardware index is ((t - t0) << pad) >> r_bits; pad > 0 implies r_bits = 0, so the kept
    // entry (every 2^pad-th) is at (t - t0) >> r_bits either way.
    const std::int64_t v = t - t0_raw_;
    const std::int64_t k = v >> r_bits_;
    const std::int64_t r = v & r_mask_;
    const std::int64_t a = table_[k], b = table_[k + 1];  // b: the next kept entry
    if constexpr (Probe::kActive) {
      const std::int64_t i = k << pad_;
      probe(1, 0, i);
      probe(1, 1, r);
      probe(1, 2, a);
      probe(1, 3, pad_ == 0 ? b : entry(i + 1));  // the ROM's own next entry
    }
    const std::int64_t y = (a << r_bits_) + (b - a) * r;  // exact, r_bits + tfrac
    const std::int64_t q = round_nearest(y, out_shift_);
    const std::int64_t result = q > one_out_ ? one_out_ : q;
    probe(2, 0, result);
    return result;
  }
  int remainder_bits() const { return r_bits_; }
  // Entry j of the ROM (0..2^bits, and the padding entry 2^bits + 1 that repeats the last), as
  // kept or, between the kept ones, computed the same way.
  std::int64_t entry(std::int64_t j) const;
  std::size_t entries() const { return (std::size_t{1} << cfg_.bits) + 1; }
  std::size_t kept_entries() const { return table_.size() - 1; }
  // Every entry (the padding copy included) at least the one before it.
  bool entries_non_decreasing() const { return std::is_sorted(table_.begin(), table_.end()); }
  // Memory of the kept entries (with the padding entry): what the limit of units/unit_set.h counts.
  std::size_t table_bytes() const { return table_.size() * sizeof(table_[0]); }
  double model(std::int64_t t_raw) const;  // the rounded entries interpolated exactly, at t_q
  double float_model(double t) const;      // exact-node interpolation at the exact t
  static double datapath_bound_ulps() { return 0.5; }
  double error_bound() const { return bound_; }
  double chord_error() const { return chord_; }

  std::int64_t t0_raw() const { return t0_raw_; }
  int span_log2() const { return s_; }
  const LutConfig& config() const { return cfg_; }

 private:
  double interp_exact(double t) const;
  std::int64_t compute_entry(std::int64_t j) const;  // node j's t^n rounded, j in 0..2^bits

  LutConfig cfg_;
  double n_ = 1;
  int s_ = 0, pad_ = 0, r_bits_ = 0, out_shift_ = 0;
  std::int64_t t0_raw_ = 0, one_in_ = 0, one_out_ = 0, tau_raw_ = -1, r_mask_ = 0;
  std::vector<std::uint32_t> table_;  // entries 0, 2^pad, 2 2^pad, ..., 2^bits, the padding
  double chord_ = 0, bound_ = 0;
};

}  // namespace glint
