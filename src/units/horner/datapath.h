// Horner pipeline for a fitted polynomial (Öztürk et al. 2006, eq.12), one multiply-add per stage.
//
// The polynomial is evaluated in the unit's variable: u = t on the full domain (Öztürk's fit), or
// u = (t - tau_q) / (1 - tau_q) on [tau_q, 1] (our fits, u_scaler.h), with monomial coefficients
// in u. tau_q is the u scaler's root code, and the fit runs on exactly that domain (slots.h): the
// fitted polynomial and the hardware share one variable (a fit on the float tau, or on a clamped
// one, would be evaluated off its domain and can rise, fall to 0 and rise again).
// Stages: acc = c_p; acc = round(acc u) + c_k for k = p-1 .. 1; the last stage forms acc u + c_0
// exactly and rounds once to the output format; then clamp to [0, 1].
//
// Error budget (against the real-valued clamp(sum c_kq u^k, 0, 1) at the quantized t, tau, k and
// coefficients): final rounding ½ ulp_out; the p - 1 inner roundings add 2^-(fh+1) each (scaled by
// u^k <= 1); rounding u costs |P'| 2^-(fh+1) <= S 2^-(fh+1), with S the largest |Bernstein
// coefficient| of P' (fit/monotone.h's slope_bound: a bound of |P'| on [0, 1] that, unlike
// sum k |c_k|, does not grow with the cancelling monomial coefficients of degrees 8-10). Faithful
// needs (p - 1 + S) 2^-(fh+1) < 2^-(fo+1): horner_required_guard() picks g = fh - fo with
// 2^g >= 2 (p - 1 + S), a factor-2 margin for the coefficients' own quantization. On the full
// domain u = t is exact and the derivative term is not needed for faithfulness, but
// horner_preferred_guard() keeps it where the registers allow (horner_max_guard()).
//
// Registers: coefficients and the accumulator are signed with fh fraction bits and as many integer
// bits as the largest |c| (high-degree fits in u have monomial coefficients in the thousands); each
// register stays <= 62 bits, and the product acc * u (acc bits + fh + 1) is formed in 128 bits only
// when it would not fit 63 (the `wide` datapath; the default specs never need it).
//
// Monotone output (horner_monotone.cpp): y = P_q(u_hw) + e with |e| <= (p - 1) 2^-(fh+1) and u_hw
// non-decreasing in t, so the output cannot step back where P_q' dmin > 2 |e|max (dmin: the least
// step of u_hw between neighbouring codes); elsewhere every code is checked.
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "units/common.h"
#include "units/horner/keys.h"
#include "units/stages.h"
#include "units/u_scaler.h"

namespace glint {

struct HornerCoefficients {
  std::vector<double> c;        // monomial coefficients in u, c[0] constant
  bool tau_domain = true;       // u = (t - tau)/(1 - tau); false: u = t
  bool constrain_one = false;   // fit has P(1) = 1: keep it exact after quantization
  bool constrain_zero = false;  // fit has P(0) = 0 (at u = 0, i.e. t = tau)
  // method=robust: the fit's largest error on its samples and least squares' on the same ones,
  // and whether the bisquare weights rejected the highlight (fit.h, robust_rejects_samples).
  double sample_max_error = 0.0;
  double ls_sample_max_error = 0.0;
  bool robust_rejects = false;
  // Where the coefficients come from (fit_engine.h): "glint", the method's fit (fit.h) that the
  // datapath rounds to nearest, or "sollya", fpminimax's fit already on the datapath's grid.
  const char* engine = "glint";
  // Sollya's certified enclosure [sup_lo, sup_hi] of max |P_q(u) - t^n| over u in [0, 1], P_q the
  // coefficients as the datapath holds them (before the clamp, which only lowers it); set where
  // the slot holds Sollya's fit (sup_certified false otherwise).
  bool sup_certified = false;
  double sup_lo = 0.0;
  double sup_hi = 0.0;
};

struct HornerConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  int guard = HornerKeys::guard.def;  // fh - fo; kAutoInt: horner_required_guard over every slot
  bool skip = CommonKeyTable::skip.def;
  bool guard_auto = false;  // guard resolved from key guard=auto (refusals say so)
};

int horner_required_guard(const HornerCoefficients& coeffs);   // faithful minimum
int horner_preferred_guard(const HornerCoefficients& coeffs);  // + derivative term
// The largest guard whose registers fit 62 bits for this slot: the accumulator (coefficient
// magnitude) and the u scaler (in + k + u bits, k = 1/(1 - tau_q) of the material).
int horner_max_guard(const HornerCoefficients& coeffs, const MaterialParams& m, const QFormat& in,
                     const QFormat& out);

