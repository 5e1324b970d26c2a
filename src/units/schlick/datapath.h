// Schlick's rational approximation S(t) = t / (n - n t + t) with a real divider.
//
// Datapath: D = n (1 - t) + t is formed exactly (one multiplier, one adder, no rounding), then one
// integer division Q = T 2^(Fn + Fo) / D, rounded to nearest. Hardware: a restoring or
// non-restoring divider producing Fo + 2 quotient bits (the last one decides the rounding).
//
// Error budget (against the real-valued S at the quantized t and n): the numerator and denominator
// are exact and the quotient is correctly rounded, so the whole budget is the final ½ ulp. The
// float model error S(t) - t^n is Schlick's own and is reported separately.
//
// The n register holds n': the material's n as Schlick uses it (match=none), or the n' that best
// matches t^n (match=minimax or width, units/match.h); the slot keeps both.
#pragma once

#include <cstdint>

#include "units/common.h"
#include "units/match.h"
#include "units/schlick/keys.h"
#include "units/stages.h"

namespace glint {

struct SchlickConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  QFormat n_format = SchlickKeys::n.def;  // shininess register
  bool skip = CommonKeyTable::skip.def;
  MatchMode match = MatchMode::kNone;  // how n' is chosen from the material's n
};
static_assert(SchlickKeys::match.def == "none", "SchlickConfig::match is the key's default");

// The n' a slot's register gets for the material's n (n itself for match=none).
double schlick_n_prime(MatchMode match, double n);

class SchlickUnit {
 public:
  // n_prime: the value for the n register (schlick_n_prime of the material's shininess).
  SchlickUnit(const SchlickConfig& cfg, const MaterialParams& m, double n_prime);
  SchlickUnit(const SchlickConfig& cfg, const MaterialParams& m)
      : SchlickUnit(cfg, m, m.shininess) {}

  // Bit-accurate result for an input already in cfg.in (any raw; > 1.0 is clamped to 1.0).
  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (schlick.cpp's layout): position 1 holds D, positions
  // 2..q+1 the restoring divider after each quotient bit (partial remainder, quotient so far),
  // position q + 2 the rounded result.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    const std::int64_t t = t_raw > one_in_ ? one_in_ : (t_raw < 0 ? 0 : t_raw);
    if (!Probe::kActive && t == 0) return 0;  // what the divider gives for t = 0, undivided
    // D and the numerator are exact integers well below 2^53 (checked in the constructor), so a
    // double quotient is within one of the true floor; the remainder fixes it exactly.
    const std::int64_t den = n_raw_ * (one_in_ - t) + (t << n_frac_);
    const std::int64_t num = t << num_shift_;
    std::int64_t q = static_cast<std::int64_t>(static_cast<double>(num) / static_cast<double>(den));
    std::int64_t r = num - q * den;
    if (r < 0) {
      --q;
      r += den;
    } else if (r >= den) {
      ++q;
      r -= den;
    }
    const std::int64_t round_bit = (2 * r >= den) ? 1 : 0;  // round to nearest, ties up
    if constexpr (Probe::kActive) record_divider(probe, den, num, 2 * q + round_bit);
    q += round_bit;
    const std::int64_t result = q > out_max_ ? out_max_ : q;
    probe(quotient_bits() + 2, 0, result);
    return result;
  }
  // Fo + 2 quotient bits: the integer bit, Fo fraction bits and the rounding bit.
  int quotient_bits() const { return cfg_.out.frac_bits + 2; }
  // Real-valued model at the quantized input and shininess.
  double model(std::int64_t t_raw) const;
  // Float approximation S_n'(t) at the exact t and n' (for the model error).
  double float_model(double t) const;

  // Budget: numerator and denominator exact, quotient correctly rounded.
  static double datapath_bound_ulps() { return 0.5; }
  double shininess_q() const;                        // n' as the register holds it
  double n_prime() const { return n_; }              // n' exact
  double material_n() const { return material_n_; }  // the n it matches
  std::int64_t n_raw() const { return n_raw_; }
  const SchlickConfig& config() const { return cfg_; }

 private:
  SchlickConfig cfg_;
  double n_ = 1.0;           // n' (exact)
  double material_n_ = 1.0;  // the material's n
  // The restoring divider's state after quotient bit k of Q = floor(2 num / D) (q bits): the
  // quotient bits so far, Q >> (q - k) (k bits, as the hardware's quotient register holds them),
  // and the partial remainder floor(2 num / 2^(q - k)) - D (Q >> (q - k)).
  template <class Probe>
  void record_divider(const Probe& probe, std::int64_t den, std::int64_t num,
                      std::int64_t quotient) const {
    probe(1, 0, den);
    const int q = quotient_bits();
    for (int k = 1; k <= q; ++k) {
      const std::int64_t so_far = quotient >> (q - k);
      probe(1 + k, 0, ((2 * num) >> (q - k)) - den * so_far);
      probe(1 + k, 1, so_far);
    }
  }

  std::int64_t n_raw_ = 0, one_in_ = 0, out_max_ = 0;
  int n_frac_ = 0, num_shift_ = 0;
};

}  // namespace glint
