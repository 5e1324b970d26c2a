// Piecewise polynomial per material: K = 2^s segments over the table's span, each a polynomial of
// degree 1..3 in the offset below the segment index, evaluated by Horner's rule. The design of
// FloPoCo's FixFunctionByPiecewisePoly and of a GPU's special-function unit, here per material
// in the t domain.
//
// Span and index (as lut): [t0, 1] with t0 = 1 - 2^-s0 the highest such point at or below tau_q
// when skipping (t0 = 0 otherwise), so v = t - t0 < 2^(Fi - s0) needs no multiplier: its top
// sb = min(segments, Fi - s0) bits are the segment index k, the rb = Fi - s0 - sb bits below it
// the offset x = r 2^-rb in [0, 1). t <= t0 gives 0 and t = 1 (v's bit above the index) gives
// exactly 1.0, both by a mux.
//
// Segments (segment_fit.h): segment k covers [a_k, a_k + h], h = (1 - t0) 2^-sb, and its
// polynomial P_k(x) equals t^n at both ends and is minimax in between. Quantized to cf =
// coef_frac fraction bits so that neighbours still meet exactly: c_0 = T_k, c_j (j >= 2) rounded
// to nearest, c_1 = T_{k+1} - c_0 - sum_{j>=2} c_j, with T_k = a_k^n rounded (T_K = 1.0). Each
// quantized P_k is then proven non-decreasing on [0, 1] exactly (P' is at most quadratic: its
// minimum over [0, 1] in integer arithmetic); a segment that fails is blended towards the chord
// from T_k to T_{k+1}, (1 - w) P_k + w chord with the least w in 1/16, ..., 1 that passes (w = 1:
// the chord itself, monotone because T is; the blend's error is at most the blend of the two).
// Such segments sit where t^n is nearly flat (skip=off, far below the lobe): the minimax error's
// equioscillation then outweighs the rise. The piecewise function is thereby continuous and
// non-decreasing from t0 to 1.
//
// Datapath (fa = out + guard fraction bits in the accumulator, fa >= cf): acc = c_d; d - 1
// multiply-adds acc = round(acc x) + c_j (j = d-1 .. 1), the product rounded to fa bits (half
// up: its constant sits in the multiplier's partial-product array, no adder); the last stage
// forms acc x + c_0 exactly and rounds once to the output, then clamps to [0, 1]. No truncated
// multiplier or squarer: Horner has no squarer, x is rb <= Fi bits wide, and a truncated product
// would add a budget term that more guard bits pay back; the exact first and last products keep
// degree 1 correctly rounded, as lut is.
//
// Error budget (datapath_bound_ulps, against model(): clamp(P_k,q(x), 0, 1) of the quantized
// coefficients at the exact x, t <= t0 -> 0, t = 1 -> 1): x is exact (a bit field), each of the
// d - 1 inner roundings is <= 2^-(fa+1) and is multiplied by x^i <= 1 afterwards, the final
// rounding <= ½ ulp, and the clamp is 1-Lipschitz: |eval - model| <= ½ + (d - 1) 2^-(guard+1)
// ulps. The automatic guard (pwp_min_guard) keeps the second term <= ¼, faithful; degree 1 is
// correctly rounded.
//
// Monotone output: model is non-decreasing in t (above), and round to nearest and the clamp keep
// order, but the inner roundings (|e| <= (d - 1) 2^-(fa+1)) can step back where P_k rises by less
// than 2|e| between neighbouring codes. output_monotone() checks every code of the span (Fi <= 20:
// at most 2^20 + 1 evaluations); the build raises an automatic guard until every group passes and
// refuses a given one that does not (with guard >= cf - out + (d - 1) rb the products are exact
// and the output correctly rounded, hence monotone).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "units/common.h"
#include "units/pwp/keys.h"
#include "units/pwp/log_datapath.h"
#include "units/stages.h"

namespace glint {

struct PwpConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  int segments = PwpKeys::segments.def;    // log2 K (at most: the span may hold fewer codes)
  int degree = PwpKeys::degree.def;        // 1..3
  int coef_frac = PwpKeys::coef_frac.def;  // kAutoInt: out + 2
  int guard = PwpKeys::guard.def;          // kAutoInt: pwp_min_guard
  bool skip = CommonKeyTable::skip.def;
  bool coef_frac_auto = false;  // resolved from auto (refusals say so)
  bool guard_auto = false;
  bool log_domain = false;            // domain=log: units/pwp/log_datapath.h
  QFormat n_format = PwpKeys::n.def;  // domain=log's n register
};

// domain=log's tables for this config.
PwpLogSpec pwp_log_spec(const PwpConfig& c);

// The widest input pwp takes: its build checks every code of the span for monotonicity.
inline constexpr int kPwpMaxInFrac = 20;
// The widest coefficients (coef_frac, also when resolved from out): the integer arithmetic of the
// quantization stays far from 64 bits.
inline constexpr int kPwpMaxCoefFrac = 48;

// coef_frac and guard resolved from auto: cf = out + 2; guard faithful ((d - 1) 2^-(g+1) <= ¼)
// and at least cf - out (the coefficients are added into the accumulator exactly).
int pwp_coef_frac(const PwpConfig& c);
int pwp_min_guard(const PwpConfig& c);

// P(x) = c_0 + ... + c_d x^d (integer coefficients, one scale) non-decreasing on [0, 1], exactly.
bool pwp_nondecreasing(const std::int64_t* c, int degree);

