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
#pragma once

#include <cstdint>
#include <vector>

#include "units/common.h"
#include "units/stages.h"

namespace glint {

struct LutConfig {
  QFormat in = kDefaultIn;
  QFormat out = kDefaultOut;
  int bits = 6;         // table address bits: 2^bits + 1 entries
  int table_frac = -1;  // entry fraction bits; -1: out.frac_bits + 2
  bool skip = true;
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
    const std::int64_t v = (t - t0_raw_) << pad_;
    const std::int64_t i = v >> r_bits_;
    const std::int64_t r = v & r_mask_;
    const std::int64_t a = table_[i], b = table_[i + 1];
    probe(1, 0, i);
    probe(1, 1, r);
    probe(1, 2, a);
    probe(1, 3, b);
    const std::int64_t y = (a << r_bits_) + (b - a) * r;  // exact, r_bits + tfrac
    const std::int64_t q = round_nearest(y, out_shift_);
    const std::int64_t result = q > one_out_ ? one_out_ : q;
    probe(2, 0, result);
    return result;
  }
  int remainder_bits() const { return r_bits_; }
  double model(std::int64_t t_raw) const;  // the rounded entries interpolated exactly, at t_q
  double float_model(double t) const;      // exact-node interpolation at the exact t
  static double datapath_bound_ulps() { return 0.5; }
  double error_bound() const { return bound_; }
  double chord_error() const { return chord_; }

  std::int64_t t0_raw() const { return t0_raw_; }
  int span_log2() const { return s_; }
  const std::vector<std::int64_t>& table() const { return table_; }
  const LutConfig& config() const { return cfg_; }

 private:
  double interp_exact(double t) const;

  LutConfig cfg_;
  double n_ = 1;
  int s_ = 0, pad_ = 0, r_bits_ = 0, out_shift_ = 0;
  std::int64_t t0_raw_ = 0, one_in_ = 0, one_out_ = 0, tau_raw_ = -1, r_mask_ = 0;
  std::vector<std::int64_t> table_;
  double chord_ = 0, bound_ = 0;
};

}  // namespace glint