class HornerUnit {
 public:
  HornerUnit(const HornerConfig& cfg, const MaterialParams& m, const HornerCoefficients& coeffs);

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (horner.cpp's layout): position 1 holds u and c_p, position k
  // (2..p) u and the accumulator after its multiply-add, position p + 1 the result.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    // The wide datapath out of line: the default specs never take it, and the hot loop keeps the
    // narrow one inlined (bench_datapath).
    if (__builtin_expect(wide_, 0)) return run_wide(t_raw, probe);
    return run_as<false>(t_raw, probe);
  }
  double model(std::int64_t t_raw) const;  // real-valued at quantized t, tau, k, coefficients
  double float_model(double t) const;      // the fitted polynomial at the exact t (unquantized)

  // The budget of the header comment for the quantized coefficients, in output ulps.
  double datapath_bound_ulps() const;
  // P_q (the quantized coefficients as a real polynomial) proven non-decreasing on [0, 1].
  bool polynomial_monotone() const;
  // eval() non-decreasing over every input code (the proof of the header comment).
  bool output_monotone() const;
  // An upper bound of |P_q'| on [0, 1].
  double slope_bound() const;
  std::vector<long double> real_coefficients() const;  // c_raw 2^-fh, exactly
  bool wide() const { return wide_; }
  const UScaler& scaler() const { return scaler_; }
  const std::vector<std::int64_t>& coeff_raw() const { return c_raw_; }
  QFormat coeff_format() const { return coeff_fmt_; }
  int internal_frac() const { return fh_; }
  int acc_int_bits() const { return acc_int_; }
  const HornerCoefficients& coefficients() const { return coeffs_; }
  const HornerConfig& config() const { return cfg_; }

 private:
  template <class Probe>
  [[gnu::noinline, gnu::cold]] std::int64_t run_wide(std::int64_t t_raw, const Probe& probe) const {
    return run_as<true>(t_raw, probe);
  }
  template <bool Wide, class Probe>
  std::int64_t run_as(std::int64_t t_raw, const Probe& probe) const {
    using Wider = std::conditional_t<Wide, __int128, std::int64_t>;
    const std::int64_t u = scaler_.apply(t_raw);
    const std::size_t p = c_raw_.size() - 1;
    std::int64_t acc = c_raw_[p];
    probe(1, 0, u);
    probe(1, 1, acc);
    int position = 2;
    for (std::size_t k = p; k-- > 1; ++position) {
      if constexpr (Wide) {
        // Round half up, as round_nearest: floor((x + half) / 2^fh).
        const Wider x = static_cast<Wider>(acc) * u + (static_cast<Wider>(1) << (fh_ - 1));
        acc = static_cast<std::int64_t>(x >> fh_) + c_raw_[k];
      } else {
        // round_nearest without its range checks: |acc u| < 2^62 here (wide_ is false), so adding
        // half an LSB cannot overflow.
        acc = ((acc * u + half_) >> fh_) + c_raw_[k];
      }
      probe(position, 0, u);
      probe(position, 1, acc);
    }
    std::int64_t q;
    if constexpr (Wide) {
      const Wider y = static_cast<Wider>(acc) * u +
                      static_cast<Wider>(c_raw_[0]) * (static_cast<Wider>(1) << fh_);
      q = static_cast<std::int64_t>((y + (static_cast<Wider>(1) << (last_shift_ - 1))) >>
                                    last_shift_);
    } else {
      q = (acc * u + c0_high_) >> last_shift_;  // c0_high_: c_0 2^fh plus the rounding half
    }
    const std::int64_t r = q < 0 ? 0 : (q > one_out_ ? one_out_ : q);
    probe(position, 0, r);
    return r;
  }

  HornerConfig cfg_;
  HornerCoefficients coeffs_;
  double tau_ = 0;
  UScaler scaler_;
  std::vector<std::int64_t> c_raw_;
  std::vector<long double> c_real_;  // c_raw 2^-fh, for model()
  QFormat coeff_fmt_;
  std::int64_t one_out_ = 0;
  int fh_ = 0, last_shift_ = 0, acc_int_ = 0;
  bool wide_ = false;                    // acc * u exceeds 63 bits: form it in 128
  std::int64_t half_ = 0, c0_high_ = 0;  // 2^(fh-1); c_0 2^fh + 2^(last_shift-1)
};

}  // namespace glint
