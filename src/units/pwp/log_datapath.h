// pwp's material-independent variant (domain=log): t^n = ex2(n lg2 t) as a GPU special-function
// unit computes it (sfu, pow), with lg2 and ex2 each a piecewise polynomial of pwp's segments and
// degree, the tables shared by every material and only n per slot (n_register.h).
//
// Datapath (F = in's fraction bits, fo = out's, d = degree, K = 2^segments):
//   lg2: a leading-one detector gives t = 2^-E m, m = 1 + mf 2^-F in [1, 2), E = 1..F; the top
//        sl = min(segments, F) bits of mf index a segment, the rl = F - sl bits below are the
//        offset x. Lg_k(x), degree d by Horner's rule at fl fraction bits (acc = c_d; d - 1
//        multiply-adds acc = round(acc x) + c_j; the last forms acc x + c_0 exactly and rounds
//        once to fl bits); log2 t = Lg - E (Lg is in [0, 1]).
//   y:   y = n log2 t, the n register (nf fraction bits) times log2 t, rounded to fy bits; y <= 0.
//   ex2: y = yi + yf, yi = floor(y), yf in [0, 1) at fy bits: its top se = min(segments, fy) bits
//        index a segment, the re = fy - se below are the offset. Ex_k(x) by Horner's rule at fe
//        bits as lg2's, the last stage exact; then the shift by -yi and one rounding (half up) to
//        fo bits, clamped to 1.0. t <= 0 gives 0 and t = 1 gives 1.0, both by a mux.
// The segments (segment_fit.h, fit_segment_of) equal log2(1 + u) and 2^u at both ends and are
// minimax in between; quantized as pwp's (c_0 = T_k, c_j (j >= 2) rounded, c_1 the rest of
// T_{k+1}), so neighbours meet exactly and Lg(0) = 0, Lg(1) = 1, Ex(0) = 1, Ex(1) = 2 exactly:
// across octaves of t and integer steps of y the composition is continuous. A quantized segment
// that is not non-decreasing (pwp_nondecreasing) is replaced by its chord (none has been: both
// functions rise by far more than a coefficient LSB per segment).
//
// Model (model(), the contract's reference for the datapath part): G(n_q (Lg(mf) - E)) with
// G(y) = Ex(frac y) 2^floor(y), the quantized polynomials at the exact offsets and exact products,
// clamped to [0, 1]; float_model: the same with the fits' real coefficients and the real n. The
// approximation part (model against t^n) is then the polynomials' minimax error carried through
// n: n eps_lg2 ln2 + eps_ex2 at most, which the contract measures.
//
// Error budget (datapath_bound_ulps, |eval - model| in output ulps u = 2^-fo, per slot):
//   dL = d 2^-(fl+1): lg2's d - 1 inner roundings (each then multiplied by x^i <= 1) and its last;
//   dy = n_q dL + 2^-(fy+1): y's error, the product rounded once;
//   G is Lipschitz on y <= 0 with S/2, S the largest slope of a quantized Ex segment in yf
//   (K max_k sum_j j |c_j|), 2^floor(y) <= 1/2 below 0 (at y_d >= 0 the clamp gives 1.0 = G(0));
//   ex2's d - 1 inner roundings <= (d - 1) 2^-(fe+1), times 2^yi <= 1; the last rounding ½ u:
//   |eval - model| <= ½ + (d - 1) 2^-(fe+1-fo) + (S/2) dy 2^fo.
// Widths from that target (pwp_log_widths): fe = fo + ge, ge = 2 (3 at d = 3) keeps the second
// term <= 1/8; fy = fo + 3 and fl = fo + 3 + ni + clog2(d), ni the n register's integer bits (the
// tables serve every n the register holds, so the widths cannot depend on the scene's), keep each
// half of the third <= 1/16 (S/2 < 1): at most ¾ u in all. The coefficients are held at the
// accumulators' fraction bits (fl and fe), so their rounding moves the model by at most
// n 2^-fl + 2^-fe, under 1/8 u.
//
// Monotone output, proven once per configuration for every n (check_monotone): Lg's datapath
// value is checked non-decreasing on every mantissa code and <= 1.0 (then log2 t is non-
// decreasing across octaves: the top of one octave, Lg - E - 1 <= -E, is below the next's first,
// 0 - E), and Ex's exact last-stage value on every code of yf, from exactly 1.0 up to at most 2.0
// (then Ex 2^yi is non-decreasing in y across integer steps: at most 2^(yi+1) below, at least
// 2^(yi+1) above). y is n_q > 0 times log2 t rounded, and round half up, the shift and the clamp
// keep order. A check that fails raises fl and fe together by one bit (`extra`) and retries. The
// checks read 2^F + 2^fy codes: F <= 20 and fo <= kPwpLogMaxOutFrac keep them under 2^25.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "units/common.h"
#include "units/stages.h"

