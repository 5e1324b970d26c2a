// Hast's highlight f(rho) = kappa (rho - tau)^d, kappa = 1/(1 - tau)^d (Hast et al. 2003, eq.2),
// as a multiplier chain in the overflow-free form f = u^d, u = (rho - tau) k, k = 1/(1 - tau).
//
// Why not kappa (rho - tau)^d: as tau -> 1, kappa = (1 - tau)^-d explodes (tau = 0.99, d = 5:
// 1e10, 34 integer bits) while (rho - tau)^d shrinks below the fraction LSB (0.01^5 = 1e-10 <
// 2^-15), so the product needs ~50-bit registers or returns 0. Scaling first keeps every
// intermediate in [0, 1]: u and all its powers fit the same unsigned 1.Fh register.
//
// Datapath: the u scaler (units/u_scaler.h), then d - 1 multiplies, the last one rounding straight
// to the output format.
//
// Error budget (against the real-valued min(1, (rho_q - tau_q) k_q)^d): final rounding ½ ulp;
// rounding u costs at most d * 2^-(Fh+1) (|d(u^d)/du| <= d), each of the d - 2 inner products
// 2^-(Fh+1) (later factors are <= 1). Faithful needs (2d - 2) 2^-(Fh+1) < 2^-(Fo+1), i.e.
// 2^g > 2d - 2 with g = Fh - Fo guard bits; the default g = ceil(log2(2d - 2)) + 1 meets it.
//
// Root and order per slot (units/match.h): the root is the material's Källberg threshold
// (match=none, "as the paper does": no highlight below it, Hast §2), an explicit root (key root=,
// Hast's own tau = 0.92) or the one matching t^n (match=minimax|width). With d=auto every slot
// has its own order d_s <= D, the chain's length: stages past d_s multiply by 1.0 instead of u
// (an operand mux), which is exact, so the slot computes u^d_s with one more rounding than a chain
// of exactly d_s (u^d_s rounded to Fh, then to Fo): budget ½ + (2 d_s - 1) 2^-(g+1) ulps, still
// faithful with the guard bits of D (2^g > 2D - 2 >= 2 d_s).
#pragma once

#include <cstdint>
#include <string>

#include "units/common.h"
#include "units/hast/keys.h"
#include "units/stages.h"
#include "units/u_scaler.h"

namespace glint {

struct HastConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  int d = HastKeys::d.def;  // exponent (the chain's length D with d=auto), one multiplier per step
  int guard = HastKeys::guard.def;  // guard bits of the chain register; kAutoInt: from d (budget)
  bool skip = CommonKeyTable::skip.def;
  bool per_slot_d = false;  // d=auto: each slot has its own order <= d (operand muxes)
  // What refusals name: guard resolved from guard=auto, and the key an explicit or matched root
  // comes from ("key 'root' = '0.9'"; empty: the material's threshold).
  bool guard_auto = false;
  std::string root_source = {};
};

int hast_default_guard(int d);

// One slot's root and order. from_material: the root is the material's Källberg threshold,
// quantized as the comparator's (root_threshold_raw); otherwise `root` in [0, 1), rounded to
// the nearest input code (below 1.0, so that f(1) = 1 still holds).
struct HastSlot {
  int d = 4;
  double root = 0.0;
  bool from_material = true;
};
class HastUnit {
 public:
  HastUnit(const HastConfig& cfg, const MaterialParams& m, const HastSlot& slot);
  HastUnit(const HastConfig& cfg, const MaterialParams& m)
      : HastUnit(cfg, m, HastSlot{cfg.d, 0.0, true}) {}

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // The datapath, stage by stage (hast.cpp's layout): position 1 holds u, position k (2..d-1)
  // u and u^k, position d the result.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    const std::int64_t u = scaler_.apply(t_raw);
    if (cfg_.d == 1) {
      const std::int64_t r = round_nearest(u, first_shift_);
      probe(1, 0, r);
      return r;
    }
    probe(1, 0, u);
    std::int64_t p = u;
    if (d_ == cfg_.d) {
      for (int i = 2; i < cfg_.d; ++i) {
        p = round_nearest(p * u, fh_);
        probe(i, 0, u);
        probe(i, 1, p);
      }
      const std::int64_t r = round_nearest(p * u, last_shift_);
      probe(cfg_.d, 0, r);
      return r;
    }
    // A slot of a shorter order (d=auto): stage i multiplies by u while i <= d_s, else by 1.0.
    const std::int64_t one = std::int64_t{1} << fh_;
    for (int i = 2; i < cfg_.d; ++i) {
      p = round_nearest(p * (i <= d_ ? u : one), fh_);
      probe(i, 0, u);
      probe(i, 1, p);
    }
    const std::int64_t r = round_nearest(p * (cfg_.d <= d_ ? u : one), last_shift_);
    probe(cfg_.d, 0, r);
    return r;
  }
  double model(std::int64_t t_raw) const;  // real-valued at quantized t, tau and k
  double float_model(double t) const;      // Hast's f at exact t and tau

  // The budget of the header comment, in output ulps.
  double datapath_bound_ulps() const;
  const UScaler& scaler() const { return scaler_; }
  int internal_frac() const { return fh_; }
  const HastConfig& config() const { return cfg_; }
  int order() const { return d_; }         // this slot's d
  double root() const { return tau_; }     // its root, exact
  double shininess() const { return n_; }  // the material's n (what match= matched)

 private:
  HastConfig cfg_;
  int d_ = 4;       // the slot's order (cfg_.d unless d=auto)
  double tau_ = 0;  // Hast's root, exact (the material's tau clamped to [0, 1), or the chosen one)
  double n_ = 0;
  UScaler scaler_;
  int fh_ = 0, first_shift_ = 0, last_shift_ = 0;
};

}  // namespace glint
