// glint's fit of pwp's segments: src/fit's Remez exchange, which the datapath then rounds to its
// grid. Sollya's fpminimax, which searches the grid itself, replaces it per segment where the key
// fit says (fit_engine.h).
#pragma once

#include <functional>
#include <vector>

namespace glint {

// t^n on [a, b] (0 <= a < b <= 1) as a polynomial of degree 1..3 in x = (t - a) / (b - a), equal
// to t^n at both ends (so that neighbouring segments meet), minimax in between: the fit runs on
// the normalised target (t^n - a^n) / (b^n - a^n), which both ends pin to 0 and 1. Monomial
// coefficients in x, c[0] = a^n.
std::vector<double> fit_segment(double n, double a, double b, int degree);

// The same for any increasing f (domain=log: log2(1 + u) and 2^u), c[0] = f(a).
std::vector<double> fit_segment_of(const std::function<double(double)>& f, double a, double b,
                                   int degree);

}  // namespace glint
