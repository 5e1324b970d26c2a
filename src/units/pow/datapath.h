// Exact-power baseline the way a GPU special-function unit computes it: t^n = exp2(n log2 t).
//
// Datapath: leading-one detector normalises t = 2^e m, m in [1, 2); log2 m from a table of
// 2^log_bits + 1 entries with linear interpolation on the remaining mantissa bits; y = n log2 t
// (one multiplier, rounded to yfrac bits); y = yi + yf with yi = floor(y); 2^yf from a table of
// 2^exp_bits + 1 entries with linear interpolation; a right shift by -yi and the final rounding.
//
// Error bound against t^n (n as quantized in the n register), stated per slot by error_bound():
//   eps_L = max linear-interpolation error of log2 on the table segments (exact, computed from
//           the tangent point of each segment) + ½ ulp table rounding + ½ ulp interpolation
//           rounding
//   dy    = n eps_L + ½ ulp of y
//   eps_E = same for 2^x on [0, 1] (absolute; 2^x >= 1 makes it relative too)
//   |out - t^n| <= (2^dy (1 + eps_E) - 1) + ½ ulp_out
// pow's real-valued model is t^n itself, so this whole bound is its datapath budget (the tables
// and their interpolation are how the datapath computes t^n, not a different function).
// The bound grows linearly in n: with the defaults it stays under ½ LSB of an 8-bit display for
// n <= 512 and under 1 LSB for n <= 1024 (tests/units/test_units_exhaustive.cpp holds it to that).
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "units/common.h"
#include "units/pow/keys.h"
#include "units/stages.h"

namespace glint {

struct PowConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  QFormat n_format = PowKeys::n.def;
  int log_bits = PowKeys::log_bits.def;  // log2 table address bits
  int log_frac = PowKeys::log_frac.def;  // log2 table entry fraction bits
  int y_frac = PowKeys::y_frac.def;      // fraction bits of y = n log2 t
  int exp_bits = PowKeys::exp_bits.def;  // exp2 table address bits
  int exp_frac = PowKeys::exp_frac.def;  // exp2 table entry fraction bits
  bool skip = CommonKeyTable::skip.def;
};

// What pow's datapath reads that does not depend on the material: the log2 and exp2 tables and
// their error terms (eps_L, eps_E of the header comment). One per configuration, shared by every
// slot of a unit: 65536 slots would otherwise build (and keep) 65536 identical copies.
struct PowTables {
  explicit PowTables(const PowConfig& cfg);  // cfg already checked (PowUnit's constructor)
  // The tables are those of cfg (same table keys).
  bool fits(const PowConfig& cfg) const {
    return cfg.log_bits == log_bits && cfg.log_frac == log_frac && cfg.exp_bits == exp_bits &&
           cfg.exp_frac == exp_frac;
  }

  int log_bits, log_frac, exp_bits, exp_frac;
  std::vector<std::int64_t> log_table, exp_table;
  double eps_log = 0, eps_exp = 0;
};

class PowUnit {
 public:
  // `tables`: a PowTables built for a config with the same table keys (log_bits, log_frac,
  // exp_bits, exp_frac), to share; null builds the unit's own.
  PowUnit(const PowConfig& cfg, const MaterialParams& m,
          std::shared_ptr<const PowTables> tables = nullptr);

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (pow.cpp's layout): 1 normalisation shift, log2 nodes and the
  // interpolation remainder; 2 log2 t and n; 3 y = n log2 t; 4 floor(y), exp2 nodes and remainder;
  // 5 the interpolated exp2 value and the result. t = 0 leaves the intermediate registers alone.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    if (t_raw <= 0) {
      probe(5, 1, 0);
      return 0;
    }
    const std::int64_t t = t_raw > one_in_ ? one_in_ : t_raw;
    const int e = 63 - __builtin_clzll(static_cast<unsigned long long>(t));  // leading one
    const std::int64_t mf = (t << (fi_ - e)) - one_in_;  // mantissa fraction, fi bits
    const std::int64_t li = mf >> log_r_bits_ << log_pad_;
    const std::int64_t lr = mf & log_r_mask_;
    const std::int64_t l0 = log_table_[li], l1 = log_table_[li + 1];
    probe(1, 0, fi_ - e);
    probe(1, 1, l0);
    probe(1, 2, l1);
    probe(1, 3, lr);
    const std::int64_t lg = l0 + round_nearest((l1 - l0) * lr, log_r_bits_);
    const std::int64_t log2t = lg - (static_cast<std::int64_t>(fi_ - e) << cfg_.log_frac);
    probe(2, 0, log2t);
    probe(2, 1, n_raw_);
    const std::int64_t y = round_nearest(n_raw_ * log2t, y_shift_);  // <= 0
    probe(3, 0, y);
    const std::int64_t yi = y >> cfg_.y_frac;  // floor
    const std::int64_t yf = y - shift_left(yi, cfg_.y_frac);
    const std::int64_t ei = yf >> exp_r_bits_ << exp_pad_;
    const std::int64_t er = yf & exp_r_mask_;
    const std::int64_t e0 = exp_table_[ei], e1 = exp_table_[ei + 1];
    probe(4, 0, yi);
    probe(4, 1, e0);
    probe(4, 2, e1);
    probe(4, 3, er);
    const std::int64_t ex = e0 + round_nearest((e1 - e0) * er, exp_r_bits_);
    probe(5, 0, ex);
    const std::int64_t shift = out_shift_ - yi;
    if (shift >= 62) {
      probe(5, 1, 0);
      return 0;
    }
    const std::int64_t r = round_nearest(ex, static_cast<int>(shift));
    const std::int64_t result = r > one_out_ ? one_out_ : r;
    probe(5, 1, result);
    return result;
  }
  // pow's own model is t^n itself (at the quantized t and n): every deviation is datapath error.
  double model(std::int64_t t_raw) const;
  double float_model(double t) const;
  // Bound on |eval - t_q^n_q| over every input (see the header comment).
  double error_bound() const { return bound_; }
  double datapath_bound_ulps() const { return std::ldexp(bound_, cfg_.out.frac_bits); }
  double log_error() const { return tables_->eps_log; }
  double exp_error() const { return tables_->eps_exp; }
  const std::shared_ptr<const PowTables>& tables() const { return tables_; }

  double shininess_q() const;
  double shininess() const { return n_; }  // the n the register stands for
  std::int64_t n_raw() const { return n_raw_; }
  const PowConfig& config() const { return cfg_; }
  std::size_t table_bits() const;

 private:
  PowConfig cfg_;
  double n_ = 1;
  std::int64_t n_raw_ = 0, one_in_ = 0, one_out_ = 0;
  int fi_ = 0, log_r_bits_ = 0, log_pad_ = 0, exp_r_bits_ = 0, exp_pad_ = 0, y_shift_ = 0;
  int out_shift_ = 0;
  std::int64_t log_r_mask_ = 0, exp_r_mask_ = 0;
  std::shared_ptr<const PowTables> tables_;
  // tables_'s entries, cached so that eval reads a table through one pointer as it did from a
  // vector of its own (no extra indirection through the shared object).
  const std::int64_t* log_table_ = nullptr;
  const std::int64_t* exp_table_ = nullptr;
  double bound_ = 0;
};

// One PowUnit per datapath group, all sharing one PowTables (built with the first). A refusal names
// the group's material, as every kind's build does.
std::vector<PowUnit> build_pow_units(const PowConfig& cfg,
                                     const std::vector<MaterialParams>& slots);

}  // namespace glint
