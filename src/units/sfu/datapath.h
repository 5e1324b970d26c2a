// The highlight as a Tesla-class GPU shader computes it (tesla_sfu.h): t^n = ex2(n * lg2 t), the
// SFU's two functions with the shader's FMUL and RRO.EX2 between them, bit-exact, then the fp32
// result converted to the output format.
//
// Datapath (one stage each): lg2 (t, uq1.F, converted to fp32 -- exact, F <= 23 -- then MUFU.LG2),
// fmul (FMUL by n: the n register's value in fp32, exact because the register is at most 24 bits
// wide), pre (RRO.EX2), ex2 (MUFU.EX2), to_fixed (the fp32 result to uq1.G, rounded to nearest,
// ties to even: what a shader's float-to-unorm output conversion does, D3D10 and later; the
// result never exceeds 1.0, clamped regardless). t = 0 is a short-cut to 0 (the hardware's lg2(0)
// = -inf gives 0 as well, through RRO's infinity code).
//
// Model: t_q^n_q, as pow's (the SFU's tables are how it computes t^n, not another function). Error
// budget: the SFU's lg2 and ex2 are only described by their bits (truncations, one's complements,
// a truncated squarer the tables absorb), so no closed-form bound is derived here; instead the
// bound is the exact maximum of |eval - model| over every input code of the group's n, computed
// when the datapath is built (at most 2^23 + 1 codes: ~0.1 us each).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "units/common.h"
#include "units/sfu/keys.h"
#include "units/sfu/tesla_sfu.h"
#include "units/stages.h"

namespace glint {

struct SfuConfig {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  QFormat n_format = SfuKeys::n.def;
  bool skip = CommonKeyTable::skip.def;
};

// The widest input and n register whose every value is an fp32 exactly (24 significant bits).
inline constexpr int kSfuMaxInFrac = 23;
inline constexpr int kSfuMaxNWidth = 24;

// A positive integer times 2^-frac as fp32 bits: exact when v < 2^24 (the callers' formats).
std::uint32_t sfu_to_fp32(std::int64_t v, int frac);
// A non-negative fp32 (at most 1.0) to `out`'s raw code, rounded to nearest, ties to even, at most
// 1.0.
std::int64_t sfu_to_fixed(std::uint32_t x, const QFormat& out);

class SfuUnit {
 public:
  SfuUnit(const SfuConfig& cfg, const MaterialParams& m);

  std::int64_t eval(std::int64_t t_raw) const { return run(t_raw, NoProbe{}); }
  // Stages (sfu.cpp's layout): 1 lg2, 2 fmul (and n), 3 pre, 4 ex2, 5 the result. t = 0 leaves
  // the fp32 registers alone.
  template <class Probe>
  std::int64_t run(std::int64_t t_raw, const Probe& probe) const {
    if (t_raw <= 0) {
      probe(5, 0, 0);
      return 0;
    }
    const std::int64_t t = t_raw > one_in_ ? one_in_ : t_raw;
    const std::uint32_t lg2 = tesla_sfu::lg2(sfu_to_fp32(t, cfg_.in.frac_bits));
    probe(1, 0, lg2);
    const std::uint32_t product = tesla_sfu::fmul(lg2, n_fp32_);
    probe(2, 0, n_fp32_);
    probe(2, 1, product);
    const std::uint32_t pre = tesla_sfu::pre_ex2(product);
    probe(3, 0, pre);
    const std::uint32_t ex2 = tesla_sfu::ex2(pre);
    probe(4, 0, ex2);
    const std::int64_t result = sfu_to_fixed(ex2, cfg_.out);
    probe(5, 0, result);
    return result;
  }
  double model(std::int64_t t_raw) const;
  double float_model(double t) const { return t <= 0 ? 0.0 : std::pow(std::min(t, 1.0), n_); }
  // The exact maximum of |eval - model| over every input code, in output ulps.
  double datapath_bound_ulps() const { return bound_ulps_; }
  double error_bound() const { return std::ldexp(bound_ulps_, -cfg_.out.frac_bits); }

  double shininess() const { return n_; }  // the n the register stands for
  double shininess_q() const;
  std::int64_t n_raw() const { return n_raw_; }
  std::uint32_t n_fp32() const { return n_fp32_; }
  const SfuConfig& config() const { return cfg_; }

 private:
  SfuConfig cfg_;
  double n_ = 1;
  std::int64_t n_raw_ = 1, one_in_ = 0;
  std::uint32_t n_fp32_ = 0;
  double bound_ulps_ = 0;
};

}  // namespace glint
