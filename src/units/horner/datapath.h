// Horner pipeline for a fitted polynomial (Öztürk et al. 2006, eq.12), one multiply-add per stage.
//
// The polynomial is evaluated in the unit's variable: u = t on the full domain (Öztürk's fit), or
// u = (t - tau) / (1 - tau) on [tau, 1] (our fits, u_scaler.h), with monomial coefficients in u.
// Stages: acc = c_p; acc = round(acc u) + c_k for k = p-1 .. 1; the last stage forms acc u + c_0
// exactly and rounds once to the output format; then clamp to [0, 1].
//
// Error budget (against the real-valued clamp(sum c_kq u^k, 0, 1) at the quantized t, tau, k and
// coefficients): final rounding ½ ulp_out; the p - 1 inner roundings add 2^-(fh+1) each (scaled by
// u^k <= 1); rounding u costs |P'| 2^-(fh+1) <= (sum k |c_k|) 2^-(fh+1). Faithful needs
// (p - 1 + sum k |c_k|) 2^-(fh+1) < 2^-(fo+1): horner_required_guard() picks g = fh - fo with
// 2^g >= 2 (p - 1 + sum k |c_k|), a factor-2 margin for the coefficients' own quantization. On the
// full domain u = t is exact and the derivative term is not needed for faithfulness, but
// horner_preferred_guard() keeps it where the registers allow (horner_max_guard()): the extra bits
// keep the inner error far below the model's step per input LSB, which keeps the rounded output
// monotone wherever the model is (faithful rounding alone would allow a 1-ulp step back).
#pragma once

#include <cstdint>
#include <vector>

#include "units/common.h"
#include "units/stages.h"
#include "units/u_scaler.h"

namespace glint {

struct HornerCoefficients {
  std::vector<double> c;        // monomial coefficients in u, c[0] constant
  bool tau_domain = true;       // u = (t - tau)/(1 - tau); false: u = t
  bool constrain_one = false;   // fit has P(1) = 1: keep it exact after quantization
  bool constrain_zero = false;  // fit has P(0) = 0 (at u = 0, i.e. t = tau)
};

struct HornerConfig {
  QFormat in = kDefaultIn;
  QFormat out = kDefaultOut;
  int guard = -1;  // fh - fo; -1: horner_required_guard over every slot
  bool skip = true;
};

int horner_required_guard(const HornerCoefficients& coeffs);                 // faithful minimum
int horner_preferred_guard(const HornerCoefficients& coeffs);                // + derivative term
int horner_max_guard(const HornerCoefficients& coeffs, const QFormat& out);  // 62-bit limit

class HornerUnit {
 public:
  HornerUnit(const HornerConfig& cfg, const MaterialParams& m, const HornerCoefficients& coeffs);

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (horner.cpp's layout): position 1 holds u and c_p, position k
  // (2..p) u and the accumulator after its multiply-add, position p + 1 the result.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    const std::int64_t u = scaler_.apply(t_raw);
    const std::size_t p = c_raw_.size() - 1;
    std::int64_t acc = c_raw_[p];
    probe(1, 0, u);
    probe(1, 1, acc);
    int position = 2;
    for (std::size_t k = p; k-- > 1; ++position) {
      acc = round_nearest(acc * u, fh_) + c_raw_[k];
      probe(position, 0, u);
      probe(position, 1, acc);
    }
    const std::int64_t y = acc * u + shift_left(c_raw_[0], fh_);
    const std::int64_t q = round_nearest(y, last_shift_);
    const std::int64_t r = q < 0 ? 0 : (q > one_out_ ? one_out_ : q);
    probe(position, 0, r);
    return r;
  }
  double model(std::int64_t t_raw) const;  // real-valued at quantized t, tau, k, coefficients
  double float_model(double t) const;      // the fitted polynomial at the exact t (unquantized)

  // The budget of the header comment for the quantized coefficients, in output ulps.
  double datapath_bound_ulps() const;
  const UScaler& scaler() const { return scaler_; }
  const std::vector<std::int64_t>& coeff_raw() const { return c_raw_; }
  QFormat coeff_format() const { return coeff_fmt_; }
  int internal_frac() const { return fh_; }
  int acc_int_bits() const { return acc_int_; }
  const HornerCoefficients& coefficients() const { return coeffs_; }
  const HornerConfig& config() const { return cfg_; }

 private:
  HornerConfig cfg_;
  HornerCoefficients coeffs_;
  double tau_ = 0;
  UScaler scaler_;
  std::vector<std::int64_t> c_raw_;
  QFormat coeff_fmt_;
  std::int64_t one_out_ = 0;
  int fh_ = 0, last_shift_ = 0, acc_int_ = 0;
};

}  // namespace glint
