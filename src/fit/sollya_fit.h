// Sollya (libsollya, Debian libsollya-dev) beside fit.h's own fits: a minimax fit whose
// coefficients are searched on the fixed-point grid the hardware holds them on (fpminimax,
// Brisebarre & Chevillard, ARITH 18), and a certified sup norm of the approximation error
// (supnorm, an interval enclosure).
//
// Why: fit.h's Remez fit is minimax over the reals, and the unit then rounds each coefficient to
// nearest on its grid: the rounded polynomial is close to, but not the best on, that grid. When the
// coefficients' rounding is comparable to the levelled error (high degrees, few guard bits),
// fpminimax's lattice reduction finds a better point of the grid; where the levelled error
// dominates (low degrees) both end within a hair of each other. Callers measure both and keep the
// better (units/horner/slots.cpp).
//
// Sollya's library is neither reentrant nor thread-safe: every call here holds one process-wide
// lock, and initializes the library on first use. Its messages are silenced: failures come back as
// values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fit/fit.h"

namespace glint {

// The fixed-point fit of t^n that fpminimax finds for options (domain kTau, method kMinimax; the
// constraints constrain_zero / constrain_one honoured exactly: P(0) = 0 and P(1) = 1 in u), every
// coefficient a multiple of 2^-frac_bits. start: the real minimax fit (fit_power's coefficients,
// monomial in u), from whose error extrema fpminimax takes its interpolation points (Sollya's own
// Remez does not converge on the constrained bases, which vanish at u = 0 or 1).
struct FixedPointFit {
  bool ok = false;
  std::string failure;            // why not, when !ok
  std::vector<std::int64_t> raw;  // coefficients times 2^frac_bits, c_0 first
  std::vector<double> coeffs;     // the same as doubles (exact: |raw| < 2^53)
  double milliseconds = 0.0;      // wall time of the fpminimax call
};
// points (optional): fpminimax's interpolation points in u, at least as many as free
// coefficients, instead of the ones it derives from start's error extrema (which it cannot when
// start's error does not alternate, e.g. a monotone refit's).
FixedPointFit fit_power_fixed_point(const FitOptions& options, int frac_bits,
                                    const std::vector<double>& start,
                                    const std::vector<double>* points = nullptr);

// A certified enclosure [lo, hi] of max |P(v) - t(v)^n| over v in [0, 1], P the polynomial with
// monomial coefficients c (exact: c_k = raw_k 2^-frac_bits), t(v) = tau + (1 - tau) v for kU and
// v for kT. hi is a bound (Sollya's supnorm); ok false when Sollya could not certify it (then lo
// and hi are 0).
struct CertifiedSupNorm {
  bool ok = false;
  double lo = 0.0;
  double hi = 0.0;  // rounded up to double
  double milliseconds = 0.0;
};
CertifiedSupNorm certified_sup_norm(const std::vector<std::int64_t>& raw, int frac_bits,
                                    FitVariable variable, double shininess, double tau);

// One segment of a piecewise polynomial (units/pwp): t^n on [a, b] as P(x), t = a + (b - a) x, x
// in [0, 1], whose ends are given on the grid: P(0) = end0_raw 2^-frac_bits and P(1) = end1_raw
// 2^-frac_bits exactly, so that neighbouring segments meet. fpminimax searches the free
// coefficients c_j (j = 2..degree, every one a multiple of 2^-frac_bits) of P = P(0) + (P(1) -
// P(0)) x + sum c_j (x^j - x); c_1 = end1 - end0 - sum c_j is then on the grid too. start: a real
// fit with the same ends, monomial in x (degree + 1 values), from whose error extrema fpminimax
// takes its interpolation points; points (at least degree - 1 of them, in x), when given, are
// those points (fpminimax then skips its own search for them: 0.1 ms a segment instead of 10). raw:
// c_0 .. c_degree.
FixedPointFit fit_segment_fixed_point(double shininess, double a, double b, int degree,
                                      int frac_bits, std::int64_t end0_raw, std::int64_t end1_raw,
                                      const std::vector<double>& start,
                                      const std::vector<double>& points = {});

// A certified enclosure of max |P(x) - (a + (b - a) x)^n| over x in [0, 1] (as
// certified_sup_norm, on a segment).
CertifiedSupNorm certified_segment_sup_norm(const std::vector<std::int64_t>& raw, int frac_bits,
                                            double shininess, double a, double b);

}  // namespace glint
