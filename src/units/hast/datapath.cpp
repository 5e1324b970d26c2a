#include "units/hast/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "reference/reference.h"
#include "units/keys.h"

namespace glint {

int hast_default_guard(int d) {
  const int need = 2 * d - 2;  // see the budget in hast_unit.h
  int g = 0;
  while ((1 << g) < need) ++g;
  return g + 1;
}

HastUnit::HastUnit(const HastConfig& cfg, const MaterialParams& m, const HastSlot& slot)
    : cfg_(cfg) {
  check_format(cfg.in);
  check_format(cfg.out);
  // not from a spec: the key reader takes d in 1..16 only
  if (cfg.d < 1 || cfg.d > 16) throw std::invalid_argument("hast: d must be in 1..16");
  if (cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0 || cfg.in.frac_bits < 0)
    // not from a spec: read_common_keys refuses such formats
    throw std::invalid_argument("hast: input and output formats must represent 1.0");
  const int g = cfg.guard >= 0 ? cfg.guard : hast_default_guard(cfg.d);
  cfg_.guard = g;
  fh_ = cfg.out.frac_bits + g;
  const std::string guard_value = auto_value(cfg.guard >= 0 && !cfg.guard_auto, g);
  if (2 * (fh_ + 1) > 62)
    // refusal: hast.chain
    throw std::invalid_argument(fmt::format(
        "hast: {}: the chain register (u and its powers: 1 integer bit, the output's {} "
        "fraction bits and {} guard bits) would be {} bits wide, more than 31",
        key_values({{"out", cfg.out.name()}, {"guard", guard_value}}), cfg.out.frac_bits, g,
        fh_ + 1));
  // not from a spec: the build gives every slot an order in 1..d
  if (slot.d < 1 || slot.d > cfg.d) throw std::invalid_argument("hast: slot order outside 1..d");
  d_ = slot.d;
  n_ = m.shininess;
  std::int64_t root_raw = 0;
  if (slot.from_material) {
    // The material's tau (Källberg) clamped into [0, 1), rounded as the float test's threshold.
    // An always-skipped material's root is 0 (root_threshold_raw), for Hast's f too.
    tau_ = m.always_skip ? 0.0 : std::clamp(m.tau, 0.0, 1.0);
    root_raw = root_threshold_raw(m, cfg.in);
  } else {
    if (!(slot.root >= 0.0 && slot.root < 1.0))
      // not from a spec: key root is read in [0, 1), match= solves roots in [0, 1)
      throw std::invalid_argument(fmt::format("hast: root {} outside [0, 1)", slot.root));
    // Nearest input code, kept below 1.0: a root at 1.0 would leave no highlight at all.
    tau_ = slot.root;
    root_raw = std::min<std::int64_t>(std::llround(std::ldexp(slot.root, cfg.in.frac_bits)),
                                      cfg.in.raw_one() - 1);
  }
  scaler_ =
      UScaler(cfg.in, root_raw, fh_,
              key_values({{"in", cfg.in.name()}, {"out", cfg.out.name()}, {"guard", guard_value}}),
              slot.from_material ? "the root the material's threshold (match=none)"
                                 : "the root from " + cfg.root_source);
  first_shift_ = fh_ - cfg.out.frac_bits;
  last_shift_ = 2 * fh_ - cfg.out.frac_bits;
}

double HastUnit::datapath_bound_ulps() const {
  // u's rounding times |d(u^d)/du| <= d, plus d - 2 inner products (d = 1: u's rounding alone,
  // then the final ½ ulp).
  // A slot shorter than the chain (d=auto) has one more: u^d rounded to Fh before the last
  // stage's multiply by 1.0 rounds it to Fo (datapath.h).
  const int d = d_;
  const int roundings = d < cfg_.d ? 2 * d - 1 : (d == 1 ? 1 : 2 * d - 2);
  return 0.5 + roundings * std::ldexp(1.0, -(cfg_.guard + 1));
}

double HastUnit::model(std::int64_t t_raw) const {
  // u^d by d - 1 long double products (d <= 16: relative error below 2^-59, far under any output
  // ulp), several times cheaper than powl in the contract's sweep over every input code.
  const long double u = scaler_.exact(t_raw);
  long double p = u;
  for (int i = 1; i < d_; ++i) p *= u;
  return static_cast<double>(p);
}

double HastUnit::float_model(double t) const {
  if (scaler_.root_raw() >= cfg_.in.raw_one()) return 0.0;
  if (tau_ >= 1.0) return 0.0;
  return hast(t > 1 ? 1.0 : t, tau_, d_);
}

}  // namespace glint