// Which engine fitted a group's segments (fit_engine.h): how many hold Sollya's fit, and the
// largest certified sup norm of |P_k,q - t^n| over those (none: 0).
struct PwpFitRecord {
  int fitted = 0;  // segments with a free coefficient (degree >= 2, more than one code)
  int sollya = 0;
  double sup_lo = 0.0, sup_hi = 0.0;
};

class PwpUnit {
 public:
  // domain=log: `log_tables` built for pwp_log_spec(cfg), shared by the groups (null: its own).
  PwpUnit(const PwpConfig& cfg, const MaterialParams& m,
          std::shared_ptr<const PwpLogTables> log_tables = nullptr);

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (pwp.cpp's layout): position 1 holds the index, x and acc = c_d,
  // positions 2..d x and acc after each multiply-add, position d + 1 the result. t <= t0 and
  // t = 1 leave positions 1..d alone.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    if (log_) return log_->run(t_raw, probe);
    const int last = cfg_.degree + 1;
    if (t_raw <= t0_raw_) {
      probe(last, 0, 0);
      return 0;
    }
    if (t_raw >= one_in_) {
      probe(last, 0, one_out_);
      return one_out_;
    }
    const std::int64_t v = t_raw - t0_raw_;
    const std::int64_t k = v >> rb_;
    const std::int64_t x = v & x_mask_;
    const std::int64_t* c = &c_raw_[static_cast<std::size_t>(k) * stride_];
    std::int64_t acc = c[cfg_.degree] * (std::int64_t{1} << align_);
    probe(1, 0, k);
    probe(1, 1, x);
    probe(1, 2, acc);
    int position = 2;
    for (int j = cfg_.degree - 1; j >= 1; --j, ++position) {
      acc = ((acc * x + half_x_) >> rb_) + c[j] * (std::int64_t{1} << align_);
      probe(position, 0, x);
      probe(position, 1, acc);
    }
    // Coefficients may be negative: scaled by a product, as a left shift of a negative value is
    // undefined before C++20.
    const std::int64_t q =
        (acc * x + c[0] * (std::int64_t{1} << c0_shift_) + half_out_) >> out_shift_;
    const std::int64_t result = q < 0 ? 0 : (q > one_out_ ? one_out_ : q);
    probe(position, 0, result);
    return result;
  }
  double model(std::int64_t t_raw) const;  // the quantized segments at the exact x
  double float_model(double t) const;      // the fitted segments at the exact t
  double datapath_bound_ulps() const;

  // The accumulator's guard bits (the build raises an automatic guard until every group's output
  // is monotone); refuses registers wider than the 62-bit product allows.
  void set_guard(int guard);
  // eval() non-decreasing over every input code (header comment).
  bool output_monotone() const;

  std::int64_t t0_raw() const { return t0_raw_; }
  int span_log2() const { return s0_; }
  int segment_bits() const { return sb_; }  // log2 of the segments in use
  int offset_bits() const { return rb_; }   // x's width
  std::size_t segment_count() const { return std::size_t{1} << sb_; }
  // Coefficient j of segment k at coef_frac fraction bits.
  std::int64_t coeff(std::size_t k, int j) const {
    return c_raw_[k * stride_ + static_cast<std::size_t>(j)];
  }
  int acc_int_bits() const { return acc_int_; }  // signed accumulator: integer bits with the sign
  int blended_segments() const { return blended_; }  // repaired towards the chord (header)
  int chord_segments() const { return chords_; }
  double shininess() const { return n_; }
  // Segment k's ends in t, and its fit (c_0 first) before quantization.
  double segment_start(std::size_t k) const;
  double segment_end(std::size_t k) const;
  std::vector<double> segment_fit(std::size_t k) const;
  // Segment k takes raw (c_0 .. c_d at coef_frac bits, the same ends, non-decreasing: the caller's
  // proofs, fit_engine.h); its fit is then raw itself. set_guard() afterwards resizes the
  // accumulator.
  void replace_segment(std::size_t k, const std::vector<std::int64_t>& raw);
  const PwpFitRecord& fit_record() const { return fit_record_; }
  void set_fit_record(const PwpFitRecord& r) { fit_record_ = r; }
  std::size_t table_bytes() const { return (c_raw_.size() + c_fit_.size()) * 8; }
  const PwpConfig& config() const { return cfg_; }
  const PwpLogPath* log_path() const { return log_ ? &*log_ : nullptr; }

 private:
  PwpConfig cfg_;
  double n_ = 1;
  int s0_ = 0, sb_ = 0, rb_ = 0, fa_ = 0, align_ = 0, c0_shift_ = 0, out_shift_ = 0, acc_int_ = 1;
  std::size_t stride_ = 1;
  std::int64_t t0_raw_ = 0, one_in_ = 0, one_out_ = 0, x_mask_ = 0, half_x_ = 0, half_out_ = 0;
  long double x_scale_ = 1, c_scale_ = 1;  // 2^-rb, 2^-cf (model)
  std::vector<std::int64_t> c_raw_;        // per segment: c_0 .. c_d at coef_frac fraction bits
  std::vector<double> c_fit_;              // the fit's coefficients, same layout (float_model)
  int blended_ = 0, chords_ = 0;
  std::vector<int> repair_;  // per segment: 0 the fit, 1 blended, 2 the chord
  PwpFitRecord fit_record_;
  bool guard_given_ = false;
  std::optional<PwpLogPath> log_;  // domain=log: the whole datapath
};

}  // namespace glint
