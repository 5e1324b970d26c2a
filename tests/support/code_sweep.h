// A unit's slot over every input code from 0 to `last`, comparator included: what the exhaustive
// unit tests assert (the contract, monotonicity, exact 0 when skipped, exact 1.0 at t = 1).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "units/unit.h"

namespace glint::test {

struct CodeSweep {
  double max_ulps = 0;        // |eval - model| / ulp where computed
  double max_abs_vs_pow = 0;  // |eval - t_q^n| where computed (codes above 1.0 read as 1.0)
  std::int64_t first_nonmonotone = -1;
  std::int64_t at_one = -1;  // the result at t = 1.0, if `last` reaches it
  std::int64_t nonzero_skipped = 0;
};

inline CodeSweep sweep_codes(const SpecularUnit& u, std::size_t slot, double n, std::int64_t last) {
  CodeSweep s;
  const QFormat in = u.in_format(), out = u.out_format();
  std::int64_t prev = -1;
  for (std::int64_t t = 0; t <= last; ++t) {
    const std::int64_t r = u.eval_with_skip(slot, t);
    if (r < prev && s.first_nonmonotone < 0) s.first_nonmonotone = t;
    prev = r;
    if (t == in.raw_one()) s.at_one = r;
    if (u.skip(slot, t)) {
      s.nonzero_skipped += r != 0;
      continue;
    }
    const double v = std::ldexp(static_cast<double>(r), -out.frac_bits);
    const double tq = std::min(1.0, std::ldexp(static_cast<double>(t), -in.frac_bits));
    s.max_ulps = std::max(s.max_ulps, std::fabs(v - u.model(slot, t)) / out.ulp());
    s.max_abs_vs_pow = std::max(s.max_abs_vs_pow, std::fabs(v - std::pow(tq, n)));
  }
  return s;
}

}  // namespace glint::test