namespace glint {

// The widest input and output domain=log takes (its build checks lg2 on every mantissa code and
// ex2 on every code of y's fraction).
inline constexpr int kPwpLogMaxInFrac = 20;
inline constexpr int kPwpLogMaxOutFrac = 21;

// What the shared tables are built from.
struct PwpLogSpec {
  QFormat in, out, n_format;
  int segments = 4, degree = 2;
};

// The internal widths of the header comment, before any `extra` bit the monotone check adds.
struct PwpLogWidths {
  int fl, fy, fe;
};
PwpLogWidths pwp_log_widths(const PwpLogSpec& s);

// Non-decreasing on [0, 1] exactly: c_0 .. c_degree, integer coefficients of one scale.
bool pwp_nondecreasing(const std::int64_t* c, int degree);

// The material-independent part: both tables, their widths, and the proof of monotonicity. One
// per configuration, shared by every datapath group (with tables=ram: ROMs all the same).
struct PwpLogTables {
  explicit PwpLogTables(const PwpLogSpec& spec);  // refuses what cannot be built (keys named)

  PwpLogSpec spec;
  int fi = 0, fo = 0, d = 0, ebits = 0;
  int sl = 0, rl = 0, fl = 0;             // lg2: index bits, offset bits, accumulator fraction bits
  int fy = 0;                             // y's fraction bits
  int se = 0, re = 0, fe = 0;             // ex2: index bits, offset bits, accumulator fraction bits
  int extra = 0;                          // bits the monotone check added to fl and fe
  std::size_t stride = 1;                 // d + 1
  std::vector<std::int64_t> lg, ex;       // per segment c_0 .. c_d at fl, fe fraction bits
  std::vector<double> lg_fit, ex_fit;     // the fits' real coefficients (float_model)
  int lg_chords = 0, ex_chords = 0;       // segments replaced by their chord
  int lg_acc_int = 1, ex_acc_int = 1;     // signed accumulators: integer bits with the sign
  double ex_slope = 0;                    // S of the header comment
  std::int64_t lg_half = 0, ex_half = 0;  // 2^(r-1) (0 when r = 0)
  std::int64_t lg_mask = 0, ex_mask = 0;  // 2^r - 1

  std::size_t lg_segments() const { return std::size_t{1} << sl; }
  std::size_t ex_segments() const { return std::size_t{1} << se; }

 private:
  void fit_tables();
  bool set_widths(int extra_bits);  // false: a register would pass 62 bits
  bool monotone() const;
};

// One datapath group: the shared tables and the group's n.
class PwpLogPath {
 public:
  PwpLogPath(std::shared_ptr<const PwpLogTables> tables, const MaterialParams& m);

