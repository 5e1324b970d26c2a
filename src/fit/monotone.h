// Monotone polynomials on [0, 1]: an exact-in-spirit check, and a fit that is monotone by
// construction.
//
// Check. In the Bernstein basis of degree q on [a, b], a polynomial lies between the smallest and
// the largest of its coefficients (the basis is a partition of unity with non-negative terms), and
// de Casteljau subdivision at the midpoint makes the coefficients converge to the values. So the
// Bernstein coefficients of P and P' on the pieces of a subdivision prove, piece by piece, P' >= 0,
// P <= 0 or P >= 1; an end coefficient (a value) with P' < 0 where 0 < P < 1 refutes. What is
// checked is clamp(P, 0, 1), the function every unit computes: a minimax fit pinned to P(0) = 0
// below a target of eps/c_y dips below 0 next to u = 0, which the clamp hides.
//
// Fit. Least squares or Lawson's minimax under the linear constraints P'(v_k) >= s at points
// v_k: inequality-constrained least squares, solved as Lawson & Hanson (Solving Least Squares
// Problems, ch. 23) do, through a least-distance problem and NNLS; the result is then proven
// monotone by the check above, with more points where it is not. Last resort, the cone:
// P(v) = sum_k b_k B_{k,p}(v) with b_0 <= b_1 <= ... <= b_p is non-decreasing on [0, 1]
// (P' = p sum_k (b_{k+1} - b_k) B_{k,p-1}). Writing b_k = b_0 + d_1 + ... + d_k with d_j >= 0
// makes the monotone polynomials a cone, and the fit a non-negative least squares problem
// (Lawson-Hanson), with P(0) = b_0 = 0 and P(1) = b_p = 1 imposed exactly. Minimax by Lawson's
// reweighting: each pass multiplies every sample's weight by its |error|, which drives the
// weighted least-squares solution towards the discrete minimax one. A margin d_j >= delta makes
// P' >= p delta everywhere, enough to survive the quantization of the coefficients.
#pragma once

#include <vector>

namespace glint {

// Bernstein coefficients on [0, 1] of the polynomial with monomial coefficients c (c[0] constant),
// and back.
std::vector<double> bernstein_from_monomial(const std::vector<double>& c);
std::vector<double> monomial_from_bernstein(const std::vector<double>& b);

enum class Monotonicity { kProven, kRefuted, kUndecided };

// Is clamp(sum c_k v^k, 0, 1) non-decreasing on [0, 1]? Computed in long double with subdivision
// down to pieces of width 2^-max_depth; kUndecided where a piece can neither be proven nor refuted
// (a derivative within rounding of 0), which callers treat as not proven.
Monotonicity check_monotone(const std::vector<long double>& c, int max_depth = 24);
Monotonicity check_monotone(const std::vector<double>& c, int max_depth = 24);

// Pieces [lo, hi] of [0, 1] on which the subdivision could not show P' >= want, refined down to
// width min_width; everywhere else P' >= want holds.
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};
std::vector<Interval> slope_below(const std::vector<long double>& c, long double want,
                                  double min_width);

// An upper bound of |P'| on [0, 1]: the largest |Bernstein coefficient| of P'. Much tighter than
// sum k |c_k| for high degrees, whose monomial coefficients cancel.
double slope_bound(const std::vector<double>& c);
double slope_bound(const std::vector<long double>& c);

struct Subspace;

// A monotone polynomial fit of samples (v_i, y_i), v_i in [0, 1].
struct MonotoneFitOptions {
  int degree = 4;
  bool zero = false;       // P(0) = 0
  bool one = false;        // P(1) = 1
  bool minimax = false;    // Lawson reweighting towards the minimax fit; else least squares
  double min_slope = 0.0;  // P' >= min_slope on all of [0, 1] (< 1 when one)
  int lawson_passes = 30;
};

// The Bernstein-cone fit: monotone by construction (every step b_{k+1} - b_k >= min_slope / p),
// but the cone holds only the gentler monotone polynomials (none steeper than v^p at 1), so it is
// the last resort. Monomial coefficients in v; throws std::invalid_argument on bad options.
std::vector<double> fit_monotone_cone(const std::vector<double>& v, const std::vector<double>& y,
                                      const MonotoneFitOptions& options);

// The monotone fit: least squares (Lawson: minimax) in the constrained space of fit.cpp under
// P' >= min_slope at a set of points (Lawson & Hanson's LSI, reduced to NNLS), the points doubled
// until the exact check proves it (check_monotone, or slope_below for min_slope > 0); the cone fit
// if that fails. *cone (optional) tells which. start (optional, monomial coefficients): a fit
// whose dip below 0 at the left end and overshoot above 1 at the right end (both hidden by the
// clamp) the monotone fit may keep.
std::vector<double> fit_monotone(const std::vector<double>& v, const std::vector<double>& y,
                                 const MonotoneFitOptions& options, bool* cone = nullptr,
                                 const std::vector<double>* start = nullptr);

}  // namespace glint
