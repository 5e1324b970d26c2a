// The horner datapath's monotonicity: of the quantized polynomial, and of the output itself.
//
// The output: y(t) = P_q(u_hw(t)) + e(t), |e| <= E = (p - 1) 2^-(fh+1) (the inner roundings, each
// scaled by u^k <= 1), and u_hw is non-decreasing in t (a rounded, clamped, increasing affine map).
// Between neighbouring codes with distinct u_hw, u_hw grows by at least dmin = max(2^-fh,
// k 2^-F - 2^-fh), so where P_q' >= 2E / dmin on [u_hw(t), u_hw(t+1)] the pre-rounding value y
// grows, and the final rounding and the clamp keep the order. Bernstein bounds of P_q'
// (fit/monotone.h) prove that on most of [0, 1]; the codes of the remaining pieces, and the top
// codes where u clamps to 1 (dmin does not hold there), are checked one by one, up to a budget
// (false beyond it: not proven).
#include <algorithm>
#include <cmath>

#include "fit/monotone.h"
#include "units/horner/datapath.h"

namespace glint {

bool HornerUnit::polynomial_monotone() const {
  return check_monotone(real_coefficients()) == Monotonicity::kProven;
}

bool HornerUnit::output_monotone() const {
  const std::int64_t root = scaler_.root_raw();
  const std::int64_t one = cfg_.in.raw_one();
  if (root >= one) return true;  // u = 0 on every code: a constant output
  // At most 2^20 codes one by one (a few ms): wide input formats have far more codes per piece,
  // and are proven by guard bits instead (the builder's repair).
  std::int64_t budget = std::int64_t{1} << 20;
  const auto ordered = [&](std::int64_t lo, std::int64_t hi) {
    lo = std::max(lo, root);
    hi = std::min(hi, one);
    budget -= hi - lo + 1;
    if (budget < 0) return false;
    std::int64_t prev = lo > root ? eval(lo - 1) : 0;
    for (std::int64_t t = lo; t <= hi; ++t) {
      const std::int64_t y = eval(t);
      if (y < prev) return false;
      prev = y;
    }
    return true;
  };
  const long double lsb_u = std::ldexp(1.0L, -fh_);
  const long double step = std::ldexp(static_cast<long double>(scaler_.k_raw()),
                                      -(cfg_.in.frac_bits + scaler_.k_frac()));
  const long double dmin = std::max(lsb_u, step - lsb_u);
  const long double e = static_cast<long double>(c_raw_.size() - 2) * 0.5L * lsb_u;
  const long double want = 2.0L * e / dmin * (1.0L + 1e-12L);
  // Pieces of at most 2^-10 of the u range: the one-by-one check stays a small fraction of the
  // codes above the root.
  for (const Interval& bad : slope_below(real_coefficients(), want, std::ldexp(1.0, -10))) {
    const auto code = [&](long double u) { return root + static_cast<std::int64_t>(u / step); };
    if (!ordered(code(bad.lo - 2 * lsb_u) - 1, code(bad.hi + 2 * lsb_u) + 2)) return false;
  }
  return ordered(one - 3, one);
}

}  // namespace glint