  // Positions (log_kind.cpp's layout): 1 lookup (E, index, x, acc = c_d), 2..d lg2's multiply-adds
  // (E, x, acc), d + 1 log2 t, d + 2 y, d + 3 the ex2 lookup (yi, index, x, acc = c_d), d + 4 ..
  // 2d + 2 ex2's multiply-adds (yi, x, acc), 2d + 3 the result. t <= 0 and t >= 1 leave positions
  // 1 .. 2d + 2 alone.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    const PwpLogTables& T = *t_;
    const int d = T.d, last = 2 * d + 3;
    if (t_raw <= 0) {
      probe(last, 0, 0);
      return 0;
    }
    if (t_raw >= one_in_) {
      probe(last, 0, one_out_);
      return one_out_;
    }
    // Lg: the mantissa below the leading one, split into the index and x.
    const int e = 63 - __builtin_clzll(static_cast<unsigned long long>(t_raw));
    const std::int64_t big_e = T.fi - e;
    const std::int64_t mf = (t_raw << big_e) - one_in_;
    const std::int64_t k = mf >> T.rl, x = mf & T.lg_mask;
    const std::int64_t* c = &T.lg[static_cast<std::size_t>(k) * T.stride];
    std::int64_t acc = c[d];
    probe(1, 0, big_e);
    probe(1, 1, k);
    probe(1, 2, x);
    probe(1, 3, acc);
    int pos = 2;
    for (int j = d - 1; j >= 1; --j, ++pos) {
      acc = ((acc * x + T.lg_half) >> T.rl) + c[j];
      probe(pos, 0, big_e);
      probe(pos, 1, x);
      probe(pos, 2, acc);
    }
    const std::int64_t lg = (acc * x + c[0] * (std::int64_t{1} << T.rl) + T.lg_half) >> T.rl;
    const std::int64_t log2t = lg - big_e * (std::int64_t{1} << T.fl);
    probe(pos++, 0, log2t);
    // y = n log2 t, rounded half up.
    const std::int64_t y = (n_raw_ * log2t + y_half_) >> y_shift_;
    probe(pos++, 0, y);
    // Ex: yf's index and offset.
    const std::int64_t yi = y >> T.fy;  // floor
    const std::int64_t yf = y - yi * (std::int64_t{1} << T.fy);
    const std::int64_t ke = yf >> T.re, xe = yf & T.ex_mask;
    const std::int64_t* ce = &T.ex[static_cast<std::size_t>(ke) * T.stride];
    acc = ce[d];
    probe(pos, 0, yi);
    probe(pos, 1, ke);
    probe(pos, 2, xe);
    probe(pos++, 3, acc);
    for (int j = d - 1; j >= 1; --j, ++pos) {
      acc = ((acc * xe + T.ex_half) >> T.re) + ce[j];
      probe(pos, 0, yi);
      probe(pos, 1, xe);
      probe(pos, 2, acc);
    }
    // Ex at fe + re fraction bits, exact, then shifted by -yi and rounded once.
    const std::int64_t v = acc * xe + ce[0] * (std::int64_t{1} << T.re);
    const std::int64_t shift = T.fe + T.re - T.fo - yi;
    std::int64_t r = 0;
    if (shift < 62) r = shift > 0 ? (v + (std::int64_t{1} << (shift - 1))) >> shift : v;
    const std::int64_t result = r < 0 ? 0 : (r > one_out_ ? one_out_ : r);
    probe(last, 0, result);
    return result;
  }
  double model(std::int64_t t_raw) const;
  double float_model(double t) const;
  double datapath_bound_ulps() const { return bound_ulps_; }

  const PwpLogTables& tables() const { return *t_; }
  const std::shared_ptr<const PwpLogTables>& shared_tables() const { return t_; }
  double shininess() const { return n_; }
  double shininess_q() const;
  std::int64_t n_raw() const { return n_raw_; }
  int y_shift() const { return y_shift_; }

 private:
  std::shared_ptr<const PwpLogTables> t_;
  double n_ = 1;
  std::int64_t n_raw_ = 1, one_in_ = 0, one_out_ = 0, y_half_ = 0;
  int y_shift_ = 0;
  double bound_ulps_ = 0;
};

}  // namespace glint
